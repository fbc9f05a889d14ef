// interactive_page.hpp — the pieces every interactive page vobench writes shares (report.html and
// `vobench plot --out FILE.html`): a Content-Security-Policy that lets the page fetch nothing at all
// (no network, no file: every byte is inline), the data island, plotly.js and report_app.js
// (report/report_assets.hpp). The page works offline by construction, not by convention.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace vobench {

// <meta> CSP and the listener that counts its violations into body[data-csp-violations]; goes first
// in <head>.
std::string page_head_security();

// The data as JSON inside <script type="application/json" id="vobench-data"> (with <, > and & as
// \u escapes, so no string in it can end the element), then plotly.js and report_app.js. Goes
// last in <body>. `data`: {"kind": "report" | "plot", "views": [...]} (report/trajectory_view.hpp).
std::string interactive_scripts(const nlohmann::json& data);

// The styles of the explorer's panels.
const char* explorer_style();

// `vobench plot --out FILE.html`: one page with the explorer on `view` (trajectories_view()).
void write_trajectory_page(const nlohmann::json& view, const std::string& title, const std::filesystem::path& out);

}  // namespace vobench
