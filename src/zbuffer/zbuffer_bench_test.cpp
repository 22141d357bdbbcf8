// Throughput of the z-buffer on a random 2 M triangle soup at 640x480, run only with LZB_BENCH=1
// (they take seconds and print figures; they assert only that the frames are complete):
//   LZB_BENCH=1 build/src/zbuffer_test --gtest_filter='ZBufferBench.*'
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <numeric>
#include <random>
#include <vector>

#include "src/core/timer.hpp"
#include "src/zbuffer/triangle_rasterizer.hpp"
#include "src/zbuffer/zbuffer_renderer.hpp"
#include "tests/support/bench.hpp"

namespace lzb {
namespace {

constexpr size_t kTriangles = 2'000'000;

using test::benchEnabled;

Scene soupScene() {
  Scene scene;
  scene.addNode("soup");
  Mesh& mesh = scene.nodes[0].mesh;
  mesh.positions.reserve(3 * kTriangles);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> pos(-5.0f, 5.0f), off(-0.04f, 0.04f);
  while (mesh.size() < kTriangles) {
    const glm::vec3 c(pos(rng), pos(rng), pos(rng));
    auto corner = [&] { return c + glm::vec3(off(rng), off(rng), off(rng)); };
    mesh.add(corner(), corner(), corner(), packRgba8(uint8_t(rng()), uint8_t(rng()), 200));
  }
  scene.finalize();
  return scene;
}

TEST(ZBufferBench, TwoMillionTriangleSoupAt640x480) {
  if (!benchEnabled()) GTEST_SKIP() << "set LZB_BENCH=1";
  const Scene scene = soupScene();
  const Camera camera(frameBounds(scene.bounds()), 640, 480);
  ZBufferRenderer renderer(scene, RenderOptions{});
  Framebuffer fb(640, 480);
  constexpr int kFrames = 4;
  double drawSeconds = 0.0, frameSeconds = 0.0, upload = 0.0;
  for (int f = 0; f < kFrames; ++f) {
    FrameStats stats;
    fb.clear();
    Stopwatch clock;
    renderer.render(camera, f, {}, fb, stats);
    const double s = clock.seconds();
    ASSERT_EQ(stats.counts["triangles_drawn"].get<double>(), double(kTriangles));
    if (f == 0) {
      upload = stats.stageSeconds[0].second;
      continue;  // the first frame also uploads
    }
    frameSeconds += s;
    drawSeconds += stats.stageSeconds[1].second;
  }
  const double frames = kFrames - 1;
  std::printf(
      "[ zbuffer  ] %zu triangles, 640x480, %s: upload %.3f s, %.2f frames/s, "
      "%.2f M triangles/s drawing (%.2f M/s whole frame)\n",
      kTriangles, renderer.glDescription().c_str(), upload, frames / frameSeconds,
      double(kTriangles) * frames / drawSeconds * 1e-6,
      double(kTriangles) * frames / frameSeconds * 1e-6);
  RecordProperty("triangles_per_second", std::to_string(double(kTriangles) * frames / drawSeconds));
  EXPECT_GT(fb.coveredCount(), fb.size() / 4);
}

// drawList's cost over drawRange: the same 2 M triangles as one range, as an ascending list and
// as a shuffled list (seconds from begin() to the end of end(), best of 3 after an upload pass).
TEST(ZBufferBench, ListVersusRangeOnTwoMillionTriangles) {
  if (!benchEnabled()) GTEST_SKIP() << "set LZB_BENCH=1";
  const Scene scene = soupScene();
  const Camera camera(frameBounds(scene.bounds()), 640, 480);
  TriangleRasterizer r(scene);
  std::vector<uint32_t> ascending(kTriangles);
  std::iota(ascending.begin(), ascending.end(), 0u);
  std::vector<uint32_t> shuffled = ascending;
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(9));
  const glm::dmat4 world(1.0);
  Framebuffer fb(640, 480);
  auto best = [&](const std::function<void()>& draw) {
    double seconds = 1e30;
    for (int i = 0; i < 3; ++i) {
      Stopwatch clock;
      r.begin(camera);
      draw();
      r.end(fb);
      seconds = std::min(seconds, clock.seconds());
      EXPECT_EQ(r.counts().triangles, kTriangles);
    }
    return seconds;
  };
  r.begin(camera);
  r.drawRange(0, world, 0, kTriangles, 0);  // uploads
  r.end(fb);
  const double range = best([&] { r.drawRange(0, world, 0, kTriangles, 0); });
  const double list = best([&] { r.drawList(0, world, ascending, 0); });
  const double random = best([&] { r.drawList(0, world, shuffled, 0); });
  std::printf(
      "[ zbuffer  ] 2 M triangles, 640x480: drawRange %.3f s, drawList ascending %.3f s (x%.2f), "
      "shuffled %.3f s (x%.2f)\n",
      range, list, list / range, random, random / range);
  RecordProperty("list_over_range", std::to_string(list / range));
  EXPECT_GT(fb.coveredCount(), fb.size() / 4);
}

}  // namespace
}  // namespace lzb
