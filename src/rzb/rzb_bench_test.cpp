// Benchmarks run by runs/rzb/run.py, only with LZB_BENCH=1 (skipped in ctest), e.g.
//   LZB_BENCH=1 RZB_BENCH_SCENE=builtin:city build/src/rzb_test --gtest_filter='RzbBench.Table1'
// Each prints one JSON line starting with "BENCH ".
#include <gtest/gtest.h>

#include <time.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <map>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "src/core/system.hpp"
#include "src/core/timer.hpp"
#include "src/image/metrics.hpp"
#include "src/rzb/box_sampler.hpp"
#include "src/rzb/rzb_renderer.hpp"
#include "src/scene/load.hpp"
#include "src/zbuffer/zbuffer_renderer.hpp"
#include "tests/support/cameras.hpp"
#include "tests/support/meshes.hpp"
#include "tests/support/options.hpp"
#include "tests/support/render.hpp"

namespace lzb::rzb {
namespace {

double cpuSeconds() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

bool benchEnabled() {
  const char* v = std::getenv("LZB_BENCH");
  return v && std::string(v) == "1";
}

int benchThreads() {
  const char* t = std::getenv("RZB_BENCH_THREADS");
  return t ? std::atoi(t) : 2;
}

// The scene named by RZB_BENCH_SCENE (or `otherwise`), loaded with its camera, and the benchmark's
// thread count (RZB_BENCH_THREADS, default 2), already in use.
struct BenchSetup {
  std::string spec;
  Scene scene;
  int threads;
};
BenchSetup benchSetup(const char* otherwise = nullptr) {
  const char* spec = std::getenv("RZB_BENCH_SCENE");
  if (!spec) spec = otherwise;
  if (!spec) throw std::runtime_error("set RZB_BENCH_SCENE");
  BenchSetup b{spec, loadScene(spec, true), benchThreads()};
  useThreads(b.threads);
  return b;
}

// The point pass's parts on one scene: draws only, draws + list search, the whole splat; and the
// atomic-min scatter limit measured in the same process.
TEST(RzbBench, PointPassParts) {
  if (!benchEnabled()) GTEST_SKIP() << "set LZB_BENCH=1";
  const BenchSetup bench = benchSetup("builtin:chessboard?n=64");
  const Scene& scene = bench.scene;
  const int threads = bench.threads;
  const Camera camera = test::sceneCamera(scene, 640, 480);
  // RZB_BENCH_FALLBACK=auto keeps the z-buffer fallback (only the point pass is timed here).
  const char* fb = std::getenv("RZB_BENCH_FALLBACK");
  RzbParams p;
  p.fallback = fb && std::string(fb) == "auto";
  RzbRenderer r(scene, test::renderOptions("rzb", threads, 7), p);
  FrameStats warm;
  test::renderFrame(r, camera, &warm);
  // The renderer's selection; its sample boxes.
  const double pixels = 640.0 * 480.0;
  SelectParams sp;
  sp.eps = p.eps;
  sp.samplesPerPixel = p.samplesPerPixel(pixels);
  sp.fallbackPx = p.fallbackThreshold(pixels);
  sp.maxBoxSamples = 16.0 * pixels * sp.samplesPerPixel;
  const SampleStream stream(7, 1);
  const Selection sel = selectBoxes(r.sampleScene(), camera, sp, stream);
  std::vector<SplatJob> jobs;
  for (uint32_t i = 0; i < sel.boxes.size(); ++i)
    if (!sel.boxes[i].fallback) appendJobs(jobs, i, sel.boxes[i].samples, nullptr);
  const uint64_t samples = sel.samples;
  // Best of three wall times; cpu: the CPU seconds of that run (robust to a shared machine).
  std::map<std::string, double> cpu;
  auto timed = [&](const std::string& name, auto&& body) {
    double best = 1e30;
    for (int rep = 0; rep < 3; ++rep) {
      const double c0 = cpuSeconds();
      Stopwatch c;
      body();
      const double wall = c.seconds();
      if (wall < best) {
        best = wall;
        cpu[name] = cpuSeconds() - c0;
      }
    }
    return best;
  };
  uint64_t sink = 0;
  const double drawS = timed("draw", [&] {
    uint64_t acc = 0;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) reduction(^ : acc)
    for (size_t k = 0; k < jobs.size(); ++k)
      for (uint64_t s0 = 0; s0 < jobs[k].count; s0 += kDrawBatch) {
        const uint32_t n = uint32_t(std::min<uint64_t>(kDrawBatch, jobs[k].count - s0));
        const DrawWords d = batchDraws(stream, sel.boxes[jobs[k].box].key, jobs[k].first + s0, n);
        acc ^= d.w[0][n - 1];
      }
    sink ^= acc;
  });
  const double pickS = timed("pick", [&] {
    uint64_t acc = 0;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) reduction(^ : acc)
    for (size_t k = 0; k < jobs.size(); ++k) {
      auto f = [&](const glm::dvec3& q, const glm::dvec3&, uint64_t id, const DistributionTree*,
                   uint32_t) { acc ^= id + uint64_t(q.x); };
      const SelectedBox& box = sel.boxes[jobs[k].box];
      drawBoxSamples(box, stream, jobs[k].first, jobs[k].count, box.samples, f);
    }
    sink ^= acc;
  });
  KeyBuffer keys;
  const SplatSetup setup = SplatSetup::from(camera, 1);
  PassCounts pc;
  const double splatS = timed("splat", [&] {
    keys.reset(640, 480, scene.expandedTriangles() > 0xffffffffull, threads);
    pc = splatJobs(jobs, sel.boxes, stream, setup, true, keys, threads);
  });
  const double limit = measureScatterLimit(640, 480, threads, 1.0);
  nlohmann::json j = {{"scene", scene.source},
                      {"fallback", p.fallback ? "auto" : "off"},
                      {"threads", threads},
                      {"samples", samples},
                      {"boxes", sel.boxes.size()},
                      {"draw_per_s", samples / drawS},
                      {"draw_pick_per_s", samples / pickS},
                      {"splat_per_s", samples / splatS},
                      {"splatted", pc.splatted},
                      {"scatter_limit_per_s", limit},
                      {"fraction_of_limit", samples / splatS / limit},
                      {"wide_keys", keys.wide()},
                      {"cpu_ns_per_sample_draw", cpu["draw"] / samples * 1e9},
                      {"cpu_ns_per_sample_draw_pick", cpu["pick"] / samples * 1e9},
                      {"cpu_ns_per_sample_splat", cpu["splat"] / samples * 1e9},
                      {"sink", sink & 1}};
  std::printf("BENCH %s\n", j.dump().c_str());
}

