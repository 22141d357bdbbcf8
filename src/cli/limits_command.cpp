#include "src/cli/limits_command.hpp"

#include <cstdio>
#include <cstring>
#include <vector>

#include <nlohmann/json.hpp>

#include "src/core/depth_key.hpp"
#include "src/core/error.hpp"
#include "src/core/system.hpp"
#include "src/core/timer.hpp"
#include "src/splat/splatter.hpp"

namespace lzb {

namespace {

// The best of several copies of a buffer far larger than the caches.
double memcpyRate(double seconds) {
  const size_t bytes = size_t(256) << 20;
  std::vector<char> a(bytes, 1), b(bytes, 2);
  double best = 0.0;
  Stopwatch clock;
  do {
    Stopwatch one;
    std::memcpy(b.data(), a.data(), bytes);
    best = std::max(best, double(bytes) / one.seconds());
    std::swap(a, b);
  } while (clock.seconds() < seconds);
  return best;
}

// Keys written frame after frame in order (the key buffer's clear and resolve pass), pixels/s.
double keyWriteRate(int width, int height, int threads, double seconds) {
  const long n = long(width) * long(height);
  std::vector<uint64_t> keys(static_cast<size_t>(n));
  uint64_t frames = 0;
  Stopwatch clock;
  do {
#pragma omp parallel for schedule(static) num_threads(threads)
    for (long i = 0; i < n; ++i) keys[size_t(i)] = kEmptyKey - uint64_t(frames);
    ++frames;
  } while (clock.seconds() < seconds);
  return double(frames) * double(n) / clock.seconds();
}

}  // namespace

void addLimitsOptions(CLI::App& c, LimitsArgs& a) {
  c.add_option("--width", a.width, "frame width of the scatter and key tests")->capture_default_str();
  c.add_option("--height", a.height, "frame height of the scatter and key tests")->capture_default_str();
  c.add_option("--threads,-t", a.threads, "threads (0: the cores this rank owns)")->capture_default_str();
  c.add_option("--seconds", a.seconds, "time spent on each measurement")->capture_default_str();
}

int runLimits(const LimitsArgs& a, const mpi::Group& g) {
  require(a.width >= 1 && a.width <= 16384 && a.height >= 1 && a.height <= 16384, "--width/--height",
          "must be in [1, 16384]");
  require(a.threads >= 0 && a.threads <= 1024, "--threads", "must be in [0, 1024]");
  require(a.seconds > 0.0 && a.seconds <= 60.0, "--seconds", "must be in (0, 60]");
  const int threads = a.threads > 0 ? a.threads : coresOwned();
  const nlohmann::json out = {
      {"threads", threads},
      {"width", a.width},
      {"height", a.height},
      {"memcpy_bytes_per_s", memcpyRate(a.seconds)},
      {"atomic_min_scatter_per_s", measureScatterLimit(a.width, a.height, threads, a.seconds)},
      {"key_writes_per_s", keyWriteRate(a.width, a.height, threads, a.seconds)}};
  if (g.root()) std::printf("%s\n", out.dump(2).c_str());
  return 0;
}

}  // namespace lzb
