// RzbRenderer end to end: the same image for any thread and rank count, accuracy against the exact
// z-buffer on the city and a real scanned mesh, the fallback path, the cache, 10^12 triangles.
#include "src/rzb/rzb_renderer.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include "src/core/error.hpp"
#include "src/core/shading.hpp"
#include "src/core/timer.hpp"
#include "src/image/metrics.hpp"
#include "src/scene/load.hpp"
#include "src/zbuffer/zbuffer_renderer.hpp"
#include "tests/support/cameras.hpp"
#include "tests/support/frames.hpp"
#include "tests/support/meshes.hpp"
#include "tests/support/options.hpp"
#include "tests/support/reference.hpp"
#include "tests/support/render.hpp"

namespace lzb::rzb {
namespace {

// A fallback threshold high enough that the point pass draws most of a small city.
RzbParams pointHeavy() {
  RzbParams p;
  p.fallbackPx = 64.0;
  return p;
}

const Scene& smallCity() {
  static const Scene scene = loadScene("builtin:city?blocks=3", true);
  return scene;
}

// Both fallback z-buffers, the native one (default) and OSMesa.
constexpr FallbackRender kRenders[] = {FallbackRender::kNative, FallbackRender::kGl};

TEST(RzbRenderer, SameImageForOneAndTwoThreads) {
  const Scene& scene = smallCity();
  const Camera camera = test::sceneCamera(scene, 160, 120);
  for (FallbackRender render : kRenders) {
    RzbParams p = pointHeavy();
    p.fallbackRender = render;
    RzbRenderer one(scene, test::renderOptions("rzb", 1, 7), p),
        two(scene, test::renderOptions("rzb", 2, 7), p);
    FrameStats stats;
    const Framebuffer a = test::renderFrame(one, camera, &stats, {}, 3);
    const Framebuffer b = test::renderFrame(two, camera, nullptr, {}, 3);
    EXPECT_GT(stats.counts["samples_splatted"].get<double>(), 1e4);
    EXPECT_GT(stats.counts["fallback_triangles"].get<double>(), 0.0);
    EXPECT_TRUE(test::sameImage(a, b)) << fallbackRenderName(render);
    // Another frame number draws other samples.
    const Framebuffer c = test::renderFrame(two, camera, nullptr, {}, 4);
    EXPECT_FALSE(test::sameImage(a, c));
  }
}

TEST(RzbRenderer, TwoRanksCompositeToTheOneRankImage) {
  const Scene& scene = smallCity();
  const Camera camera = test::sceneCamera(scene, 160, 120);
  for (FallbackRender render : kRenders) {
    RzbParams p = pointHeavy();
    p.fallbackRender = render;
    RzbRenderer r(scene, test::renderOptions("rzb", 2, 7), p);
    FrameStats s0, s1;
    const Framebuffer whole = test::renderFrame(r, camera, nullptr, {}, 1);
    Framebuffer part0 = test::renderFrame(r, camera, &s0, {0, 2}, 1);
    const Framebuffer part1 = test::renderFrame(r, camera, &s1, {1, 2}, 1);
    // Both ranks did a real share of each kind of work.
    EXPECT_GT(s0.counts["samples_drawn"].get<double>(), 0.0);
    EXPECT_GT(s1.counts["samples_drawn"].get<double>(), 0.0);
    EXPECT_GT(s0.counts["fallback_triangles"].get<double>(), 0.0);
    EXPECT_GT(s1.counts["fallback_triangles"].get<double>(), 0.0);
    compositeNearer(part0, part1);
    EXPECT_TRUE(test::sameImage(part0, whole)) << fallbackRenderName(render);
  }
}

TEST(RzbRenderer, TwoRanksWithWideKeysOnTenToTheTwelveTriangles) {
  const Scene scene = loadScene("builtin:chessboard?n=1048576", true);
  ASSERT_GT(scene.expandedTriangles(), uint64_t(1e12));
  const Camera camera = test::sceneCamera(scene, 96, 72);
  RzbParams p;
  p.fallback = false;
  RzbRenderer r(scene, test::renderOptions("rzb", 2, 7), p);
  const Framebuffer whole = test::renderFrame(r, camera);
  Framebuffer part0 = test::renderFrame(r, camera, nullptr, {0, 2});
  compositeNearer(part0, test::renderFrame(r, camera, nullptr, {1, 2}));
  EXPECT_TRUE(test::sameImage(part0, whole));
  EXPECT_GT(whole.coveredCount(), whole.size() / 3);
}

// Two measures: the report's (src/image/metrics.hpp: the pixel's ID is one of the z-buffer's 17
// samples of the pixel, over covered pixels) and visibleInPixelRate (the ID seen anywhere in a
// 5x supersampled z-buffer around the pixel). The 17 samples cannot see most triangles much
// smaller than a pixel, so a random point sampler is held to the denser measure: the defaults
// (fallback on) must pass the report's; the point pass itself, with most triangles sampled, the
// supersampled one.
void expectAccurate(const Scene& scene, const Camera& camera, const std::string& name,
                    const RzbParams& pointParams) {
  const ReferenceFrame ref = test::zbufferReference(scene, camera);
  {
    RzbRenderer r(scene, test::renderOptions("rzb", 2, 7), RzbParams{});
    const Accuracy a = compare(test::renderFrame(r, camera), ref);
    std::printf("[ rzb      ] %s %dx%d, defaults: correct %.4f of covered pixels\n", name.c_str(),
                camera.width(), camera.height(), a.correctRateCovered);
    EXPECT_GE(a.correctRateCovered, 0.99) << name;
  }
  RzbRenderer r(scene, test::renderOptions("rzb", 2, 7), pointParams);
  FrameStats stats;
  const Framebuffer fb = test::renderFrame(r, camera, &stats);
  const double visible = test::visibleInPixelRate(fb, scene, camera);
  std::printf("[ rzb      ] %s, point pass (%g samples, %g fallback triangles): correct %.4f "
              "(visible in pixel), %.4f of covered pixels (17 samples)\n",
              name.c_str(), stats.counts["samples_drawn"].get<double>(),
              stats.counts["fallback_triangles"].get<double>(), visible,
              compare(fb, ref).correctRateCovered);
  EXPECT_GT(stats.counts["samples_splatted"].get<double>(), 0.5 * double(fb.coveredCount()));
  EXPECT_GE(visible, 0.99) << name;
}

TEST(RzbRenderer, CityCorrectPixelRateAtD1) {
  const Scene& scene = smallCity();
  expectAccurate(scene, test::sceneCamera(scene, 320, 240), "city", pointHeavy());
}

TEST(RzbRenderer, RealScannedMeshCorrectPixelRateAtD1) {
  const std::string path = test::scannedMesh("bunny00.off");
  if (path.empty()) GTEST_SKIP() << "bunny00.off missing: run scripts/fetch-test-meshes.sh";
  const Scene scene = loadScene(path, true);
  RzbParams off;
  off.fallback = false;
  expectAccurate(scene, test::sceneCamera(scene, 320, 240), "bunny", off);
}

TEST(RzbRenderer, LargeTrianglesGoToTheZBufferAndMatchItExactly) {
  // A few big quads at different depths: every box is over the threshold, so the image is the
  // exact z-buffer's (IDs and depths bit for bit, colours by the same rule).
  Scene scene;
  scene.addNode("quads");
  Mesh& m = scene.nodes[0].mesh;
  for (int k = 0; k < 4; ++k) {
    const float z = -2.0f * float(k), x = float(k) - 1.5f;
    ASSERT_TRUE(m.add({x - 2, -2, z}, {x + 2, -2, z}, {x + 2, 2, z}, packRgba8(200, 50, 50)));
    ASSERT_TRUE(m.add({x - 2, -2, z}, {x + 2, 2, z}, {x - 2, 2, z}, packRgba8(50, 200, 50)));
  }
  scene.finalize();
  const Camera camera = test::lookAtCamera({0.5, 0.3, 8}, {0, 0, -3}, 0.5, 50.0, 160, 120);
  // OSMesa's image for --fallback-render gl, the native z-buffer's for the default.
  RzbParams gl;
  gl.fallbackRender = FallbackRender::kGl;
  RzbRenderer rg(scene, test::renderOptions("rzb", 2, 7), gl);
  FrameStats stats;
  const Framebuffer fg = test::renderFrame(rg, camera, &stats);
  EXPECT_EQ(stats.counts["samples_drawn"].get<double>(), 0.0);
  EXPECT_EQ(stats.counts["fallback_triangles"].get<double>(), 8.0);
  EXPECT_TRUE(test::sameImage(fg, test::zbufferFrame(scene, camera)));
  RzbRenderer rn(scene, test::renderOptions("rzb", 2, 7), RzbParams{});
  FrameStats ns;
  const Framebuffer fn = test::renderFrame(rn, camera, &ns);
  EXPECT_EQ(ns.counts["fallback_triangles"].get<double>(), 8.0);
  Framebuffer native(camera.width(), camera.height());
  DrawLists all;
  all.lists.push_back({0, glm::dmat4(1.0), 0, {0, 1, 2, 3, 4, 5, 6, 7}});
  all.triangles = 8;
  NativeRasterizer().draw(scene, camera, all, {}, 1, native);
  EXPECT_TRUE(test::sameImage(fn, native));
  // The two z-buffers agree on every pixel's triangle here (no edge passes near a centre).
  EXPECT_EQ(fn.id, fg.id);
  // With the fallback off the same scene is all points, and still right almost everywhere.
  RzbParams off;
  off.fallback = false;
  RzbRenderer points(scene, test::renderOptions("rzb", 2, 7), off);
  FrameStats ps;
  const Framebuffer pf = test::renderFrame(points, camera, &ps);
  EXPECT_EQ(ps.counts["fallback_boxes"].get<double>(), 0.0);
  EXPECT_GE(compare(pf, test::zbufferReference(scene, camera)).correctRateCovered, 0.99);
}

TEST(RzbRenderer, CachedFramesAreTheSameImageAndHit) {
  const Scene& scene = smallCity();
  const Camera camera = test::sceneCamera(scene, 160, 120);
  RzbParams p = pointHeavy();
  p.cacheMb = 64.0;
  RzbRenderer r(scene, test::renderOptions("rzb", 2, 7), p);
  FrameStats first, second;
  const Framebuffer a = test::renderFrame(r, camera, &first);
  const Framebuffer b = test::renderFrame(r, camera, &second, {}, 1);
  EXPECT_GT(first.counts["cache_misses"].get<double>(), 0.0);
  EXPECT_EQ(first.counts["cache_hits"].get<double>(), 0.0);
  EXPECT_EQ(second.counts["cache_misses"].get<double>(), 0.0);
  EXPECT_EQ(second.counts["cache_hits"].get<double>(), first.counts["cache_misses"].get<double>());
  EXPECT_EQ(second.counts["cache_samples_generated"].get<double>(), 0.0);
  EXPECT_TRUE(test::sameImage(a, b));
  // Quantization removes duplicate samples: fewer splats than a fresh frame draws.
  RzbRenderer fresh(scene, test::renderOptions("rzb", 2, 7), pointHeavy());
  FrameStats fs;
  const Framebuffer c = test::renderFrame(fresh, camera, &fs);
  EXPECT_LT(second.counts["samples_drawn"].get<double>(), fs.counts["samples_drawn"].get<double>());
  // Quantization costs little accuracy against a fresh sample set.
  EXPECT_GE(test::visibleInPixelRate(b, scene, camera),
            test::visibleInPixelRate(c, scene, camera) - 0.02);
  // A budget too small for everything still gives the same image (sets used once, not kept).
  RzbParams tight = p;
  tight.cacheMb = 0.5;
  RzbRenderer small(scene, test::renderOptions("rzb", 2, 7), tight);
  FrameStats ts;
  EXPECT_TRUE(test::sameImage(test::renderFrame(small, camera, &ts), a));
  EXPECT_LE(ts.counts["cache_bytes"].get<double>(), 0.5 * 1024 * 1024);
}

TEST(RzbRenderer, CacheBudgetBelowOneBoxIsAnInputError) {
  const Scene& scene = smallCity();
  RzbParams p;
  p.cacheMb = 0.01;
  RzbRenderer r(scene, test::renderOptions("rzb", 1, 7), p);
  const Camera camera = test::sceneCamera(scene, 640, 480);
  Framebuffer fb(640, 480);
  FrameStats stats;
  EXPECT_THROW(r.render(camera, 0, {}, fb, stats), InputError);
}

TEST(RzbRenderer, InstancedChessboardOfTenToTheTwelveRendersInSeconds) {
  const Scene scene = loadScene("builtin:chessboard?n=1048576", true);
  const Camera camera = test::sceneCamera(scene, 640, 480);
  RzbRenderer r(scene, test::renderOptions("rzb", 2, 7), RzbParams{});
  Stopwatch clock;
  FrameStats stats;
  const Framebuffer fb = test::renderFrame(r, camera, &stats);
  const double seconds = clock.seconds();
  std::printf("[ rzb      ] chessboard 2.2e12 triangles 640x480: %.2f s, %g samples\n", seconds,
              stats.counts["samples_drawn"].get<double>());
  EXPECT_LT(seconds, 10.0);
  // The board fills the lower part of the view; every shown ID is a board triangle.
  EXPECT_GT(fb.coveredCount(), fb.size() / 3);
  for (size_t i = 0; i < fb.size(); i += 997)
    if (fb.covered(i)) {
      EXPECT_TRUE(scene.resolve(fb.id[i]).has_value());
    }
}

TEST(RzbRenderer, GaussReconstructionIsCloseToTheZBuffer) {
  const Scene& scene = smallCity();
  const Camera camera = test::sceneCamera(scene, 120, 90);
  RzbParams p = pointHeavy();
  RzbRenderer pixel(scene, test::renderOptions("rzb", 2, 7), p);
  Framebuffer pf = test::renderFrame(pixel, camera);
  shadeFromIds(scene, camera, pf);  // as the frame driver does for colour from the IDs
  p.reconstruct = Reconstruct::kGauss;
  RzbRenderer r(scene, test::renderOptions("rzb", 2, 7), p);
  FrameStats stats;
  const Framebuffer fb = test::renderFrame(r, camera, &stats);
  const ReferenceFrame ref = test::zbufferReference(scene, camera);
  const Accuracy a = compare(fb, ref), ap = compare(pf, ref);
  const double visible = test::visibleInPixelRate(fb, scene, camera);
  const double visiblePixel = test::visibleInPixelRate(pf, scene, camera);
  std::printf("[ rzb      ] city 120x90 gauss: visible in pixel %.4f, PSNR (aa) %.1f dB; pixel: "
              "%.4f, %.1f dB\n", visible, a.psnrAa, visiblePixel, ap.psnrAa);
  EXPECT_GT(stats.counts["gauss_visible_samples"].get<double>(), 0.0);
  EXPECT_GE(visible, visiblePixel - 0.02);
  EXPECT_GT(a.psnrAa, 20.0);
  // Every covered pixel got a colour (alpha 255), and not just the flat triangle colour.
  size_t blended = 0;
  for (size_t i = 0; i < fb.size(); ++i) {
    if (!fb.covered(i)) continue;
    EXPECT_EQ(channel(fb.color[i], 3), 255);
    blended += fb.color[i] != pf.color[i];
  }
  EXPECT_GT(blended, fb.coveredCount() / 10);
  // Rank 0 renders everything; rank 1 adds nothing.
  const Framebuffer other = test::renderFrame(r, camera, nullptr, {1, 2});
  EXPECT_EQ(other.coveredCount(), 0u);
}

TEST(RzbRenderer, AutoEpsPicksAValueInRange) {
  const Scene& scene = smallCity();
  const Camera camera = test::sceneCamera(scene, 320, 240);
  RzbParams p;
  p.autoEps = true;
  RzbRenderer r(scene, test::renderOptions("rzb", 2, 7), p);
  FrameStats stats;
  const Framebuffer fb = test::renderFrame(r, camera, &stats);
  EXPECT_GE(r.lastEps(), 1.1 - 1e-9);
  EXPECT_LE(r.lastEps(), 5.0 + 1e-9);
  EXPECT_GT(stats.shared["eps_evaluations"].get<double>(), 3.0);
  EXPECT_GE(test::visibleInPixelRate(fb, scene, camera), 0.99);
}

}  // namespace
}  // namespace lzb::rzb
