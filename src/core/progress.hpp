#pragma once
// A one-line progress display on stderr for long work (only rank 0 enables it; --quiet silences).
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>

#include "src/core/timer.hpp"

namespace lzb {

class Progress {
 public:
  Progress(std::string label, uint64_t total, bool enabled);
  ~Progress() {
    note_ = nullptr;  // it may read what its caller has already destroyed
    done();
  }
  void add(uint64_t n = 1);  // thread-safe
  // Also sets the note the line ends with (say, the median frame time so far), made only when a
  // line is printed: at most a few times a second, whatever the count.
  void add(uint64_t n, std::function<std::string()> note);
  void done();               // prints the final line once

 private:
  void print(bool final);
  std::string label_;
  std::function<std::string()> note_;
  uint64_t total_, count_ = 0;
  bool enabled_, finished_ = false;
  double lastPrint_ = -1.0;
  Stopwatch clock_;
  std::mutex mutex_;
};

}  // namespace lzb
