#include "src/core/progress.hpp"

#include <cstdio>

namespace lzb {

Progress::Progress(std::string label, uint64_t total, bool enabled)
    : label_(std::move(label)), total_(total), enabled_(enabled) {}

void Progress::add(uint64_t n) {
  if (!enabled_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  count_ += n;
  // At most a few lines a second, so progress never costs measurable time.
  if (clock_.seconds() - lastPrint_ >= 0.25) print(false);
}

void Progress::add(uint64_t n, std::function<std::string()> note) {
  if (!enabled_) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    note_ = std::move(note);
  }
  add(n);
}

void Progress::done() {
  if (!enabled_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (finished_) return;
  finished_ = true;
  count_ = total_;
  print(true);
}

void Progress::print(bool final) {
  lastPrint_ = clock_.seconds();
  const double pct = total_ ? 100.0 * double(count_) / double(total_) : 100.0;
  // Time left at the rate so far; padded so a shorter line covers the longer one before it.
  std::string tail = note_ ? ", " + note_() : "";
  if (!final && count_ > 0 && count_ < total_) {
    char left[48];
    std::snprintf(left, sizeof(left), ", about %.0fs left",
                  lastPrint_ / double(count_) * double(total_ - count_));
    tail += left;
  }
  std::fprintf(stderr, "\r%s: %5.1f%% (%llu/%llu) %.1fs%-40s%s", label_.c_str(), pct,
               (unsigned long long)count_, (unsigned long long)total_, lastPrint_, tail.c_str(),
               final ? "\n" : "");
  std::fflush(stderr);
}

}  // namespace lzb
