// LZB's stages against the ray caster and against simple limits of the machine, measured in one
// process on the same frames; run only with LZB_BENCH=1 (it takes a minute and prints figures):
//   LZB_BENCH=1 build/raycast/raycast_test --gtest_filter='LzbBench.*'
// The paper's experiment by default: builtin:city?blocks=12, 512 x 512, the 80 frames of the
// default circle, 2 threads. LZB_BENCH_SCENE, LZB_BENCH_WIDTH, LZB_BENCH_HEIGHT, LZB_BENCH_FRAMES,
// LZB_BENCH_ROUNDS (3), LZB_BENCH_THREADS and LZB_BENCH_RAYS (embree | walk) change it.
//
// Each round renders every frame with lzb, then with raycast (alternating, so both see the same
// load), each followed by the root's shading as in `lzb render`; per frame the median over the
// rounds is kept, and the table gives medians over the frames. Limits, measured on the same
// frames in the same rounds:
//   rays       Embree's rate in the raycast frames (rays per second, 262 K coherent rays a frame);
//   boxes      frustum tests of the culled leaves' content boxes in a flat loop (boxes per second);
//   fill       clearing the framebuffer's depth and ID (pixels written per second);
//   scan       reading every pixel's ID (pixels read per second: the unfinished mask's input).
// Each stage's rate is its work over its seconds, beside the limit that bounds it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "raycast/exact/raycast_renderer.hpp"
#include "raycast/lzb/lzb_renderer.hpp"
#include "src/core/shading.hpp"
#include "src/core/statistics.hpp"
#include "src/core/timer.hpp"
#include "src/image/metrics.hpp"
#include "src/scene/load.hpp"
#include "src/zbuffer/zbuffer_renderer.hpp"
#include "tests/support/bench.hpp"
#include "tests/support/cameras.hpp"
#include "tests/support/options.hpp"