// One node holding every triangle of `scene` in world space (no instancing).
Scene flattened(const Scene& scene) {
  Scene out;
  out.addNode("flat");
  Mesh& m = out.nodes[0].mesh;
  for (const DrawItem& item : flattenScene(scene)) {
    const Mesh& src = scene.nodes[item.node].mesh;
    for (uint32_t t = 0; t < src.size(); ++t) {
      glm::vec3 v[3];
      for (int k = 0; k < 3; ++k)
        v[k] = glm::vec3(item.transform * glm::dvec4(glm::dvec3(src.vertex(t, k)), 1.0));
      m.add(v[0], v[1], v[2], src.color(t));
    }
  }
  out.camera = scene.camera;
  return out;
}

// Section 8.4: a ~5,800-triangle object inserted into a 1.2 M triangle city one triangle at a
// time and removed again, against rebuilding the tree; and sampling speed while dirty.
TEST(RzbBench, DynamicUpdates) {
  if (!benchEnabled()) GTEST_SKIP() << "set LZB_BENCH=1";
  Scene scene = flattened(loadScene("builtin:city?blocks=10", true));
  const uint32_t cityTriangles = uint32_t(scene.nodes[0].mesh.size());
  const std::string path = test::scannedMesh("elephant.off");
  ASSERT_FALSE(path.empty()) << "elephant.off missing";
  const Scene object = loadScene(path, true);
  // The object, 12 m tall, standing in the street in front of the camera.
  const Bounds ob = object.bounds();
  const double scale = 12.0 / std::max(ob.extent().y, 1e-9);
  const glm::dvec3 at = scene.camera->position + 30.0 * glm::normalize(scene.camera->lookAt - scene.camera->position);
  Mesh& m = scene.nodes[0].mesh;
  const Mesh& om = object.nodes[object.root].mesh;
  for (uint32_t t = 0; t < om.size(); ++t) {
    glm::vec3 v[3];
    for (int k = 0; k < 3; ++k)
      v[k] = glm::vec3((glm::dvec3(om.vertex(t, k)) - glm::dvec3(ob.center().x, ob.lo.y, ob.center().z)) * scale +
                       glm::dvec3(at.x, 0.0, at.z));
    m.add(v[0], v[1], v[2], om.color(t));
  }
  scene.finalize();
  const uint32_t total = uint32_t(m.size());
  std::vector<uint32_t> city(cityTriangles);
  for (uint32_t t = 0; t < cityTriangles; ++t) city[t] = t;

  Stopwatch clock;
  DistributionTree full(scene, 0, {}, true, {}, DistributionParams{});
  const double rebuild = clock.lap();
  DistributionTree tree(scene, 0, city, false, {}, DistributionParams{});
  clock.lap();
  for (uint32_t t = cityTriangles; t < total; ++t) tree.insertTriangle(t);
  const double insert = clock.lap();
  const double areaAfterInsert = tree.totalArea();
  // Sampling speed while dirty against the static tree, over the whole tree.
  auto sampleRate = [&](const DistributionTree& tr) {
    const SampleStream stream(1, 2);
    uint64_t acc = 0, n = 0;
    Stopwatch c;
    for (const DistributionTree::ClassRoot& cr : tr.classes()) {
      SelectedBox b;
      b.tree = &tr;
      b.node = cr.root;
      b.key = cr.root;
      const uint64_t count = uint64_t(2e6 * tr.node(cr.root).area / tr.totalArea()) + 1;
      auto sink = [&](const glm::dvec3& p, const glm::dvec3&, uint64_t id, const DistributionTree*,
                      uint32_t) { acc += id ^ uint64_t(p.x); };
      drawBoxSamples(b, stream, 0, count, count, sink);
      n += count;
    }
    EXPECT_NE(acc, 1u);
    return double(n) / c.seconds();
  };
  const double dirtyRate = sampleRate(tree), staticRate = sampleRate(full);
  clock.lap();
  for (uint32_t t = cityTriangles; t < total; ++t) tree.removeTriangle(t);
  const double remove = clock.lap();
  tree.compact();
  const double compactS = clock.lap();
  const nlohmann::json j = {{"city_triangles", cityTriangles},
                            {"object_triangles", total - cityTriangles},
                            {"rebuild_s", rebuild},
                            {"insert_s", insert},
                            {"remove_s", remove},
                            {"insert_remove_s", insert + remove},
                            {"us_per_triangle", (insert + remove) / (2.0 * (total - cityTriangles)) * 1e6},
                            {"compact_s", compactS},
                            {"area_error", std::abs(areaAfterInsert / full.totalArea() - 1.0)},
                            {"dirty_samples_per_s", dirtyRate},
                            {"static_samples_per_s", staticRate}};
  std::printf("BENCH %s\n", j.dump().c_str());
  EXPECT_LT(std::abs(areaAfterInsert / full.totalArea() - 1.0), 1e-12);
}

