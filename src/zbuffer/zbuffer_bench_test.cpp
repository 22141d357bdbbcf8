// Throughput of the z-buffer on a random 2 M triangle soup at 640x480 (a regular test, so the
// figure is printed on every run; it asserts only that the frame is complete and plausible).
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "src/core/timer.hpp"
#include "src/zbuffer/zbuffer_renderer.hpp"

namespace lzb {
namespace {

TEST(ZBufferBench, TwoMillionTriangleSoupAt640x480) {
  constexpr size_t kTriangles = 2'000'000;
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

}  // namespace
}  // namespace lzb
