// Throughput measurements, run only with LZB_BENCH=1 (they take seconds and print figures):
//   LZB_BENCH=1 build/raycast/raycast_test --gtest_filter='RaycastBench.*'
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <random>

#include <gtest/gtest.h>

#include "raycast/exact/raycast_renderer.hpp"
#include "src/core/system.hpp"
#include "tests/support/scenes.hpp"

namespace lzb {
namespace {

bool benchEnabled() {
  const char* v = std::getenv("LZB_BENCH");
  return v && *v && *v != '0';
}

// Best frame of several: other processes may share the cores, so the minimum is the estimate.
struct Timing {
  double build = 0, trace = 1e30, rays = 0;
  size_t covered = 0;
};

Timing run(const Scene& scene, const Camera& cam, int threads, const RaycastTuning& tuning,
           int frames) {
  RenderOptions options;
  options.threads = threads;
  RaycastRenderer r(scene, options, tuning);
  Timing t;
  t.build = r.embreeScene().buildStats().seconds;
  for (int f = 0; f < frames; ++f) {
    Framebuffer fb(cam.width(), cam.height());
    FrameStats stats;
    r.render(cam, f, {}, fb, stats);
    for (const auto& [name, s] : stats.stageSeconds)
      if (name == "trace") t.trace = std::min(t.trace, s);
    t.rays = stats.counts.value("rays", 0.0);
    t.covered = fb.coveredCount();
  }
  return t;
}

void report(const char* what, const Timing& t) {
  std::printf("%-42s build %6.3f s  trace %6.4f s/frame  %5.2f Mrays/s  covered %zu\n", what,
              t.build, t.trace, t.rays / t.trace * 1e-6, t.covered);
}

TEST(RaycastBench, TriangleSoup2M) {
  if (!benchEnabled()) GTEST_SKIP() << "set LZB_BENCH=1";
  Scene scene;
  scene.addNode("soup");
  std::mt19937_64 rng(1);
  test::addRandomTriangles(scene.nodes[0].mesh, 2'000'000, 0.01, rng);
  scene.finalize();
  CameraSpec spec = frameBounds(scene.bounds());
  spec.position = spec.lookAt + 0.45 * (spec.position - spec.lookAt);  // the soup fills the view
  spec.nearPlane = 0.01;
  const Camera cam(spec, 640, 480);
  for (bool high : {true, false})
    for (bool packets : {true, false}) {
      RaycastTuning tuning;
      tuning.packets = packets;
      tuning.embree.highQuality = high;
      char label[128];
      std::snprintf(label, sizeof label, "soup 2M, 2 threads, %s, %s", high ? "HIGH" : "MEDIUM",
                    packets ? "packets" : "rtcIntersect1");
      const Timing t = run(scene, cam, 2, tuning, 8);
      report(label, t);
      EXPECT_GT(t.covered, 640u * 480u * 9 / 10);
    }
  std::printf("peak memory %.0f MiB\n", double(peakMemoryBytes()) / (1 << 20));
}

// A 256 x 256 chessboard block (131072 triangles) under `levels` nested 2 x 2 instance levels.
Scene chessboard(int levels) {
  Scene scene;
  const uint32_t block = scene.addNode("block");
  Mesh& mesh = scene.nodes[block].mesh;
  for (int j = 0; j < 256; ++j)
    for (int i = 0; i < 256; ++i) {
      const Rgba8 c = (i + j) % 2 ? packRgba8(230, 230, 230, 255) : packRgba8(30, 30, 30, 255);
      const glm::vec3 a(i, 0, j), b(i + 1, 0, j), d(i + 1, 0, j + 1), e(i, 0, j + 1);
      mesh.add(a, e, d, c);
      mesh.add(a, d, b, c);
    }
  uint32_t below = block;
  double side = 256.0;
  for (int l = 0; l < levels; ++l) {
    const uint32_t n = scene.addNode("level " + std::to_string(l + 1));
    for (int k = 0; k < 4; ++k) {
      const glm::dvec3 t((k & 1) * side, 0.0, (k >> 1) * side);
      scene.nodes[n].instances.push_back({below, glm::translate(glm::dmat4(1.0), t)});
    }
    below = n;
    side *= 2.0;
  }
  scene.root = below;
  scene.finalize();
  return scene;
}

TEST(RaycastBench, InstancedChessboard1e12) {
  if (!benchEnabled()) GTEST_SKIP() << "set LZB_BENCH=1";
  const Scene scene = chessboard(12);
  ASSERT_GE(scene.expandedTriangles(), uint64_t(1e12));
  const double side = 256.0 * 4096.0;
  CameraSpec spec;
  spec.position = {0.3 * side, 2000.0, 0.05 * side};
  spec.lookAt = {0.5 * side, 0.0, 0.3 * side};
  spec.nearPlane = 1.0;
  spec.farPlane = 2.0 * side;
  const Camera cam(spec, 640, 480);
  std::printf("chessboard: %.3g expanded triangles, %llu unique\n",
              double(scene.expandedTriangles()), (unsigned long long)scene.uniqueTriangles());
  for (bool packets : {true, false}) {
    RaycastTuning tuning;
    tuning.packets = packets;
    const Timing t = run(scene, cam, 2, tuning, 8);
    report(packets ? "chessboard 2.2e12, 2 threads, packets"
                   : "chessboard 2.2e12, 2 threads, rtcIntersect1",
           t);
    EXPECT_GT(t.covered, 640u * 480u / 2);
  }
  std::printf("peak memory %.0f MiB\n", double(peakMemoryBytes()) / (1 << 20));
}

}  // namespace
}  // namespace lzb