Camera walkCamera(const Scene& scene, int frame, double step, int width, int height) {
  CameraSpec c = *scene.camera;
  const glm::dvec3 f = glm::normalize(c.lookAt - c.position);
  c.position += double(frame) * step * f;
  c.lookAt += double(frame) * step * f;
  return Camera(withClipPlanes(c, scene.bounds()), width, height);
}

// Table 1 analogue: per scene and splat size, the frame time with a new sample set and with the
// cache (same view, warm), the z-buffer's time, and accuracy against it.
TEST(RzbBench, Table1) {
  if (!benchEnabled()) GTEST_SKIP() << "set LZB_BENCH=1";
  const BenchSetup bench = benchSetup();
  const Scene& scene = bench.scene;
  const int threads = bench.threads;
  const char* spec = bench.spec.c_str();
  const Camera camera = test::sceneCamera(scene, 640, 480);
  const bool withZ = !std::getenv("RZB_BENCH_NO_ZBUFFER");
  ReferenceFrame exact;
  double zSeconds = 0.0;
  if (withZ) {
    ZBufferRenderer z(scene, test::renderOptions("rzb", threads, 7));
    test::renderFrame(z, camera);  // uploads
    Stopwatch c;
    const Framebuffer centres = test::renderFrame(z, camera);
    zSeconds = c.seconds();
    exact = reduceReference(centres, test::renderFrame(z, subsampleCamera(camera)));
  }
  for (int d : {1, 2, 5}) {
    for (bool cache : {false, true}) {
      RzbParams p;
      p.splat = d;
      p.reconstruct = d > 1 ? Reconstruct::kSplat : Reconstruct::kPixel;
      p.cacheMb = cache ? 1024.0 : 0.0;
      RzbRenderer r(scene, test::renderOptions("rzb", threads, 7), p);
      double first = 0.0, best = 1e30;
      Framebuffer fb;
      FrameStats stats;
      for (int f = 0; f < 4; ++f) {
        FrameStats s;
        Stopwatch c;
        fb = test::renderFrame(r, camera, &s, {}, f);
        const double t = c.seconds();
        if (f == 0) first = t;
        if (f > 0 && t < best) best = t, stats = s;
      }
      nlohmann::json j = {{"scene", spec},
                          {"triangles", scene.expandedTriangles()},
                          {"d", d},
                          {"cache", cache},
                          {"first_frame_s", first},
                          // Frames 1..3: fresh sample sets (cache off) or the warm cache (on),
                          // both after the first frame's GL context and mesh uploads.
                          {"frame_s", best},
                          {"zbuffer_s", zSeconds},
                          {"samples", stats.counts["samples_drawn"]},
                          {"fallback_triangles", stats.counts["fallback_triangles"]},
                          {"setup_s", r.sampleScene().stats().buildSeconds},
                          {"tree_bytes", r.sampleScene().stats().memoryBytes}};
      if (withZ) {
        const Accuracy accuracy = compare(fb, exact);
        j["correct_rate_covered"] = accuracy.correctRateCovered;
        j["psnr_aa"] = std::isfinite(accuracy.psnrAa) ? nlohmann::json(accuracy.psnrAa) : nlohmann::json(nullptr);
      }
      std::printf("BENCH %s\n", j.dump().c_str());
    }
  }
}

