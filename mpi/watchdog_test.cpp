// The watchdog ends a rank that finished no step within its limit, and never one that keeps
// finishing steps.
#include "mpi/watchdog.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

namespace lzb::mpi {
namespace {

void sleepSeconds(double s) {
  std::this_thread::sleep_for(std::chrono::duration<double>(s));
}

TEST(StallWatchdogDeathTest, EndsARankThatFinishesNoStepWithinItsLimit) {
  EXPECT_EXIT(
      {
        StallWatchdog watchdog(3, 0.3, true);
        sleepSeconds(5.0);
      },
      testing::ExitedWithCode(1), "rank 3 finished no frame");
}

TEST(StallWatchdog, KeepsARankThatFinishesStepsInTime) {
  StallWatchdog watchdog(0, 1.0, true);  // a second: a loaded machine may delay a step a little
  for (int i = 0; i < 25; ++i) {
    sleepSeconds(0.1);
    watchdog.progress();
  }
  SUCCEED();  // still here after 2.5 s, over twice its limit
}

TEST(StallWatchdog, AutomaticLimitWaitsForTheFirstStep) {
  StallWatchdog watchdog(0, 0.0, true);
  sleepSeconds(0.6);  // no step yet: set-up is unbounded
  watchdog.progress();
  SUCCEED();
}

TEST(StallWatchdog, DisabledDoesNothing) {
  StallWatchdog watchdog(0, 0.01, false);
  sleepSeconds(0.3);
  SUCCEED();
}

}  // namespace
}  // namespace lzb::mpi
