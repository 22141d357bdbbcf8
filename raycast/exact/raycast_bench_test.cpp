// Throughput measurements, run only with LZB_BENCH=1 (they take seconds and print figures):
//   LZB_BENCH=1 build/raycast/raycast_test --gtest_filter='RaycastBench.*'
// RaycastBench.LeafLayouts reads LZB_BENCH_SCENE (a scene spec) and LZB_BENCH_LAYOUTS (Embree
// device configurations separated by ';', "default" for none, "compact" for the scene flag);
// runs/memory/leaves.py sets them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "raycast/exact/raycast_renderer.hpp"
#include "src/core/system.hpp"
#include "src/scene/load.hpp"
#include "tests/support/bench.hpp"
#include "tests/support/scenes.hpp"

namespace lzb {
namespace {

using test::benchEnabled;

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
  const Scene scene = test::soupScene(2'000'000, 0.01, 1);
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

// Embree's leaf layouts on one scene, built side by side and their frames interleaved: Embree's
// bytes a triangle (held, and allocated at most while building), the median trace of a frame
// along the default circle, the pixels (over its frames) whose ID or depth differ from the first
// layout's, and the process's peak resident bytes (meaningful for one layout a process).
TEST(RaycastBench, LeafLayouts) {
  if (!benchEnabled()) GTEST_SKIP() << "set LZB_BENCH=1";
  const char* spec = std::getenv("LZB_BENCH_SCENE");
  const Scene scene = loadScene(spec && *spec ? spec : "builtin:landscape?objects=40000", true);
  const char* chosen = std::getenv("LZB_BENCH_LAYOUTS");
  std::vector<std::string> layouts;
  std::stringstream list(chosen && *chosen ? chosen : "default;tri_accel=bvh8.triangle4i");
  for (std::string item; std::getline(list, item, ';');) layouts.push_back(item);
  RenderOptions options;
  options.threads = 2;
  std::vector<std::unique_ptr<RaycastRenderer>> renderers;
  for (const std::string& config : layouts) {
    RaycastTuning tuning;
    tuning.embree.compactLeaves = config == "compact";
    tuning.embree.deviceConfig = config == "default" || config == "compact" ? "" : config;
    renderers.push_back(std::make_unique<RaycastRenderer>(scene, options, tuning));
  }
  constexpr int kFrames = 9;
  const CameraSpec base = frameBounds(scene.bounds());
  std::vector<std::vector<double>> trace(layouts.size());
  std::vector<uint64_t> otherIds(layouts.size(), 0), otherDepths(layouts.size(), 0);
  for (int f = 0; f < kFrames; ++f) {
    const Camera cam(withClipPlanes(pathCamera(scene, base, f, kFrames), scene.bounds()), 640, 480);
    Framebuffer first(cam.width(), cam.height());
    for (size_t k = 0; k < layouts.size(); ++k) {
      Framebuffer fb(cam.width(), cam.height());
      FrameStats stats;
      renderers[k]->render(cam, f, {}, fb, stats);
      for (const auto& [name, s] : stats.stageSeconds)
        if (name == "trace" && f > 0) trace[k].push_back(s);  // frame 0 pays the page faults
      if (k == 0) first = fb;
      for (size_t i = 0; i < fb.id.size(); ++i) {
        otherIds[k] += fb.id[i] != first.id[i];
        otherDepths[k] += fb.depth[i] != first.depth[i];
      }
    }
  }
  const double tris = double(scene.uniqueTriangles());
  std::printf(
      "layout,unique_triangles,embree_bytes_per_triangle,embree_peak_allocated_per_triangle,"
      "build_s,median_trace_ms,pixels_other_id,pixels_other_depth,"
      "process_peak_bytes_per_triangle\n");
  for (size_t k = 0; k < layouts.size(); ++k) {
    const EmbreeBuildStats& b = renderers[k]->embreeScene().buildStats();
    std::sort(trace[k].begin(), trace[k].end());
    std::printf("%s,%.0f,%.1f,%.1f,%.2f,%.2f,%llu,%llu,%.1f\n", layouts[k].c_str(), tris,
                double(b.bytes) / tris, double(b.peakBytes) / tris, b.seconds,
                1e3 * trace[k][trace[k].size() / 2], (unsigned long long)otherIds[k],
                (unsigned long long)otherDepths[k], double(peakMemoryBytes()) / tris);
    EXPECT_GT(b.bytes, 0u);
    EXPECT_GE(b.peakBytes, b.bytes);
  }
}

}  // namespace
}  // namespace lzb
