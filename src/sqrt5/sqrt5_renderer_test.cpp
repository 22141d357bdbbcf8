// --method sqrt5 on procedural and mesh scenes: no holes at the requested density, accuracy
// against the exact ray caster, bounded refinement at grazing angles, and the same frame for any
// thread count and any split into rank shares.
#include <gtest/gtest.h>

#include <cstdio>
#include <cmath>

#include "raycast/exact/raycast_renderer.hpp"
#include "src/image/metrics.hpp"
#include "src/scene/load.hpp"
#include "src/sqrt5/sqrt5_renderer.hpp"
#include "tests/support/cameras.hpp"
#include "tests/support/frames.hpp"
#include "tests/support/options.hpp"
#include "tests/support/reference.hpp"
#include "tests/support/render.hpp"

namespace lzb::sqrt5 {
namespace {

Sqrt5Params defaults() { return parseSqrt5Options({}); }

// At the default A'min (spacing below 0.71 px, 1-pixel splats) the displaced plane and sphere leave
// (almost) no pixel empty that the exact image covers. Measured: 0 of 12,280 (plane) and 0 of
// 7,090 (sphere) at 160 x 120; the bound allows the pixels a sub-pixel tessellation deviation can
// move across a silhouette.
TEST(Sqrt5Renderer, NoHolesOnDisplacedSurfacesAtTheRequestedDensity) {
  for (const char* spec : {"builtin:displaced", "builtin:displaced?shape=sphere"}) {
    const Scene scene = loadScene(spec, true);
    const Camera cam = test::sceneCamera(scene, 160, 120);
    Sqrt5Renderer r(scene, test::renderOptions("sqrt5", 2), defaults());
    const Framebuffer image = test::renderFrame(r, cam);
    const Framebuffer ref = test::exactFrame(scene, cam, test::renderOptions("sqrt5", 2));
    const size_t h = test::holes(image, ref), c = test::covered(ref);
    std::printf("%s: %zu holes of %zu covered pixels\n", spec, h, c);
    EXPECT_GT(c, 4000u);
    EXPECT_LE(double(h), 0.002 * double(c)) << spec;
  }
}

// Accuracy against raycast on builtin:displaced at the default settings (the report's figure,
// witnessed by rays). Measured 99.98 % of covered pixels at 160 x 120; asserted above 98 %: the
// exact surface is sampled, the references draw its tessellation (within 0.5 px, tested in
// src/scene), so the differences are pixels where the two surfaces cross.
TEST(Sqrt5Renderer, AccurateAgainstRaycastOnTheDisplacedPlane) {
  const Scene scene = loadScene("builtin:displaced", true);
  const Camera cam = test::sceneCamera(scene, 160, 120);
  Sqrt5Renderer r(scene, test::renderOptions("sqrt5", 2), defaults());
  const Accuracy a =
      test::accuracy(scene, cam, test::renderFrame(r, cam), test::renderOptions("sqrt5", 2));
  std::printf("displaced: correct_rate_covered %.4f, exact ids %.4f, holes %zu\n",
              a.correctRateCovered, a.exactIdRateCovered, a.missingPixels);
  EXPECT_GT(a.correctRateCovered, 0.98);
}

// A flat plane seen at 0.1 degrees above its surface: the projected spacing along the view
// direction shrinks with the elevation, across it with the distance, so refinement stays shallow
// (measured: 3 levels) below the default bound of 12; a bound of 2 is what stops it then. Either
// way the samples stay within the roots times 5 per level and within 40 per pixel / A'min.
TEST(Sqrt5Renderer, RefinementDepthIsBoundedAtGrazingAngles) {
  const Scene scene = loadScene("builtin:displaced?amp=0&tess=8", true);
  CameraSpec spec;
  spec.position = {0.0, 0.01, 5.5};
  spec.lookAt = {0.0, 0.0, -5.0};
  spec.nearPlane = 0.01;
  spec.farPlane = 100.0;
  const Camera cam(spec, 160, 120);
  for (int levels : {2, 12}) {
    Sqrt5Params p = defaults();
    p.levels = levels;
    Sqrt5Renderer r(scene, test::renderOptions("sqrt5", 2), p);
    const Sqrt5Renderer::Frame f = r.prepare(cam, WorkShare{});
    ASSERT_EQ(f.placements.size(), 1u);
    const Sqrt5Renderer::DrawCounts c = r.draw(f);
    std::printf("levels %d: roots %llu, samples %llu, deepest %d, at bound %llu\n", levels,
                (unsigned long long)c.trees.roots, (unsigned long long)c.trees.drawn,
                c.trees.deepest, (unsigned long long)c.trees.atLevelBound);
    EXPECT_LE(c.trees.deepest, levels);
    if (levels == 2) {
      EXPECT_EQ(c.trees.deepest, 2);
      EXPECT_GT(c.trees.atLevelBound, 0u);
    } else {
      EXPECT_LT(c.trees.deepest, levels);
      EXPECT_EQ(c.trees.atLevelBound, 0u);
    }
    EXPECT_LE(double(c.trees.drawn), double(c.trees.roots) * std::pow(5.0, levels));
    EXPECT_LE(double(c.trees.drawn), 40.0 * 160 * 120 / p.amin);
  }
}

// Horizon culling drops only hidden initial samples: the terrain's default view (along the ground
// to the horizon) gives the same frame with culling on and off, and culls some (measured: 277 of
// 13,225 initial samples at 160 x 120, 7 % fewer samples generated).
TEST(Sqrt5Renderer, HorizonCullingNeverChangesTheImage) {
  const Scene scene = loadScene("builtin:terrain?tess=128", true);
  const Camera cam = test::sceneCamera(scene, 160, 120);
  Sqrt5Params off = defaults();
  off.horizon = false;
  Sqrt5Renderer culling(scene, test::renderOptions("sqrt5", 2), defaults()),
      plain(scene, test::renderOptions("sqrt5", 2), off);
  FrameStats a, b;
  const Framebuffer on = test::renderFrame(culling, cam, &a),
                    all = test::renderFrame(plain, cam, &b);
  size_t differ = 0;
  for (size_t i = 0; i < on.size(); ++i) differ += on.id[i] != all.id[i];
  EXPECT_EQ(differ, 0u) << "pixels that differ with culling";
  EXPECT_TRUE(test::sameIdsAndDepths(on, all));
  EXPECT_EQ(a.shared.value("terrain_sectors", 0.0), 1.0);
  const double culled = a.counts.value("samples_culled_horizon", 0.0),
               initial = a.counts.value("samples_initial", 0.0);
  std::printf("terrain: %.0f of %.0f initial samples culled (%.0f at the top test); samples "
              "generated %.0f with culling, %.0f without\n",
              culled, initial, a.counts.value("samples_culled_horizon_at_top", 0.0),
              a.counts.value("samples_generated", 0.0), b.counts.value("samples_generated", 0.0));
  EXPECT_EQ(b.counts.value("samples_culled_horizon", 0.0), 0.0);
  EXPECT_GT(culled, 0.0);
  EXPECT_LT(a.counts.value("samples_generated", 0.0), b.counts.value("samples_generated", 0.0));
}

// The forest cache (section 5.2): a second frame from a nearby viewpoint reuses the first's
// samples and gives exactly the frame a renderer without a cache gives.
TEST(Sqrt5Renderer, ForestCacheReusesSamplesWithoutChangingTheImage) {
  const Scene scene = loadScene("builtin:displaced?tess=128", true);
  CameraSpec spec = *scene.camera;
  const Camera first = test::sceneCamera(scene, 160, 120);
  spec.position += glm::dvec3(0.05, -0.05, 0.02);
  const Camera second(withClipPlanes(spec, scene.bounds()), 160, 120);
  Sqrt5Params none = defaults();
  none.cacheMb = 0;
  Sqrt5Renderer cached(scene, test::renderOptions("sqrt5", 2), defaults()),
      fresh(scene, test::renderOptions("sqrt5", 2), none);
  FrameStats s1, s2, s3;
  test::renderFrame(cached, first, &s1);
  const Framebuffer a = test::renderFrame(cached, second, &s2),
                    b = test::renderFrame(fresh, second, &s3);
  EXPECT_TRUE(test::sameIdsAndDepths(a, b));
  const double hits = s2.counts.value("cache_hits", 0.0), misses = s2.counts.value("cache_misses", 0.0);
  std::printf("cache: frame 2 hits %.0f, misses %.0f, %.1f MB; uncached generated %.0f samples\n",
              hits, misses, s2.counts.value("cache_bytes", 0.0) / 1e6,
              s3.counts.value("samples_generated", 0.0));
  EXPECT_EQ(s1.counts.value("cache_hits", 0.0), 0.0);
  EXPECT_GT(hits, 4.0 * misses);
  EXPECT_LT(s2.counts.value("samples_generated", 0.0), 0.5 * s3.counts.value("samples_generated", 0.0));
  EXPECT_EQ(s2.counts.value("samples_drawn", 0.0), s3.counts.value("samples_drawn", 0.0));
}

// 1 and 2 threads, and the shares of 3 ranks composited, give the same frame (procedural and mesh
// placements together).
TEST(Sqrt5Renderer, SameFrameForAnyThreadsAndShares) {
  const Scene scene = loadScene("builtin:displaced?shape=sphere&tess=64", true);
  const Camera cam = test::sceneCamera(scene, 96, 72);
  Sqrt5Renderer one(scene, test::renderOptions("sqrt5", 1), defaults()),
      two(scene, test::renderOptions("sqrt5", 2), defaults());
  const Framebuffer a = test::renderFrame(one, cam), b = test::renderFrame(two, cam);
  EXPECT_TRUE(test::sameIdsAndDepths(a, b));
  Framebuffer shares(cam.width(), cam.height());
  uint64_t drawn = 0;
  int working = 0;
  for (int rank = 0; rank < 3; ++rank) {
    FrameStats s;
    Sqrt5Renderer r(scene, test::renderOptions("sqrt5", 1), defaults());
    compositeNearer(shares, test::renderFrame(r, cam, &s, WorkShare{rank, 3}));
    const uint64_t mine = s.counts.value("samples_drawn", 0.0);
    drawn += mine;
    working += mine > 0;
  }
  EXPECT_TRUE(test::sameIdsAndDepths(a, shares));
  FrameStats all;
  test::renderFrame(one, cam, &all);
  EXPECT_EQ(drawn, uint64_t(all.counts.value("samples_drawn", 0.0)));
  EXPECT_GE(working, 2);  // the work was split
}

// Mesh placements whose prefix would be at least kPolygonFactor x their triangle count are drawn
// as polygons by the native z-buffer, the others as points, into one frame: the same for 1 and 2
// threads and for 3 ranks' shares composited, the triangles dealt like the samples.
TEST(Sqrt5Renderer, PolygonPlacementsMixWithPointsAndSplitLikeTheRest) {
  const Scene scene = loadScene("builtin:sphereflake?depth=2", true);
  const Camera cam = test::sceneCamera(scene, 160, 120);
  Sqrt5Renderer one(scene, test::renderOptions("sqrt5", 1), defaults()),
      two(scene, test::renderOptions("sqrt5", 2), defaults());
  FrameStats all;
  const Framebuffer a = test::renderFrame(one, cam, &all), b = test::renderFrame(two, cam);
  EXPECT_TRUE(test::sameIdsAndDepths(a, b));
  const double polygons = all.shared.value("placements_polygons", 0.0);
  EXPECT_GT(polygons, 0.0);
  EXPECT_LT(polygons, all.shared.value("placements_visible", 0.0));
  EXPECT_GT(all.counts.value("halton_samples_drawn", 0.0), 0.0);
  EXPECT_EQ(all.counts.value("polygon_placements_drawn", 0.0), polygons);
  Framebuffer shares(cam.width(), cam.height());
  uint64_t triangles = 0;
  int working = 0;
  for (int rank = 0; rank < 3; ++rank) {
    FrameStats s;
    Sqrt5Renderer r(scene, test::renderOptions("sqrt5", 1), defaults());
    compositeNearer(shares, test::renderFrame(r, cam, &s, WorkShare{rank, 3}));
    const uint64_t mine = s.counts.value("triangles_drawn", 0.0);
    triangles += mine;
    working += mine > 0;
  }
  EXPECT_TRUE(test::sameIdsAndDepths(a, shares));
  EXPECT_EQ(triangles, uint64_t(all.counts.value("triangles_drawn", 0.0)));
  EXPECT_GE(working, 2);
}

// Mesh objects by Halton prefixes: the forest's trees and terrain tiles, against raycast.
// Measured 99.0 % of covered pixels at 160 x 120; Halton points are not a lattice, so thin leaves
// seen at the prefix's density leave some pixels to farther leaves; asserted above 90 %.
TEST(Sqrt5Renderer, HaltonMeshesAgainstRaycast) {
  const Scene scene = loadScene("builtin:halton-forest?trees=16", true);
  const Camera cam = test::sceneCamera(scene, 160, 120);
  Sqrt5Renderer r(scene, test::renderOptions("sqrt5", 2), defaults());
  FrameStats s;
  const Framebuffer image = test::renderFrame(r, cam, &s);
  EXPECT_GT(s.counts.value("halton_samples_drawn", 0.0), 0.0);
  const Accuracy a = test::accuracy(scene, cam, image, test::renderOptions("sqrt5", 2));
  std::printf("halton-forest: correct_rate_covered %.4f, holes %zu\n", a.correctRateCovered,
              a.missingPixels);
  EXPECT_GT(a.correctRateCovered, 0.90);
}

}  // namespace
}  // namespace lzb::sqrt5
