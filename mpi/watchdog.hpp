#pragma once
// A rank whose peer vanished can wait in a collective forever when the launcher does not end the
// job: mpirun ends it at once, but a launcher that keeps the other ranks (mpirun
// --enable-recovery, or a direct launch that does not kill a step on a lost task) leaves them
// blocked. The watchdog ends its own rank when the rank finished no step within its limit: it
// prints why and exits with status 1, so the launcher sees a failed rank and no rank waits forever.
#include <condition_variable>
#include <mutex>
#include <thread>

#include "src/core/timer.hpp"

namespace lzb::mpi {

class StallWatchdog {
 public:
  // Seconds the watchdog lets a step take at least when its limit is automatic.
  static constexpr double kFloorSeconds = 60.0;

  // limitSeconds > 0: no step (set-up included, counted from now) may take longer; 0: automatic,
  // from the first finished step on: 10 x the longest step so far, at least kFloorSeconds.
  // Disabled: no thread, progress() does nothing.
  StallWatchdog(int rank, double limitSeconds, bool enabled);
  ~StallWatchdog();
  StallWatchdog(const StallWatchdog&) = delete;
  StallWatchdog& operator=(const StallWatchdog&) = delete;

  void progress();  // a step (a frame) finished on this rank

 private:
  void watch();
  double limitLocked() const;  // 0: none yet

  int rank_;
  double fixed_, last_ = 0.0, longest_ = 0.0;
  bool stepped_ = false, stop_ = false;
  Stopwatch clock_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread thread_;
};

}  // namespace lzb::mpi
