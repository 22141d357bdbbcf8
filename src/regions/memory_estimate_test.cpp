// Every method has a measured memory model, and an estimate beyond the usable memory is refused
// with the scene's name and the estimate.
#include "src/regions/memory_estimate.hpp"

#include <gtest/gtest.h>

#include "src/core/error.hpp"
#include "src/core/method.hpp"
#include "src/core/system.hpp"

namespace lzb::regions {
namespace {

TEST(MemoryEstimate, EveryRegisteredMethodHasAMeasuredModel) {
  for (const auto& method : makeRegisteredMethods()) {
    EXPECT_TRUE(hasMemoryModel(method->name())) << method->name();
    EXPECT_GT(methodPeakBytes(method->name(), 2'000'000),
              methodPeakBytes(method->name(), 1'000'000))
        << method->name() << ": more triangles, more memory";
  }
}

TEST(MemoryEstimate, ThePeakIsTheBaseAndTheBytesPerTriangle) {
  // runs/distribute/memory_model.csv: raycast 126 bytes a triangle over a 73 MiB base, rounded
  // up, not by much.
  const uint64_t a = methodPeakBytes("raycast", 0), b = methodPeakBytes("raycast", 1'000'000);
  EXPECT_GE(a, uint64_t(73) << 20);
  EXPECT_GE(b - a, 126'000'000u);
  EXPECT_LE(b - a, 160'000'000u);
}

TEST(MemoryEstimate, CompactLeavesLowerTheEmbreeMethodsOnly) {
  const uint64_t n = 1'000'000;
  for (const char* method : {"raycast", "lzb", "hybrid"})
    EXPECT_LT(methodPeakBytes(method, n, true), methodPeakBytes(method, n)) << method;
  // runs/memory/README.md: raycast 67.7-72.7 bytes a triangle with compact leaves.
  EXPECT_GE(methodPeakBytes("raycast", n, true) - methodPeakBytes("raycast", 0, true), 68'000'000u);
  EXPECT_EQ(methodPeakBytes("zbuffer", n, true), methodPeakBytes("zbuffer", n));
  EXPECT_TRUE(parseCompactBvh("compact", "--bvh"));
  EXPECT_FALSE(parseCompactBvh("fast", "--bvh"));
  EXPECT_THROW(parseCompactBvh("small", "--bvh"), InputError);
}

TEST(MemoryEstimate, MoreThanTheUsableMemoryIsRefusedWithTheEstimate) {
  EXPECT_NO_THROW(requireEstimate(1, "scene.ply", "a share"));
  const uint64_t tooMuch = usableMemoryBytes() + (uint64_t(1) << 30);
  try {
    requireEstimate(tooMuch, "scene.ply", "rank 1 of 2 holding 9 triangles", ": more ranks");
    FAIL() << "not refused";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("scene.ply: rank 1 of 2 holding 9 triangles needs an estimated"),
              std::string::npos)
        << m;
    EXPECT_NE(m.find(": more ranks"), std::string::npos) << m;
  }
}

TEST(MemoryEstimate, RanksOnOneMachineShareItsMemory) {
  const uint64_t alone = usableMemoryBytes();
  setProcessesOnMachine(4);
  const uint64_t shared = usableMemoryBytes();
  setProcessesOnMachine(1);
  EXPECT_LE(shared, alone / 4 + 1);
  EXPECT_EQ(usableMemoryBytes() > shared, alone > shared);
}

}  // namespace
}  // namespace lzb::regions
