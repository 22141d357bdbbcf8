#pragma once
// `lzb sweep`'s results: one row per combination, summarized from its frames, and sweep.csv.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "src/image/metrics.hpp"

namespace lzb {

// What one frame of a combination gave: the FrameDriver entry's seconds and counts, and the
// accuracy against the frame's reference.
struct FrameMeasure {
  double seconds = 0.0;
  nlohmann::json counts;
  Accuracy accuracy;
};

struct SweepRow {
  std::vector<std::string> values;  // one per swept parameter
  int frames = 0;
  double setupSeconds = 0.0;
  double medianFrameSeconds = 0.0;  // frames after the first (the only one when there is one)
  double correctMin = 0.0, correctMedian = 0.0;  // correct_rate_covered over all frames
  double exactIdMedian = 0.0;                    // exact_id_rate_covered, median over frames
  double psnrAaMedian = 0.0;                     // +inf when the colours are identical
  std::map<std::string, double> counts;  // the report's numeric counts, median over the timed frames
};

SweepRow summarize(std::vector<std::string> values, double setupSeconds,
                   const std::vector<FrameMeasure>& frames);

// sweep.csv: "# <command line>", a header (the parameter names, frames, setup_s,
// median_frame_s, correct_rate_covered_min, correct_rate_covered_median,
// exact_id_rate_covered_median, psnr_aa_median, then every count any row has) and one line per
// row; written atomically.
void writeSweepCsv(const std::filesystem::path& path, const std::string& commandLine,
                   const std::vector<std::string>& names, const std::vector<SweepRow>& rows);

}  // namespace lzb
