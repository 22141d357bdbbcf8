#pragma once
// A one-line progress display on stderr for long work (only rank 0 enables it; --quiet silences).
#include <cstdint>
#include <mutex>
#include <string>

#include "src/core/timer.hpp"

namespace lzb {

class Progress {
 public:
  Progress(std::string label, uint64_t total, bool enabled);
  ~Progress() { done(); }
  void add(uint64_t n = 1);  // thread-safe
  // Also replaces the note the line ends with (say, the median frame time so far).
  void add(uint64_t n, std::string note);
  void done();               // prints the final line once

 private:
  void print(bool final);
  std::string label_, note_;
  uint64_t total_, count_ = 0;
  bool enabled_, finished_ = false;
  double lastPrint_ = -1.0;
  Stopwatch clock_;
  std::mutex mutex_;
};

}  // namespace lzb
