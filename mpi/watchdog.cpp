#include "mpi/watchdog.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

namespace lzb::mpi {

StallWatchdog::StallWatchdog(int rank, double limitSeconds, bool enabled)
    : rank_(rank), fixed_(limitSeconds) {
  if (enabled) thread_ = std::thread([this] { watch(); });
}

StallWatchdog::~StallWatchdog() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void StallWatchdog::progress() {
  if (!thread_.joinable()) return;
  std::lock_guard<std::mutex> lock(mutex_);
  const double now = clock_.seconds();
  longest_ = std::max(longest_, now - last_);
  last_ = now;
  stepped_ = true;
}

double StallWatchdog::limitLocked() const {
  if (fixed_ > 0.0) return fixed_;
  return stepped_ ? std::max(kFloorSeconds, 10.0 * longest_) : 0.0;
}

void StallWatchdog::watch() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    wake_.wait_for(lock, std::chrono::milliseconds(250));
    const double limit = limitLocked(), waited = clock_.seconds() - last_;
    if (stop_ || limit <= 0.0 || waited <= limit) continue;
    std::fprintf(stderr,
                 "lzb: rank %d finished no frame for %.0f s (limit %.0f s, --stall-timeout): a "
                 "peer rank was probably lost; ending this rank\n",
                 rank_, waited, limit);
    std::fflush(stderr);
    std::_Exit(1);  // no destructors: MPI_Finalize would wait for the lost peer too
  }
}

}  // namespace lzb::mpi