// Section 8.5: an 80-frame walkthrough with and without the cache (starting empty), with the
// stage times of both (which part the cache can speed up). RZB_BENCH_FALLBACK=off: point pass
// only; RZB_BENCH_SPLAT=d; RZB_BENCH_FRAMES=n (default 80).
TEST(RzbBench, CacheWalkthrough) {
  if (!benchEnabled()) GTEST_SKIP() << "set LZB_BENCH=1";
  const BenchSetup bench = benchSetup();
  const Scene& scene = bench.scene;
  const int threads = bench.threads;
  const char* spec = bench.spec.c_str();
  const char* stepEnv = std::getenv("RZB_BENCH_STEP");
  const double step = stepEnv ? std::atof(stepEnv) : 0.5;
  const char* framesEnv = std::getenv("RZB_BENCH_FRAMES");
  const int frames = framesEnv ? std::atoi(framesEnv) : 80;
  RzbParams plain;
  const char* fb = std::getenv("RZB_BENCH_FALLBACK");
  plain.fallback = !(fb && std::string(fb) == "off");
  const char* splat = std::getenv("RZB_BENCH_SPLAT");
  plain.splat = splat ? std::atoi(splat) : 1;
  plain.reconstruct = plain.splat > 1 ? Reconstruct::kSplat : Reconstruct::kPixel;
  RzbParams cached = plain;
  cached.cacheMb = 2048.0;
  RzbRenderer a(scene, test::renderOptions("rzb", threads, 7), plain),
      b(scene, test::renderOptions("rzb", threads, 7), cached);
  const auto stages = [](const FrameStats& s) {
    nlohmann::json j = nlohmann::json::object();
    for (const auto& [n, v] : s.stageSeconds) j[n] = v;
    return j;
  };
  for (int f = 0; f < frames; ++f) {
    const Camera camera = walkCamera(scene, f, step, 640, 480);
    FrameStats sa, sb;
    Stopwatch c;
    test::renderFrame(a, camera, &sa, {}, f);
    const double ta = c.lap();
    test::renderFrame(b, camera, &sb, {}, f);
    const double tb = c.lap();
    const nlohmann::json j = {{"scene", spec},
                              {"fallback", plain.fallback ? "auto" : "off"},
                              {"d", plain.splat},
                              {"frame", f},
                              {"plain_s", ta},
                              {"cached_s", tb},
                              {"plain_stages", stages(sa)},
                              {"cached_stages", stages(sb)},
                              {"cache_hits", sb.counts["cache_hits"]},
                              {"cache_misses", sb.counts["cache_misses"]},
                              {"cache_bytes", sb.counts["cache_bytes"]},
                              {"fallback_triangles", sa.counts["fallback_triangles"]},
                              {"plain_samples", sa.counts["samples_drawn"]},
                              {"cached_samples", sb.counts["samples_drawn"]}};
    std::printf("BENCH %s\n", j.dump().c_str());
  }
}

