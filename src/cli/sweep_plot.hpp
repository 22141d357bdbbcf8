#pragma once
// sweep.png: median frame time (log x) against error = 1 - correct_rate_covered (median over
// frames; log y), one labelled point per combination, drawn by gnuplot.
#include <filesystem>
#include <string>
#include <vector>

#include "src/cli/sweep_table.hpp"

namespace lzb {

// Whether a `gnuplot` executable is on PATH.
bool gnuplotAvailable();

// Draws `path` (atomically) with gnuplot, a point per row labelled `labels[i]`; an error of 0
// (nothing wrong) is drawn at a floor below the least non-zero error, which the axis names.
// Throws std::runtime_error when gnuplot fails.
void plotSweep(const std::filesystem::path& path, const std::string& title,
               const std::vector<std::string>& labels, const std::vector<SweepRow>& rows);

}  // namespace lzb
