#include "src/cli/sweep_plot.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "src/core/atomic_file.hpp"

namespace lzb {

namespace {

// gnuplot's single-quoted strings end at a quote; labels and titles never need one.
std::string unquoted(std::string s) {
  std::replace(s.begin(), s.end(), '\'', '`');
  std::replace(s.begin(), s.end(), '"', '`');
  return s;
}

// Where error 0 is drawn on the log axis: a tenth of the least non-zero error, else 1e-6.
double errorFloor(const std::vector<SweepRow>& rows) {
  double least = 1e-5;
  for (const SweepRow& r : rows)
    if (1.0 - r.correctMedian > 0.0) least = std::min(least, 1.0 - r.correctMedian);
  return least / 10.0;
}

std::string script(const std::filesystem::path& out, const std::string& title,
                   const std::vector<std::string>& labels, const std::vector<SweepRow>& rows) {
  const double atZero = errorFloor(rows);
  char floorText[32];
  std::snprintf(floorText, sizeof floorText, "%.1e", atZero);
  std::string s = "set terminal pngcairo size 1100,750 noenhanced\n";
  s += "set output '" + unquoted(out.string()) + "'\n";
  s += "set title '" + unquoted(title) + "'\n";
  s += "set logscale xy\nset grid\nset key off\nset offsets graph 0.05, graph 0.2, graph 0.1, graph 0.1\n";
  s += "set xlabel 'median frame time (s, frames after the first; log)'\n";
  s += "set ylabel 'error = 1 - correct_rate_covered (median over frames; log; 0 drawn at " +
       std::string(floorText) + ")'\n";
  s += "$points << EOD\n";
  for (size_t i = 0; i < rows.size(); ++i) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g %.9g", rows[i].medianFrameSeconds,
                  std::max(1.0 - rows[i].correctMedian, atZero));
    s += std::string(buf) + " \"" + unquoted(labels[i]) + "\"\n";
  }
  s += "EOD\n";
  s += "plot $points using 1:2 with points pt 7 ps 1.2, '' using 1:2:3 with labels left offset 0.8,0.4\n";
  return s;
}

}  // namespace

bool gnuplotAvailable() {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "";
  for (size_t start = 0, end; start <= dirs.size(); start = end + 1) {
    end = dirs.find(':', start);
    if (end == std::string::npos) end = dirs.size();
    const std::string dir = dirs.substr(start, end - start);
    if (!dir.empty() && ::access((dir + "/gnuplot").c_str(), X_OK) == 0) return true;
  }
  return false;
}

void plotSweep(const std::filesystem::path& path, const std::string& title,
               const std::vector<std::string>& labels, const std::vector<SweepRow>& rows) {
  writeAtomically(path, [&](const std::filesystem::path& tmp) {
    FILE* gnuplot = ::popen("gnuplot", "w");
    if (!gnuplot) throw std::runtime_error("sweep.png: cannot start gnuplot");
    const std::string text = script(tmp, title, labels, rows);
    std::fwrite(text.data(), 1, text.size(), gnuplot);
    const int status = ::pclose(gnuplot);
    if (status != 0)
      throw std::runtime_error("sweep.png: gnuplot failed (status " + std::to_string(status) + ")");
  });
}

}  // namespace lzb
