// gnuplot.hpp — drawing a figure with gnuplot: one script that writes PNG, SVG and PDF from one plot
// body, the data beside it, and gnuplot run in the figure's folder (looked up on PATH; a missing
// gnuplot leaves data and script, and the caller says so). Shared by the report's figures and
// `vobench plot`.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

namespace vobench::gnuplot {

// The script for <stem>.{png,svg,pdf}: `setup` once, then `plot` per terminal. Sizes in pixels (the
// PDF at 100 px an inch). `noenhanced`: names with _ or ^ print as written.
std::string script(const std::string& stem, const std::string& setup, const std::string& plot, int width, int height);

bool available();

// Okabe & Ito's colour-blind-safe palette (2008), black left out (it marks references): the colour of
// the k-th line or bar is colour(k).
const char* colour(std::size_t k);

// Runs `gnuplot <stem>.gp` in `folder`; true when it succeeded and wrote <stem>.png. On failure its
// output stays in <stem>.log and a warning names it.
bool run(const std::filesystem::path& folder, const std::string& stem);

// A label in a gnuplot data file: double-quoted; gnuplot reads no escapes there, so a quote in the
// name becomes an apostrophe, and control characters are cleaned.
std::string data_label(const std::string& text);

}  // namespace vobench::gnuplot
