// The hybrid method: exact where the scene has large triangles (the city), close to the
// definition on sub-pixel geometry (a field of scanned-mesh instances, a board of 5 * 10^8
// instanced squares), the same image for any
// split over ranks, and a walk that really leaves the sampled geometry to the point pass.
#include "src/hybrid/hybrid_renderer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "raycast/exact/ray_witness.hpp"
#include "raycast/exact/raycast_renderer.hpp"
#include "raycast/lzb/lzb_renderer.hpp"
#include "src/core/error.hpp"
#include "src/core/shading.hpp"
#include "src/image/metrics.hpp"
#include "src/scene/load.hpp"
#include "src/zbuffer/zbuffer_renderer.hpp"
#include "tests/support/cameras.hpp"
#include "tests/support/meshes.hpp"
#include "tests/support/options.hpp"
#include "tests/support/reference.hpp"
#include "tests/support/render.hpp"

namespace lzb {
namespace {

using hybrid::HybridParams;
using hybrid::HybridRenderer;

// A field of 256 armadillos (13 M triangles): most triangles far smaller than a pixel.
const Scene* field() {
  static const Scene* scene = [] {
    const std::string mesh = test::scannedMesh("armadillo.off");
    return mesh.empty() ? nullptr
                        : new Scene(loadScene("builtin:replicated?mesh=" + mesh + "&k=16&levels=1", true));
  }();
  return scene;
}

// The point pass exercised at these small sizes: rzb's threshold d^2 / ln(pixels) at 160 x 120
// (~0.1 px), which samples these scenes; the automatic one (kAutoFallbackPx) samples only far
// smaller triangles.
// The local z-buffering frame's stages, whatever the probe would choose (--frame-way local).
HybridParams local() {
  HybridParams p;
  p.frameWay = hybrid::FrameWay::kLocal;
  return p;
}

HybridParams sampling() {
  HybridParams p = local();
  p.fallbackPx = 1.0 / std::log(160.0 * 120.0);
  return p;
}

// Rank shares of r's frame, 2 and then 3 of them composited, give `whole`'s IDs and depths.
void expectSharesComposeTo(Renderer& r, const Camera& cam, const Framebuffer& whole) {
  for (int size : {2, 3}) {
    Framebuffer composite(cam.width(), cam.height());
    for (int rank = 0; rank < size; ++rank)
      compositeNearer(composite, test::renderFrame(r, cam, nullptr, {rank, size}));
    EXPECT_EQ(composite.id, whole.id) << size << " ranks";
    EXPECT_EQ(composite.depth, whole.depth) << size << " ranks";
  }
}

TEST(HybridRenderer, IsExactOnTheCity) {
  const Scene scene = loadScene("builtin:city?blocks=4", true);
  HybridRenderer r(scene, test::renderOptions("lzb", 2), HybridParams{});
  for (int f : {0, 2}) {
    const Camera cam = test::pathFrame(scene, f, 4, 192, 144);
    const Accuracy a =
        test::accuracy(scene, cam, test::renderFrame(r, cam), test::renderOptions("lzb", 2));
    EXPECT_GE(a.correctRateCovered, 0.999) << "frame " << f;
    EXPECT_EQ(a.missingPixels, 0u) << "frame " << f;
  }
}

// The areas' lists and sums (LeafAreas::prepareSampling) are built by the first frame that
// samples, once, and what it reports is what they hold; a run whose frames sample nothing never
// holds them.
TEST(HybridRenderer, BuildsTheSamplingSumsOnlyWhenAFrameSamples) {
  const Scene scene = loadScene("builtin:forest?trees=40", true);
  const Camera cam = test::pathFrame(scene, 1, 4, 160, 120);
  HybridParams exact = local();
  exact.fallbackPx = 1e-12;  // no triangle projects below: nothing sampled
  HybridRenderer none(scene, test::renderOptions("lzb", 2), exact);
  const double eager = none.setupStats().shared.value("leaf_area_bytes", 0.0);
  FrameStats plain;
  test::renderFrame(none, cam, &plain);
  EXPECT_EQ(plain.shared.value("sampled_leaves", -1.0), 0.0);
  EXPECT_FALSE(plain.shared.contains("leaf_area_bytes"));

  HybridRenderer some(scene, test::renderOptions("lzb", 2), sampling());
  FrameStats first, second;
  test::renderFrame(some, cam, &first);
  test::renderFrame(some, cam, &second);
  ASSERT_GT(first.shared.value("sampled_leaves", 0.0), 0.0);
  EXPECT_GT(first.shared.value("leaf_area_bytes", 0.0), 4.0 * eager) << "the sums, built";
  EXPECT_FALSE(second.shared.contains("leaf_area_bytes")) << "built once";

  const localz::LzbAccel accel(scene, localz::LzbAccelParams{});
  const hybrid::LeafAreas areas(accel);
  EXPECT_FALSE(areas.samplingPrepared());
  areas.prepareSampling();
  EXPECT_TRUE(areas.samplingPrepared());
  EXPECT_EQ(areas.memoryBytes(), uint64_t(first.shared.value("leaf_area_bytes", 0.0)));
}

// Where nothing is sampled (the city) the hybrid's rays are lzb's, frame after frame: the walk
// counts are each frame's own (they once accumulated over the frames of a run).
TEST(HybridRenderer, WithNothingSampledCastsLikeLzbEveryFrame) {
  const Scene scene = loadScene("builtin:city?blocks=4", true);
  HybridRenderer hybrid(scene, test::renderOptions("lzb", 2), local());
  localz::LzbRenderer lzb(scene, test::renderOptions("lzb", 2), localz::LzbOptions{});
  for (int f : {0, 1}) {  // (at this size frame 2 samples distant blocks)
    const Camera cam = test::pathFrame(scene, f, 4, 192, 144);
    FrameStats hs, ls;
    const Framebuffer h = test::renderFrame(hybrid, cam, &hs);
    const Framebuffer l = test::renderFrame(lzb, cam, &ls);
    EXPECT_EQ(hs.shared.value("sampled_leaves", -1.0), 0.0) << "frame " << f;
    // Embree's rays, as lzb's (nothing to skip).
    EXPECT_FALSE(hs.counts.contains("octree_leaves_visited")) << "frame " << f;
    // (Not hit_placements_resolved: per-thread cache misses, which depend on the tile schedule.)
    for (const char* k : {"rays_cast", "rays_hit", "pvl_size"})
      EXPECT_EQ(hs.counts.value(k, -1.0), ls.counts.value(k, -2.0)) << k << ", frame " << f;
    EXPECT_EQ(h.id, l.id) << "frame " << f;
    // Every covered pixel was finished by the near pass or the PVL, none by samples.
    EXPECT_EQ(hs.counts.value("sample_pixels", -1.0), 0.0) << "frame " << f;
    EXPECT_EQ(hs.shared.value("near_pixels", 0.0) + hs.counts.value("pvl_pixels", 0.0),
              double(h.coveredCount()))
        << "frame " << f;
  }
}

TEST(HybridRenderer, SubPixelFieldIsSampledAndShowsVisibleTriangles) {
  const Scene* scene = field();
  if (!scene) GTEST_SKIP() << "armadillo.off missing: run scripts/fetch-test-meshes.sh";
  HybridRenderer hybrid(*scene, test::renderOptions("lzb", 2), sampling());
  localz::LzbOptions walk;  // what the hybrid's rays do where the point pass takes leaves
  walk.farRays = localz::FarRays::kWalk;
  localz::LzbRenderer lzb(*scene, test::renderOptions("lzb", 2), walk);
  const Camera cam = test::pathFrame(*scene, 1, 4, 160, 120);
  FrameStats hs, ls;
  const Framebuffer image = test::renderFrame(hybrid, cam, &hs);
  test::renderFrame(lzb, cam, &ls);
  const Accuracy a = test::accuracy(*scene, cam, image, test::renderOptions("lzb", 2));
  EXPECT_GE(a.correctRateCovered, 0.95);  // the randomized z-buffer paper's 95-99 %
  EXPECT_LE(a.missingPixels, a.coveredPixels / 100);
  // The point pass took the field: samples show most covered pixels, and the walk skipped the
  // sampled triangles instead of testing them.
  EXPECT_GT(hs.shared.value("sampled_leaves", 0.0), 0.0);
  EXPECT_GT(hs.counts.value("sample_pixels", 0.0), 0.5 * double(a.coveredPixels));
  EXPECT_LT(hs.counts.value("ray_triangle_tests", 0.0), 0.5 * ls.counts.value("ray_triangle_tests", 0.0));
  EXPECT_LT(hs.counts.value("pvl_size", 0.0), 0.1 * ls.counts.value("pvl_size", 0.0));
}

// The rule's test of a whole placement (mayTakeLeaves, which spares the point pass a look at
// every culled leaf) never turns away a placement with a leaf the rule samples.
TEST(HybridRenderer, PlacementTestNeverHidesASampledLeaf) {
  const Scene scene = loadScene("builtin:city?blocks=4", true);
  const localz::LzbAccel accel(scene, localz::LzbAccelParams{});
  const hybrid::LeafAreas areas(accel);
  uint64_t sampledLeaves = 0, placementsTurnedAway = 0;
  for (double threshold : {1e-3, 0.1, 10.0})
    for (int f : {0, 2}) {
      const Camera cam = test::pathFrame(scene, f, 4, 192, 144);
      hybrid::SampledLeafRule rule(accel, areas, cam.pixelsPerUnitAt(1.0), threshold);
      rule.setPlane(cam.nearPlane());
      const localz::CulledScene culled =
          localz::cullScene(accel, cam);  // (every leaf listed, none taken whole)
      for (const localz::CullPath& p : culled.paths) {
        const localz::LeafPlacement placement{p.depthGrad, p.depthOffset,
                                              maxAreaScale(glm::dmat3(p.world))};
        const bool may = rule.mayTakeLeaves(p.node, placement);
        placementsTurnedAway += !may;
        for (uint32_t l = p.firstLeaf; l < p.firstLeaf + p.leafCount; ++l) {
          const localz::CullLeaf& leaf = culled.leaves[l];
          if (!rule.sampled(p.node, leaf.leaf, leaf.depthMin, placement.areaScale)) continue;
          ++sampledLeaves;
          EXPECT_TRUE(may) << "threshold " << threshold << ", frame " << f;
        }
      }
    }
  EXPECT_GT(sampledLeaves, 0u);
  EXPECT_GT(placementsTurnedAway, 0u);
}

// With the automatic threshold the field (triangles of ~0.01-0.1 pixel here) is drawn by the
// rays and the PVL, exactly: sampling it cost more than lazy ray casting and lost accuracy.
TEST(HybridRenderer, AutomaticThresholdDrawsTheFieldExactly) {
  const Scene* scene = field();
  if (!scene) GTEST_SKIP() << "armadillo.off missing: run scripts/fetch-test-meshes.sh";
  HybridRenderer hybrid(*scene, test::renderOptions("lzb", 2), local());
  const Camera cam = test::pathFrame(*scene, 1, 4, 160, 120);
  FrameStats stats;
  const Accuracy a = test::accuracy(*scene, cam, test::renderFrame(hybrid, cam, &stats),
                                    test::renderOptions("lzb", 2));
  EXPECT_EQ(stats.shared.value("sampled_leaves", -1.0), 0.0);
  EXPECT_GE(a.correctRateCovered, 0.999);
}

// The 2- and 3-rank shares of `params`' frame composite to the 1-rank image, and the counts
// `split` of the ranks are shares of the 1-rank counts (each less, summing to them).
void expectRankSharesComposite(const Scene& scene, const Camera& cam, const HybridParams& params,
                               const std::vector<std::string>& split) {
  HybridRenderer one(scene, test::renderOptions("lzb", 2), params);
  FrameStats alone;
  const Framebuffer single = test::renderFrame(one, cam, &alone);
  for (int size : {2, 3}) {
    Framebuffer composite(cam.width(), cam.height());
    std::vector<double> sums(split.size(), 0.0);
    for (int rank = 0; rank < size; ++rank) {
      HybridRenderer r(scene, test::renderOptions("lzb", 1), params);
      FrameStats stats;
      const Framebuffer part = test::renderFrame(r, cam, &stats, {rank, size});
      compositeNearer(composite, part);
      for (size_t k = 0; k < split.size(); ++k) {
        sums[k] += stats.counts.value(split[k], 0.0);
        EXPECT_LT(stats.counts.value(split[k], 0.0), alone.counts.value(split[k], 0.0)) << split[k];
      }
    }
    EXPECT_EQ(composite.id, single.id) << size << " ranks";
    EXPECT_EQ(composite.depth, single.depth) << size << " ranks";
    for (size_t k = 0; k < split.size(); ++k)
      EXPECT_EQ(sums[k], alone.counts.value(split[k], -1.0)) << split[k] << ", " << size << " ranks";
  }
}

TEST(HybridRenderer, RankSharesCompositeToTheOneRankImageOnASampledField) {
  const Scene* scene = field();
  if (!scene) GTEST_SKIP() << "armadillo.off missing: run scripts/fetch-test-meshes.sh";
  expectRankSharesComposite(*scene, test::pathFrame(*scene, 1, 4, 160, 120), sampling(),
                            {"samples_drawn", "rays_cast"});
}

// The far pass by cost: on the field (~680 culled triangles a pixel at 160 x 120) each
// unfinished pixel takes its Embree hit, no PVL; asked for lazy, the PVL draws it; both exact,
// and the direct rays split over ranks to the 1-rank image. The city stays lazy (the test above).
TEST(HybridRenderer, DenseFarSceneIsCastDirectlyAndExactly) {
  const Scene* scene = field();
  if (!scene) GTEST_SKIP() << "armadillo.off missing: run scripts/fetch-test-meshes.sh";
  const Camera cam = test::pathFrame(*scene, 1, 4, 160, 120);
  HybridParams lazy = local();
  lazy.farPass = hybrid::FarPass::kLazy;
  for (const HybridParams& params : {local(), lazy}) {
    const bool direct = params.farPass == hybrid::FarPass::kAuto;
    HybridRenderer hybrid(*scene, test::renderOptions("lzb", 2), params);
    FrameStats stats;
    const Framebuffer image = test::renderFrame(hybrid, cam, &stats);
    const auto& stages = stats.stageSeconds;
    EXPECT_EQ(std::count_if(stages.begin(), stages.end(),
                            [](const auto& st) { return st.first == "raycast"; }),
              direct ? 1 : 0);
    EXPECT_EQ(stats.counts.contains("pvl_size"), !direct);
    EXPECT_GT(stats.counts.value(direct ? "ray_pixels" : "pvl_pixels", 0.0), 0.0);
    EXPECT_EQ(stats.shared.value("near_pixels", 0.0) +
                  stats.counts.value(direct ? "ray_pixels" : "pvl_pixels", 0.0),
              double(image.coveredCount()));
    EXPECT_GE(test::accuracy(*scene, cam, image, test::renderOptions("lzb", 2)).correctRateCovered,
              0.999)
        << direct;
  }
  expectRankSharesComposite(*scene, cam, local(), {"rays_cast"});
}

// The direct frame's cull stops at the median coarse hit depth (the field holds far more than
// 16 triangles a pixel in front of it), and the frame is the whole cull's: byte for byte the
// image of local z-buffering's naive stage (the same cost plane, near pass and Embree rays).
TEST(HybridRenderer, DirectFrameCullsOnlyToTheMedianHitAndDrawsTheWholeCullsImage) {
  const Scene* scene = field();
  if (!scene) GTEST_SKIP() << "armadillo.off missing: run scripts/fetch-test-meshes.sh";
  const Camera cam = test::pathFrame(*scene, 1, 4, 160, 120);
  HybridRenderer hybrid(*scene, test::renderOptions("lzb", 2), local());
  localz::LzbOptions naive;
  naive.stage = localz::LzbStage::kNaive;
  localz::LzbRenderer lzb(*scene, test::renderOptions("lzb", 2), naive);
  FrameStats hs, ls;
  const Framebuffer image = test::renderFrame(hybrid, cam, &hs);
  const Framebuffer whole = test::renderFrame(lzb, cam, &ls);
  ASSERT_TRUE(hs.shared.contains("cull_depth"));
  EXPECT_GT(hs.shared.value("cull_depth", 0.0), cam.nearPlane());
  EXPECT_LT(hs.shared.value("cull_depth", 0.0), cam.farPlane());
  EXPECT_LT(hs.shared.value("culled_leaves", 0.0), ls.shared.value("culled_leaves", 0.0));
  EXPECT_EQ(hs.shared.value("plane_depth", -1.0), ls.shared.value("plane_depth", -2.0));
  EXPECT_EQ(image.id, whole.id);
  EXPECT_EQ(image.depth, whole.depth);
  // Lazy frames cull the whole frustum.
  HybridParams lazy = local();
  lazy.farPass = hybrid::FarPass::kLazy;
  HybridRenderer lazyHybrid(*scene, test::renderOptions("lzb", 2), lazy);
  FrameStats zs;
  test::renderFrame(lazyHybrid, cam, &zs);
  EXPECT_FALSE(zs.shared.contains("cull_depth"));
  EXPECT_EQ(zs.shared.value("culled_leaves", -1.0), ls.shared.value("culled_leaves", -2.0));
}

// A board of 5.4 * 10^8 sub-pixel squares built by 8 levels of nested 2 x 2 instancing: whole
// instanced subtrees are sampled as units (a few hundred, not a cull through 65,536 placed
// blocks), every square visible where it should be, and the units' samples split over ranks and
// threads to the same image.
TEST(HybridRenderer, InstancedBoardIsSampledAsWholeSubtrees) {
  const Scene scene = loadScene("builtin:chessboard?n=16384", true);
  const Camera cam = test::pathFrame(scene, 1, 4, 160, 120);
  HybridRenderer one(scene, test::renderOptions("lzb", 2), sampling());
  FrameStats alone;
  const Framebuffer single = test::renderFrame(one, cam, &alone);
  const Accuracy a = test::accuracy(scene, cam, single, test::renderOptions("lzb", 2));
  EXPECT_GE(a.correctRateCovered, 0.99);
  EXPECT_LE(a.missingPixels, a.coveredPixels / 100);
  const double units = alone.shared.value("sampled_leaves", 0.0);
  EXPECT_GT(units, 0.0);
  EXPECT_LT(units, 2000.0);
  EXPECT_EQ(alone.counts.value("pvl_size", 0.0), 0.0);  // nothing left for the rays
  EXPECT_GT(alone.counts.value("sample_pixels", 0.0), 0.99 * double(a.coveredPixels));
  HybridRenderer oneThread(scene, test::renderOptions("lzb", 1), sampling());
  EXPECT_EQ(test::renderFrame(oneThread, cam).id, single.id);
  for (int size : {2, 3}) {
    Framebuffer composite(cam.width(), cam.height());
    double samples = 0.0;
    for (int rank = 0; rank < size; ++rank) {
      FrameStats stats;
      compositeNearer(composite, test::renderFrame(oneThread, cam, &stats, {rank, size}));
      samples += stats.counts.value("samples_drawn", 0.0);
      EXPECT_LT(stats.counts.value("samples_drawn", 0.0), alone.counts.value("samples_drawn", 0.0));
    }
    EXPECT_EQ(composite.id, single.id) << size << " ranks";
    EXPECT_EQ(composite.depth, single.depth) << size << " ranks";
    EXPECT_EQ(samples, alone.counts.value("samples_drawn", -1.0)) << size << " ranks";
  }
}

// The frame's way: on the field (hundreds of triangles a pixel) the probe finds more triangles
// in front of its plane than pixels they would finish and casts every pixel, the raycast
// method's image byte for byte with no cull; from the city's street the near walls finish
// pixels with few triangles and the frame is local z-buffering's, unless the plane's estimate
// says otherwise. Cast every pixel (rays), the ranks' tiles composite to the 1-rank image.
TEST(HybridRenderer, ProbeCastsEveryPixelWhereNearTrianglesOutnumberThePixelsTheyFinish) {
  const Scene* scene = field();
  if (!scene) GTEST_SKIP() << "armadillo.off missing: run scripts/fetch-test-meshes.sh";
  const Camera cam = test::pathFrame(*scene, 1, 4, 160, 120);
  HybridRenderer hybrid(*scene, test::renderOptions("lzb", 2), HybridParams{});
  RaycastRenderer raycast(*scene, test::renderOptions("raycast", 2));
  FrameStats hs;
  const Framebuffer image = test::renderFrame(hybrid, cam, &hs);
  const Framebuffer exact = test::renderFrame(raycast, cam);
  EXPECT_EQ(hs.shared.value("every_pixel_cast", -1.0), 1.0);
  EXPECT_GE(hs.shared.value("probe_triangles", 0.0), hs.shared.value("probe_finished_pixels", 1.0));
  EXPECT_GT(hs.shared.value("probe_finished_pixels", 0.0), 0.0);
  for (const auto& [stage, seconds] : hs.stageSeconds) EXPECT_NE(stage, "cull");
  EXPECT_EQ(image.id, exact.id);
  EXPECT_EQ(image.depth, exact.depth);

  // The city's street at 640 x 480: the probe and the plane's estimate keep it local. At
  // 192 x 144 the probe keeps it local, but the plane's estimate costs more than half the
  // castable pixels, and the frame casts every pixel after all.
  const Scene city = loadScene("builtin:city?blocks=4", true);
  HybridRenderer auto_(city, test::renderOptions("lzb", 2), HybridParams{});
  FrameStats cs, small;
  test::renderFrame(auto_, test::pathFrame(city, 0, 4, 640, 480), &cs);
  EXPECT_EQ(cs.shared.value("every_pixel_cast", -1.0), 0.0);
  EXPECT_LT(cs.shared.value("probe_triangles", 1e9), cs.shared.value("probe_finished_pixels", 0.0));
  EXPECT_LT(cs.shared.value("plane_cost", 1e9),
            HybridParams::kCastPixelCost * cs.shared.value("castable_pixels", 0.0));
  const Camera street = test::pathFrame(city, 0, 4, 192, 144);
  test::renderFrame(auto_, street, &small);
  EXPECT_EQ(small.shared.value("every_pixel_cast", -1.0), 1.0);
  EXPECT_LT(small.shared.value("probe_triangles", 1e9),
            small.shared.value("probe_finished_pixels", 0.0));
  EXPECT_EQ(small.shared.value("castable_pixels", 0.0), 192.0 * 144.0);

  HybridParams rays;
  rays.frameWay = hybrid::FrameWay::kRays;
  HybridRenderer cast(city, test::renderOptions("lzb", 1), rays);
  RaycastRenderer cityRays(city, test::renderOptions("raycast", 1));
  const Framebuffer whole = test::renderFrame(cityRays, street);
  EXPECT_EQ(test::renderFrame(cast, street).id, whole.id);
  expectSharesComposeTo(cast, street, whole);
}

// The city from outside (its circle's middle frames): the probe casts every pixel, its coarse
// rays miss in most castable pixels, and the rays stay in the screen cover: fewer rays than
// castable pixels, raycast's image byte for byte, and so split over 2 and 3 ranks.
TEST(HybridRenderer, AFrameCastFromAfarCastsOnlyUnderItsScreenCover) {
  const Scene city = loadScene("builtin:city?blocks=3", true);
  const Camera cam = test::pathFrame(city, 5, 11, 256, 192);
  HybridRenderer hybrid(city, test::renderOptions("lzb", 2), HybridParams{});
  RaycastRenderer raycast(city, test::renderOptions("raycast", 2));
  FrameStats hs, rs;
  const Framebuffer image = test::renderFrame(hybrid, cam, &hs);
  const Framebuffer exact = test::renderFrame(raycast, cam, &rs);
  EXPECT_EQ(hs.shared.value("every_pixel_cast", -1.0), 1.0);
  const double blocks = hs.shared.value("cover_blocks", -1.0);
  EXPECT_GT(blocks, 0.0);
  EXPECT_EQ(hs.counts.value("rays_cast", 0.0), 16.0 * blocks);
  EXPECT_LT(hs.counts.value("rays_cast", 0.0), 0.5 * rs.counts.value("rays", 0.0));
  EXPECT_EQ(image.id, exact.id);
  EXPECT_EQ(image.depth, exact.depth);
  expectSharesComposeTo(hybrid, cam, exact);
}

TEST(HybridRenderer, BadParametersNameTheOption) {
  EXPECT_EQ(hybrid::parseFrameWay("rays", "--frame-way"), hybrid::FrameWay::kRays);
  try {
    hybrid::parseFrameWay("pixels", "--frame-way");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--frame-way"), std::string::npos);
  }
  HybridParams p;
  p.splat = 0;
  EXPECT_THROW(p.validate(), InputError);
  p = {};
  p.oversample = -1.0;
  EXPECT_THROW(p.validate(), InputError);
  p = {};
  p.lzb.planeFraction = 2.0;
  EXPECT_THROW(p.validate(), InputError);
}

}  // namespace
}  // namespace lzb