namespace lzb::localz {
namespace {

using test::benchEnabled;
using test::envInt;
using test::envString;

// Per frame, per figure: the values of every round.
using Samples = std::vector<std::map<std::string, std::vector<double>>>;

// Median over frames of each frame's median over rounds.
double frameMedian(const Samples& s, const std::string& key) {
  std::vector<double> perFrame;
  for (const auto& frame : s) {
    const auto it = frame.find(key);
    perFrame.push_back(it == frame.end() ? 0.0 : median(it->second));
  }
  return median(perFrame);
}

// Seconds of the flat loop that tests the culled leaves' content boxes against the frustum.
double boxTestSeconds(const LzbRenderer& r, const Camera& cam, uint64_t& boxes) {
  const CulledScene& culled = r.culled();
  const Frustum world = cam.frustum();
  std::vector<Frustum> local;
  for (const CullPath& p : culled.paths) local.push_back(frustumToNodeSpace(world, p.world));
  Stopwatch clock;
  uint64_t inside = 0;
  for (const CullLeaf& l : culled.leaves)
    inside += local[l.path].classify(
                  r.accel().node(culled.paths[l.path].node).contentBox(l.leaf)) == Cull::kInside;
  const double seconds = clock.seconds();
  boxes = culled.leaves.size();
  EXPECT_LE(inside, boxes);  // keeps the loop
  return seconds;
}

TEST(LzbBench, StagesAgainstRaycastAndLimits) {
  if (!benchEnabled()) GTEST_SKIP() << "set LZB_BENCH=1";
  const std::string source = envString("LZB_BENCH_SCENE", "builtin:city?blocks=12");
  const int width = envInt("LZB_BENCH_WIDTH", 512), height = envInt("LZB_BENCH_HEIGHT", 512);
  const int frames = envInt("LZB_BENCH_FRAMES", 80), rounds = envInt("LZB_BENCH_ROUNDS", 3);
  const int threads = envInt("LZB_BENCH_THREADS", 2);
  const Scene scene = loadScene(source, true);
  LzbOptions options;
  options.farRays = parseFarRays(envString("LZB_BENCH_RAYS", "embree"), "LZB_BENCH_RAYS");
  LzbRenderer lzb(scene, test::renderOptions("lzb", threads), options);
  RaycastRenderer raycast(scene, test::renderOptions("lzb", threads));
  Framebuffer a(width, height), b(width, height);
  Samples s{size_t(frames)};
  for (int round = 0; round < rounds; ++round)
    for (int f = 0; f < frames; ++f) {
      const Camera cam = test::pathFrame(scene, f, frames, width, height);
      auto& out = s[size_t(f)];
      FrameStats ls, rs;
      Stopwatch clock;
      a.clear();
      lzb.render(cam, f, {}, a, ls);
      shadeFromIds(scene, cam, a);
      out["lzb"].push_back(clock.lap());
      b.clear();
      raycast.render(cam, f, {}, b, rs);
      shadeFromIds(scene, cam, b);
      out["raycast"].push_back(clock.lap());
      for (const auto& [name, seconds] : ls.stageSeconds) out[name].push_back(seconds);
      for (const auto& [name, seconds] : rs.stageSeconds) out["rc_" + name].push_back(seconds);
      for (const auto* counts : {&ls.counts, &ls.shared, &rs.counts})
        for (auto it = counts->begin(); it != counts->end(); ++it)
          if (it.value().is_number()) out[it.key()].push_back(it.value().get<double>());
      out["ratio"].push_back(out["raycast"].back() / out["lzb"].back());
      // The limits, on this frame's data.
      uint64_t boxes = 0;
      out["box_seconds"].push_back(boxTestSeconds(lzb, cam, boxes));
      out["boxes"].push_back(double(boxes));
      clock.lap();
      b.clear();
      out["fill_seconds"].push_back(clock.lap());
      uint64_t covered = 0;
      for (uint64_t id : a.id) covered += id != kNoId;
      out["scan_seconds"].push_back(clock.lap());
      out["covered"].push_back(double(covered));
    }
  const double pixels = double(width) * double(height);
  auto m = [&](const std::string& key) { return frameMedian(s, key); };
  auto rate = [&](const std::string& work, const std::string& stage) {
    const double t = m(stage);
    return t > 0.0 ? m(work) / t : 0.0;
  };
  std::printf("%s %dx%d, %d frames x %d rounds, %d threads, --lzb-rays %s (medians per frame)\n",
              source.c_str(), width, height, frames, rounds, threads,
              toString(options.farRays).c_str());
  std::printf("frame: lzb %.3f ms, raycast %.3f ms, raycast/lzb %.2fx (median of per-frame ratios "
              "%.2fx)\n",
              1e3 * m("lzb"), 1e3 * m("raycast"), m("raycast") / m("lzb"), m("ratio"));
  const double rayLimit = pixels / m("rc_trace");
  const double boxLimit = m("boxes") / std::max(m("box_seconds"), 1e-9);
  const double fillLimit = pixels / m("fill_seconds"), scanLimit = pixels / m("scan_seconds");
  std::printf("%-12s %9s  %-44s %s\n", "stage", "ms", "rate", "limit");
  std::printf("%-12s %9.3f  %8.2f M culled leaves/s %19s %8.2f M box tests/s\n", "cull",
              1e3 * m("cull"), 1e-6 * rate("culled_leaves", "cull"), "", 1e-6 * boxLimit);
  std::printf("%-12s %9.3f  %8.2f M coarse rays/s %21s %8.2f M rays/s (raycast)\n", "plane",
              1e3 * m("plane"), 1e-6 * rate("coarse_rays", "plane"), "", 1e-6 * rayLimit);
  std::printf("%-12s %9.3f  %8.2f M near triangles/s, %6.1f M px/s %4s %8.1f M px/s (fill)\n",
              "near", 1e3 * m("near"), 1e-6 * rate("near_triangles", "near"),
              1e-6 * (pixels - m("unfinished_pixels")) / std::max(m("near"), 1e-9), "",
              1e-6 * fillLimit);
  std::printf("%-12s %9.3f  %8.1f M px/s %31s %8.1f M px/s (scan)\n", "unfinished",
              1e3 * m("unfinished"), 1e-6 * pixels / std::max(m("unfinished"), 1e-9), "",
              1e-6 * scanLimit);
  std::printf("%-12s %9.3f  %8.2f M objects/s\n", "oor_project", 1e3 * m("oor_project"),
              1e-6 * rate("oor_objects", "oor_project"));
  std::printf("%-12s %9.3f  %8.2f M rays/s (%.0f rays) %17s %8.2f M rays/s (raycast)\n",
              "pvl_find", 1e3 * m("pvl_find"), 1e-6 * rate("rays_cast", "pvl_find"),
              m("rays_cast"), "", 1e-6 * rayLimit);
  std::printf("%-12s %9.3f  %8.2f M PVL triangles/s (%.0f, %.0f set up) %3s %8.1f M px/s (fill)\n",
              "pvl_render", 1e3 * m("pvl_render"), 1e-6 * rate("pvl_size", "pvl_render"),
              m("pvl_size"), m("pvl_raster_triangles"), "", 1e-6 * fillLimit);
  EXPECT_GT(m("rays_cast"), 0.0);
}

}  // namespace
}  // namespace lzb::localz
