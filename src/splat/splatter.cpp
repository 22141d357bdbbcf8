#include "src/splat/splatter.hpp"

#include "src/core/error.hpp"
#include "src/core/philox_stream.hpp"
#include "src/core/timer.hpp"

namespace lzb {

void validateSplat(int splat, const std::string& field) {
  require(splat >= 1 && splat <= kMaxSplat, field,
          "must be in [1, " + std::to_string(kMaxSplat) + "], got " + std::to_string(splat));
}

SplatSetup SplatSetup::from(const Camera& camera, int splat) {
  SplatSetup s;
  s.width = camera.width();
  s.height = camera.height();
  s.pixelScale = camera.pixelsPerUnitAt(1.0);
  s.nearPlane = camera.nearPlane();
  s.farPlane = camera.farPlane();
  s.splat = splat;
  return s;
}

double measureScatterLimit(int width, int height, int threads, double seconds) {
  const uint64_t pixels = uint64_t(width) * uint64_t(height);
  std::vector<uint64_t> buffer(pixels, kEmptyKey);
  constexpr long kBatch = 1 << 22;
  uint64_t done = 0;
  Stopwatch clock;
  uint64_t round = 0;
  do {
    const uint64_t base = round++ * uint64_t(kBatch);
#pragma omp parallel for schedule(static) num_threads(threads)
    for (long i = 0; i < kBatch; ++i) {
      const uint64_t x = mix64(base + uint64_t(i));
      atomicMinKey(buffer.data() + (x >> 32) % pixels, mix64(x) >> 1);
    }
    done += kBatch;
  } while (clock.seconds() < seconds);
  return double(done) / clock.seconds();
}

}  // namespace lzb
