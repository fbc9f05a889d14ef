// report_assets.hpp — the JavaScript the interactive pages embed, compiled into the binary:
// plotly.js (npm plotly.js-gl3d-dist-min, pinned by version and SHA-512 in harness/CMakeLists.txt,
// fetched at configure time by cmake/NpmAsset.cmake, MIT licence, its notice kept at its head) and
// vobench's own report_app.js. Nothing is read at run time, so a report is the same wherever
// vobench is installed and never needs the network.
#pragma once

#include <string_view>

namespace vobench {

std::string_view plotly_js();
std::string_view plotly_version();  // e.g. "plotly.js-gl3d-dist-min 4.1.1"
std::string_view report_app_js();

}  // namespace vobench
