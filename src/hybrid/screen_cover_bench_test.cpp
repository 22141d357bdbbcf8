// What the screen cover saves, measured in one process on the same frames; run only with
// LZB_BENCH=1 (about a minute; runs/peers/screen_cover.py keeps its table):
//   LZB_BENCH=1 build/src/hybrid/hybrid_test --gtest_filter='ScreenCoverBench.*'
// Per frame of the city's circle (LZB_BENCH_SCENE, default builtin:city, 1920 x 1080, 11
// frames) and per thread count (1 and 2): castEveryPixel without a cover and the walk plus the
// cast with it, alternating, LZB_BENCH_ROUNDS times (5); medians. The two images must match.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "src/core/statistics.hpp"
#include "src/core/timer.hpp"
#include "src/hybrid/screen_cover.hpp"
#include "src/scene/load.hpp"
#include "tests/support/bench.hpp"
#include "tests/support/cameras.hpp"

namespace lzb {
namespace {

TEST(ScreenCoverBench, CastWithAndWithoutTheCover) {
  if (!test::benchEnabled()) GTEST_SKIP() << "set LZB_BENCH=1";
  const std::string spec = test::envString("LZB_BENCH_SCENE", "builtin:city");
  const int width = test::envInt("LZB_BENCH_WIDTH", 1920);
  const int height = test::envInt("LZB_BENCH_HEIGHT", 1080);
  const int frames = test::envInt("LZB_BENCH_FRAMES", 11);
  const int rounds = test::envInt("LZB_BENCH_ROUNDS", 5);
  const Scene scene = loadScene(spec, true);
  const localz::LzbAccel accel(scene, {});
  EmbreeSceneOptions eo;
  eo.threads = 2;
  const EmbreeScene embree(scene, eo);
  std::printf("scene,width,height,frame,threads,castable_rays,cover_rays,walk_ms,cast_ms,"
              "cover_cast_ms,speedup\n");
  for (int f = 0; f < frames; ++f) {
    const Camera cam = test::pathFrame(scene, f, frames, width, height);
    for (int threads : {1, 2}) {
      std::vector<double> plain, walk, covered;
      uint64_t rays = 0, coverRays = 0;
      bool walked = true;
      for (int r = 0; r < rounds; ++r) {
        std::vector<uint8_t> touched;
        Framebuffer a(width, height), b(width, height);
        Stopwatch clock;
        rays = castEveryPixel(embree, cam, WorkShare{}, a, touched, threads);
        plain.push_back(clock.lap());
        const std::optional<BlockCover> cover = hybrid::screenCover(accel, cam, 1u << 22);
        walk.push_back(clock.lap());
        walked = cover.has_value();
        coverRays = castEveryPixel(embree, cam, WorkShare{}, b, touched, threads, true,
                                   cover ? &*cover : nullptr);
        covered.push_back(clock.lap() + walk.back());
        ASSERT_EQ(a.id, b.id) << f;
        ASSERT_EQ(a.depth, b.depth) << f;
      }
      const double p = median(plain), w = median(walk), c = median(covered);
      std::printf("%s,%d,%d,%d,%d,%llu,%lld,%.3f,%.3f,%.3f,%.3f\n", spec.c_str(), width, height, f,
                  threads, (unsigned long long)rays, walked ? (long long)coverRays : -1LL,
                  w * 1e3, p * 1e3, c * 1e3, p / c);
    }
  }
}

}  // namespace
}  // namespace lzb