// Fig. 7: box selection and reconstruction time against eps, and where --eps auto lands.
TEST(RzbBench, EpsCurve) {
  if (!benchEnabled()) GTEST_SKIP() << "set LZB_BENCH=1";
  const BenchSetup bench = benchSetup();
  const Scene& scene = bench.scene;
  const int threads = bench.threads;
  const char* spec = bench.spec.c_str();
  const Camera camera = test::sceneCamera(scene, 640, 480);
  std::vector<double> values;
  for (double e = 1.02; e < 16.0; e *= 1.25) values.push_back(e);
  for (int i = -1; i < int(values.size()); ++i) {
    RzbParams p;
    if (i < 0)
      p.autoEps = true;
    else
      p.eps = values[size_t(i)];
    RzbRenderer r(scene, test::renderOptions("rzb", threads, 7), p);
    FrameStats s, best;
    double bestT = 1e30;
    for (int rep = 0; rep < 3; ++rep) {
      FrameStats t;
      Stopwatch c;
      test::renderFrame(r, camera, &t);
      const double sec = c.seconds();
      if (sec < bestT) bestT = sec, best = t;
    }
    std::map<std::string, double> st;
    for (const auto& [n, v] : best.stageSeconds) st[n] = v;
    const nlohmann::json j = {{"scene", spec},
                              {"eps", r.lastEps()},
                              {"auto", i < 0},
                              {"frame_s", bestT},
                              {"select_s", st["select"]},
                              {"reconstruct_s", st["splat"] + st["resolve"] + st["fallback"]},
                              {"nodes_visited", best.shared["nodes_visited"]},
                              {"boxes", best.counts["boxes_selected"]},
                              {"samples", best.counts["samples_drawn"]}};
    std::printf("BENCH %s\n", j.dump().c_str());
  }
}

}  // namespace
}  // namespace lzb::rzb
