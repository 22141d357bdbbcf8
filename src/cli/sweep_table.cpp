#include "src/cli/sweep_table.hpp"

#include <algorithm>
#include <cstdio>
#include <set>

#include "src/core/atomic_file.hpp"
#include "src/core/statistics.hpp"

namespace lzb {

namespace {

const std::vector<std::string> kColumns = {
    "frames", "setup_s", "median_frame_s", "correct_rate_covered_min", "correct_rate_covered_median",
    "exact_id_rate_covered_median", "psnr_aa_median"};

template <class F>
std::vector<double> series(const std::vector<FrameMeasure>& frames, size_t first, F value) {
  std::vector<double> v;
  for (size_t i = first; i < frames.size(); ++i) v.push_back(value(frames[i]));
  return v;
}

// Numeric counts (histograms and labels are left out: one CSV field holds one number).
std::map<std::string, double> countMedians(const std::vector<FrameMeasure>& frames, size_t first) {
  std::map<std::string, std::vector<double>> all;
  for (size_t i = first; i < frames.size(); ++i)
    for (const auto& [key, value] : frames[i].counts.items())
      if (value.is_number()) all[key].push_back(value.get<double>());
  std::map<std::string, double> medians;
  for (const auto& [key, values] : all) medians[key] = median(values);
  return medians;
}

// A field: numbers in full (%.9g; inf for an infinite PSNR), text quoted when it needs it.
std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

std::string text(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string line(const std::vector<std::string>& fields) {
  std::string s;
  for (size_t i = 0; i < fields.size(); ++i) s += (i ? "," : "") + fields[i];
  return s + "\n";
}

}  // namespace

SweepRow summarize(std::vector<std::string> values, double setupSeconds,
                   const std::vector<FrameMeasure>& frames) {
  SweepRow r;
  r.values = std::move(values);
  r.frames = int(frames.size());
  r.setupSeconds = setupSeconds;
  // The first frame pays for lazy builds and cold caches: timed frames start at the second.
  const size_t timed = frames.size() > 1 ? 1 : 0;
  r.medianFrameSeconds = median(series(frames, timed, [](const FrameMeasure& f) { return f.seconds; }));
  const auto correct = series(frames, 0, [](const FrameMeasure& f) { return f.accuracy.correctRateCovered; });
  r.correctMin = correct.empty() ? 0.0 : *std::min_element(correct.begin(), correct.end());
  r.correctMedian = median(correct);
  r.exactIdMedian = median(series(frames, 0, [](const FrameMeasure& f) { return f.accuracy.exactIdRateCovered; }));
  r.psnrAaMedian = median(series(frames, 0, [](const FrameMeasure& f) { return f.accuracy.psnrAa; }));
  r.counts = countMedians(frames, timed);
  return r;
}

void writeSweepCsv(const std::filesystem::path& path, const std::string& commandLine,
                   const std::vector<std::string>& names, const std::vector<SweepRow>& rows) {
  std::set<std::string> countKeys;
  for (const SweepRow& r : rows)
    for (const auto& [key, value] : r.counts) countKeys.insert(key);
  std::vector<std::string> header = names;
  header.insert(header.end(), kColumns.begin(), kColumns.end());
  for (const std::string& key : countKeys)  // a count named like a column gets a prefix
    header.push_back(std::count(header.begin(), header.end(), key) ? "count_" + key : key);
  std::string csv = "# " + commandLine + "\n" + line(header);
  for (const SweepRow& r : rows) {
    std::vector<std::string> fields;
    for (const std::string& v : r.values) fields.push_back(text(v));
    for (double v : {double(r.frames), r.setupSeconds, r.medianFrameSeconds, r.correctMin,
                     r.correctMedian, r.exactIdMedian, r.psnrAaMedian})
      fields.push_back(number(v));
    for (const std::string& key : countKeys) {
      const auto it = r.counts.find(key);
      fields.push_back(it == r.counts.end() ? "" : number(it->second));
    }
    csv += line(fields);
  }
  writeTextAtomically(path, csv);
}

}  // namespace lzb
