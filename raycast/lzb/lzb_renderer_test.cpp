#include "raycast/lzb/lzb_renderer.hpp"

#include <gtest/gtest.h>

#include <barrier>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <span>
#include <thread>

#include "mpi/decomposition.hpp"
#include "raycast/exact/embree_scene.hpp"
#include "raycast/exact/raycast_renderer.hpp"
#include "src/image/metrics.hpp"
#include "src/scene/load.hpp"
#include "src/zbuffer/zbuffer_renderer.hpp"
#include "tests/support/cameras.hpp"
#include "tests/support/meshes.hpp"
#include "tests/support/options.hpp"
#include "tests/support/reference.hpp"
#include "tests/support/render.hpp"
#include "tests/support/scenes.hpp"

namespace lzb::localz {
namespace {

using test::pathFrame;

constexpr LzbStage kStages[] = {LzbStage::kNaive, LzbStage::kLazy, LzbStage::kSelective,
                                LzbStage::kOor, LzbStage::kFinal};

// Pixels of the last frame whose exact hit (Embree, from where the rays start) is missing from
// the PVL; -1 when the stage has no PVL.
long missingFromPvl(const LzbRenderer& r, const EmbreeScene& embree, const Camera& cam) {
  if (!r.options().usesPvl()) return -1;
  const auto& last = r.lastFrame();
  const double tMin = std::max(cam.nearPlane(), last.plane.depth * (1.0 - 1e-7));
  long missing = 0;
  for (uint32_t i : last.castPixels) {
    const int x = int(i) % cam.width(), y = int(i) / cam.width();
    const RayHit h = embree.intersect(cam.position(), cam.pixelDirection(x + 0.5, y + 0.5), tMin,
                                      cam.farPlane());
    if (h.hit() && !last.pvl.contains(h.id)) ++missing;
  }
  return missing;
}

// Every stage (and the given options) against its exact reference on the listed frames of a
// 4-frame path: >= 99.9 % of covered pixels correct and with the exact centre ID; every ray-cast
// pixel's exact hit in the PVL. The reference is the z-buffer, except for naive, whose far pixels
// are Embree's: against the z-buffer it would measure the two exact methods' own disagreement on
// sub-pixel geometry (zbuffer vs raycast: 0.995 of the far city's covered pixels).
void expectMatchesZBuffer(const Scene& scene, int w, int h, std::initializer_list<int> frames,
                          std::vector<LzbStage> stages = {std::begin(kStages), std::end(kStages)},
                          LzbOptions base = {}) {
  ZBufferRenderer zbuffer(scene, test::renderOptions("lzb", 2));
  RaycastRenderer raycast(scene, test::renderOptions("lzb", 2));
  const EmbreeScene embree(scene, {});
  for (LzbStage stage : stages) {
    LzbOptions o = base;
    o.stage = stage;
    LzbRenderer r(scene, test::renderOptions("lzb", 2), o);
    Renderer& exact = stage == LzbStage::kNaive ? static_cast<Renderer&>(raycast) : zbuffer;
    uint64_t cast = 0;
    for (int f : frames) {
      const Camera cam = pathFrame(scene, f, 4, w, h);
      const ReferenceFrame ref = test::renderReference(exact, scene, cam);
      const Framebuffer img = test::renderFrame(r, cam);
      const Accuracy a = compare(img, ref);
      EXPECT_GE(a.correctRateCovered, 0.999) << scene.source << " " << toString(stage) << " " << f;
      EXPECT_GE(a.exactIdRateCovered, 0.999) << scene.source << " " << toString(stage) << " " << f;
      const long missing = missingFromPvl(r, embree, cam);
      if (missing >= 0) {
        EXPECT_EQ(missing, 0) << scene.source << " " << toString(stage) << " " << f;
      }
      cast += r.lastFrame().castPixels.size();
    }
    EXPECT_GT(cast, 0u) << scene.source << " " << toString(stage) << ": no ray was cast";
  }
}

// Which z-buffer draws the near pass and which the PVL.
struct ZBuffers {
  ZBufferKind near, pvl;
};
constexpr ZBuffers kZBuffers[] = {{ZBufferKind::kNative, ZBufferKind::kNative},
                                  {ZBufferKind::kGl, ZBufferKind::kNative},
                                  {ZBufferKind::kNative, ZBufferKind::kGl},
                                  {ZBufferKind::kGl, ZBufferKind::kGl}};

std::string toString(ZBuffers z) {
  return "near " + toString(z.near) + ", PVL " + toString(z.pvl);
}

LzbOptions zbufferOptions(ZBuffers z) {
  LzbOptions o;
  o.nearRender = z.near;
  o.pvlRender = z.pvl;
  return o;
}

TEST(LzbRenderer, EveryStageMatchesZBufferOnTheCity) {
  const Scene scene = loadScene("builtin:city?blocks=4", true);
  // Frame 0 is at street level inside the city (the camera inside the octrees); frame 1 sees
  // it from outside.
  const Camera street = pathFrame(scene, 0, 4, 192, 144);
  ASSERT_TRUE(scene.bounds().contains(street.position()));
  for (ZBuffers z : kZBuffers) {
    SCOPED_TRACE(toString(z));
    expectMatchesZBuffer(scene, 192, 144, {0, 1}, {std::begin(kStages), std::end(kStages)},
                         zbufferOptions(z));
  }
}

TEST(LzbRenderer, EveryStageMatchesZBufferOnInstancedScenes) {
  // Rotated, non-uniformly scaled instances three levels deep; a sphereflake (one sphere node
  // reached along 91 instance paths, three levels).
  for (ZBuffers z : kZBuffers) {
    SCOPED_TRACE(toString(z));
    const std::vector<LzbStage> all(std::begin(kStages), std::end(kStages));
    expectMatchesZBuffer(test::nestedScene(21), 160, 120, {0, 2}, all, zbufferOptions(z));
    expectMatchesZBuffer(loadScene("builtin:sphereflake?depth=2", true), 160, 120, {0, 1}, all,
                         zbufferOptions(z));
  }
}

// The native z-buffer and OSMesa agree on the IDs (both are exact z-buffers; they may differ on a
// few pixel centres lying on an edge) and closely on the depths: the near passes alone, and
// the PVL at the ray-cast pixels.
TEST(LzbRenderer, NativeAndGlZBuffersAgree) {
  const Scene scene = loadScene("builtin:city?blocks=4", true);
  size_t nearCovered = 0;
  for (int f : {0, 2, 3}) {
    const Camera cam = pathFrame(scene, f, 4, 192, 144);
    // A static plane deep in the frustum: the near pass gets a good part of the image.
    LzbOptions nativeOptions = zbufferOptions(kZBuffers[0]),
               glOptions = zbufferOptions(kZBuffers[3]);
    nativeOptions.planeFraction = glOptions.planeFraction = 0.6;
    LzbRenderer native(scene, test::renderOptions("lzb", 2), nativeOptions);
    LzbRenderer gl(scene, test::renderOptions("lzb", 2), glOptions);
    native.keepNearPass(true);
    gl.keepNearPass(true);
    const Framebuffer a = test::renderFrame(native, cam), b = test::renderFrame(gl, cam);
    const Framebuffer &nearA = native.lastFrame().nearPass, &nearB = gl.lastFrame().nearPass;
    ASSERT_GT(nearB.coveredCount(), 0u) << f << ": no near scene to compare";
    nearCovered += nearB.coveredCount();
    long nearDiffer = 0;
    for (size_t i = 0; i < a.size(); ++i) {
      if (nearA.id[i] != nearB.id[i]) {
        ++nearDiffer;
      } else if (nearA.id[i] != kNoId) {
        EXPECT_NEAR(nearA.depth[i], nearB.depth[i], 1e-4 * nearB.depth[i]) << f << " " << i;
      }
    }
    EXPECT_LE(nearDiffer, long(a.size() / 1000)) << f;
    ASSERT_GT(native.lastFrame().pvl.triangles, 0u) << f;
    long same = 0, differ = 0;
    for (uint32_t i : native.lastFrame().castPixels) {
      if (a.id[i] != b.id[i]) {
        ++differ;
        continue;
      }
      ++same;
      if (a.id[i] != kNoId) {
        EXPECT_NEAR(a.depth[i], b.depth[i], 1e-4 * b.depth[i]) << f << " " << i;
      }
    }
    EXPECT_GT(same, 0) << f;
    EXPECT_LE(differ, long(a.size() / 1000)) << f;
    long imageDiffer = 0;
    for (size_t i = 0; i < a.size(); ++i) imageDiffer += a.id[i] != b.id[i];
    EXPECT_LE(imageDiffer, long(a.size() / 1000)) << f;
  }
  EXPECT_GT(nearCovered, size_t(3 * 192 * 144 / 10)) << "too little near scene compared";
}

TEST(LzbRenderer, PvlStagesMatchZBufferOnAForest) {
  // 16 instanced terrain tiles with trees. Its foliage z-fights: Embree and the z-buffer
  // themselves disagree on 0.1-0.3 % of its pixels, so naive (Embree far pixels) is left out;
  // the PVL stages draw through the z-buffer and match it.
  expectMatchesZBuffer(loadScene("builtin:forest?trees=6&levels=1", true), 160, 120, {0},
                       {LzbStage::kLazy, LzbStage::kSelective, LzbStage::kOor, LzbStage::kFinal});
}

TEST(LzbRenderer, EveryStageMatchesZBufferOnAScannedMesh) {
  const std::string bunny = test::scannedMesh("bunny00.off");
  if (bunny.empty()) GTEST_SKIP() << "bunny00.off unavailable (scripts/fetch-test-meshes.sh)";
  expectMatchesZBuffer(loadScene(bunny, true), 160, 120, {0, 1});
}

// The paper's own octree walk (--lzb-rays walk, with its occluders), kept for the stage study and
// used by the hybrid: every PVL stage on the same scenes as Embree's rays above.
TEST(LzbRenderer, WalkedRaysMatchZBuffer) {
  LzbOptions walk;
  walk.farRays = FarRays::kWalk;
  const std::vector<LzbStage> pvl = {LzbStage::kLazy, LzbStage::kSelective, LzbStage::kOor,
                                     LzbStage::kFinal};
  expectMatchesZBuffer(loadScene("builtin:city?blocks=4", true), 192, 144, {0, 1}, pvl, walk);
  expectMatchesZBuffer(test::nestedScene(21), 160, 120, {0, 2}, pvl, walk);
  expectMatchesZBuffer(loadScene("builtin:sphereflake?depth=2", true), 160, 120, {0, 1}, pvl, walk);
  expectMatchesZBuffer(loadScene("builtin:forest?trees=6&levels=1", true), 160, 120, {0}, pvl,
                       walk);
}

TEST(LzbRenderer, StaticOccluderSettingsStayExact) {
  const Scene scene = loadScene("builtin:city?blocks=3", true);
  for (OccluderMode mode : {OccluderMode::kStatic, OccluderMode::kDynamic})
    for (int k : {0, 1, 10}) {
      LzbOptions o = test::lzbStageOptions(LzbStage::kSelective);
      o.farRays = FarRays::kWalk;  // occluders act in the walk only
      o.occluderMode = mode;
      o.occluders = k;
      ZBufferRenderer zbuffer(scene, test::renderOptions("lzb", 2));
      LzbRenderer r(scene, test::renderOptions("lzb", 2), o);
      const Camera cam = pathFrame(scene, 0, 4, 128, 96);
      const Accuracy a =
          compare(test::renderFrame(r, cam), test::renderReference(zbuffer, scene, cam));
      EXPECT_GE(a.exactIdRateCovered, 0.999) << toString(mode) << " K=" << k;
    }
}

TEST(LzbRenderer, PlaneInFrontOfEverything) {
  const Scene scene = loadScene("builtin:city?blocks=3", true);
  LzbOptions o;
  o.planeFraction = 1e-9;  // at the near plane: no near scene, every covered pixel is ray cast
  LzbRenderer r(scene, test::renderOptions("lzb", 2), o);
  r.keepNearPass(true);
  ZBufferRenderer zbuffer(scene, test::renderOptions("lzb", 2));
  const Camera cam = pathFrame(scene, 0, 4, 128, 96);
  FrameStats stats;
  const Framebuffer img = test::renderFrame(r, cam, &stats);
  EXPECT_EQ(r.lastFrame().nearPass.size(), img.size());
  EXPECT_EQ(r.lastFrame().nearPass.coveredCount(), 0u);
  EXPECT_EQ(stats.shared.value("unfinished_pixels", 0.0), 128.0 * 96.0);
  EXPECT_GE(compare(img, test::renderReference(zbuffer, scene, cam)).exactIdRateCovered, 0.999);
}

TEST(LzbRenderer, PlaneBehindEverythingLeavesAnEmptyFarScene) {
  const Scene scene = loadScene("builtin:city?blocks=3", true);
  LzbOptions o;
  o.planeFraction = 0.999;
  LzbRenderer r(scene, test::renderOptions("lzb", 2), o);
  ZBufferRenderer zbuffer(scene, test::renderOptions("lzb", 2));
  // From above and outside: everything lies in front of 0.999 of the frustum depth.
  CameraSpec spec = frameBounds(scene.bounds());
  spec.farPlane *= 2.0;
  const Camera cam(spec, 128, 96);
  FrameStats stats;
  const Framebuffer img = test::renderFrame(r, cam, &stats);
  EXPECT_EQ(stats.shared.value("far_triangles", -1.0), 0.0);
  EXPECT_EQ(r.lastFrame().pvl.triangles, 0u);
  EXPECT_GT(stats.shared.value("unfinished_pixels", 0.0), 0.0);  // sky: cast, nothing found
  const Framebuffer ref = test::renderFrame(zbuffer, cam);
  EXPECT_EQ(img.id, ref.id);  // the near pass alone is the z-buffer image
}

// An 8 x 8 x 2 grid of axis-aligned unit cubes seen along -z from a camera on the octree's
// splitting planes: the centre column and row of pixels cast rays with zero x (y) direction
// components lying in splitting planes, between boxes whose faces lie on such planes.
TEST(LzbRenderer, RaysParallelToOctreePlanes) {
  Scene scene;
  scene.source = "cube grid";
  const uint32_t world = scene.addNode("grid"), cube = scene.addNode("cube");
  scene.root = world;
  Mesh& m = scene.nodes[cube].mesh;
  const Rgba8 c = packRgba8(200, 180, 160);
  for (int k = 0; k < 3; ++k)
    for (int side = 0; side < 2; ++side) {
      glm::vec3 q[4];
      for (int i = 0; i < 4; ++i) {
        q[i][k] = float(side);
        q[i][(k + 1) % 3] = float(i == 1 || i == 2);
        q[i][(k + 2) % 3] = float(i >= 2);
      }
      m.add(q[0], q[1], q[2], c);
      m.add(q[0], q[2], q[3], c);
    }
  for (int x = 0; x < 8; ++x)
    for (int y = 0; y < 8; ++y)
      for (int z = 0; z < 2; ++z)
        scene.nodes[world].instances.push_back(
            {cube, glm::translate(glm::dmat4(1.0), glm::dvec3(2 * x, 2 * y, -3 * z))});
  scene.finalize();
  const LzbAccel probe(scene, LzbAccelParams{});
  const glm::dvec3 mid = probe.node(world).octree().bounds().center();
  CameraSpec spec;
  spec.position = {mid.x, mid.y, 30.0};
  spec.lookAt = {mid.x, mid.y, 0.0};
  spec.fovyDegrees = 50.0;
  spec.nearPlane = 1.0;
  spec.farPlane = 100.0;
  const Camera cam(spec, 101, 75);  // odd sizes: the centre rays are exactly axis-parallel
  ASSERT_EQ(cam.pixelDirection(50.5, 10.5).x, 0.0);
  ASSERT_EQ(cam.pixelDirection(10.5, 37.5).y, 0.0);
  ZBufferRenderer zbuffer(scene, test::renderOptions("lzb", 2));
  RaycastRenderer raycast(scene, test::renderOptions("lzb", 2));
  const EmbreeScene embree(scene, {});
  const Framebuffer ref = test::renderFrame(zbuffer, cam);
  const ReferenceFrame exact =
      reduceReference(ref, test::renderFrame(zbuffer, subsampleCamera(cam)));
  const Framebuffer rays = test::renderFrame(raycast, cam);
  for (LzbStage stage : kStages)
    for (FarRays farRays : {FarRays::kEmbree, FarRays::kWalk}) {
      LzbOptions o = test::lzbStageOptions(stage);
      o.planeFraction = 1e-9;  // everything through the rays
      o.farRays = farRays;
      LzbRenderer r(scene, test::renderOptions("lzb", 2), o);
      const Framebuffer img = test::renderFrame(r, cam);
      SCOPED_TRACE(toString(farRays));
      if (stage == LzbStage::kNaive) {
        // Naive is Embree behind the plane, i.e. everywhere here: the ray caster's image. (On the
        // cubes' diagonals Embree and the z-buffer may pick different triangles of a face.)
        EXPECT_EQ(img.id, rays.id);
        continue;
      }
      EXPECT_GE(compare(img, exact).exactIdRateCovered, 0.999) << toString(stage);
      for (int y = 0; y < cam.height(); ++y)
        EXPECT_EQ(img.id[img.index(50, y)], ref.id[ref.index(50, y)])
            << toString(stage) << " " << y;
      const long missing = missingFromPvl(r, embree, cam);
      if (missing >= 0) {
        EXPECT_EQ(missing, 0) << toString(stage);
      }
    }
}

TEST(LzbRenderer, SameImageForAnyRankAndThreadCount) {
  const Scene scene = loadScene("builtin:city?blocks=3", true);
  const Camera cam = pathFrame(scene, 0, 4, 100, 70);  // partial tiles on both edges
  for (ZBuffers z : kZBuffers)
    for (LzbStage stage : {LzbStage::kNaive, LzbStage::kLazy, LzbStage::kFinal}) {
      if (stage == LzbStage::kNaive && z.pvl == ZBufferKind::kGl) continue;  // no PVL
      SCOPED_TRACE(toString(z));
      LzbOptions o = test::lzbStageOptions(stage);
      o.nearRender = z.near;
      o.pvlRender = z.pvl;
      LzbRenderer one(scene, test::renderOptions("lzb", 1), o);
      LzbRenderer two(scene, test::renderOptions("lzb", 2), o);
      const Framebuffer single = test::renderFrame(one, cam);
      const Framebuffer threads = test::renderFrame(two, cam);
      EXPECT_EQ(threads.id, single.id) << toString(stage);
      EXPECT_EQ(threads.depth, single.depth) << toString(stage);
      for (int size : {2, 3})
        for (TileDeal deal : {TileDeal::kInterleaved, TileDeal::kCost}) {
          SCOPED_TRACE(toString(deal));
          LzbOptions dealt = o;
          dealt.tileDeal = deal;
          LzbRenderer ranks(scene, test::renderOptions("lzb", 2), dealt);
          Framebuffer composite(cam.width(), cam.height());
          double rays = 0.0;
          for (int rank = 0; rank < size; ++rank) {
            FrameStats stats;
            compositeNearer(composite, test::renderFrame(ranks, cam, &stats, {rank, size}));
            const double mine = stats.counts.value("rays_cast", 0.0);
            EXPECT_GT(mine, 0.0) << "rank " << rank << " of " << size << " casts a share";
            rays += mine;
            // Every rank computes the plane alike: a shared figure, never in the summed counts.
            EXPECT_TRUE(stats.shared.contains("plane_depth"));
            EXPECT_FALSE(stats.counts.contains("plane_depth"));
          }
          EXPECT_EQ(composite.id, single.id) << toString(stage) << " on " << size << " ranks";
          EXPECT_EQ(composite.depth, single.depth)
              << toString(stage) << " on " << size << " ranks";
          FrameStats alone;
          test::renderFrame(one, cam, &alone);
          EXPECT_EQ(rays, alone.counts.value("rays_cast", -1.0));
        }
    }
}

// Ranks that render a frame at once (the frame driver) split the native near pass by triangle
// ranges and OR their covered pixels mid-frame (WorkShare::orWords); here one thread a rank with
// an in-process OR, on an image whose pixel count is no multiple of 64 (a partial last word).
TEST(LzbRenderer, RanksRenderingAtOnceSplitTheNearPass) {
  const Scene scene = loadScene("builtin:city?blocks=3", true);
  const Camera cam = pathFrame(scene, 0, 4, 100, 70);
  LzbRenderer one(scene, test::renderOptions("lzb", 1), LzbOptions{});
  FrameStats alone;
  const Framebuffer single = test::renderFrame(one, cam, &alone);
  const double nearTotal = alone.shared.value("near_triangles", 0.0);
  ASSERT_GT(nearTotal, 1000.0) << "the view needs a near pass worth splitting";
  EXPECT_EQ(alone.counts.value("near_triangles_drawn", -1.0), nearTotal);
  for (int size : {2, 3}) {
    SCOPED_TRACE(size);
    std::vector<std::unique_ptr<LzbRenderer>> ranks;
    for (int r = 0; r < size; ++r)
      ranks.push_back(
          std::make_unique<LzbRenderer>(scene, test::renderOptions("lzb", 1), LzbOptions{}));
    std::vector<std::vector<uint64_t>> posted(size_t(size), std::vector<uint64_t>{});
    std::barrier sync(size);
    std::vector<Framebuffer> fbs(static_cast<size_t>(size));
    std::vector<FrameStats> stats(static_cast<size_t>(size));
    std::vector<std::thread> threads;
    for (int r = 0; r < size; ++r)
      threads.emplace_back([&, r] {
        WorkShare share{r, size};
        share.orWords = [&, r](std::span<uint64_t> words) {
          posted[size_t(r)].assign(words.begin(), words.end());
          sync.arrive_and_wait();
          for (const std::vector<uint64_t>& other : posted)
            for (size_t w = 0; w < words.size(); ++w) words[w] |= other[w];
          sync.arrive_and_wait();  // every rank has read every post before the next one
        };
        fbs[size_t(r)] = test::renderFrame(*ranks[size_t(r)], cam, &stats[size_t(r)], share);
      });
    for (std::thread& t : threads) t.join();
    Framebuffer composite(cam.width(), cam.height());
    double drawn = 0.0;
    for (int r = 0; r < size; ++r) {
      compositeNearer(composite, fbs[size_t(r)]);
      const double mine = stats[size_t(r)].counts.value("near_triangles_drawn", 0.0);
      EXPECT_GT(mine, 0.0) << "rank " << r;
      EXPECT_LT(mine, nearTotal) << "rank " << r;
      drawn += mine;
      // Every rank knows every unfinished pixel, as the single rank does.
      EXPECT_EQ(stats[size_t(r)].shared.value("unfinished_pixels", -1.0),
                alone.shared.value("unfinished_pixels", -2.0));
    }
    EXPECT_EQ(drawn, nearTotal);
    EXPECT_EQ(composite.id, single.id);
    EXPECT_EQ(composite.depth, single.depth);
  }
}

TEST(LzbRenderer, ReportsStagesAndCounts) {
  const Scene scene = loadScene("builtin:city?blocks=3", true);
  LzbRenderer r(scene, test::renderOptions("lzb", 2), LzbOptions{});
  const Camera cam = pathFrame(scene, 0, 4, 96, 64);
  FrameStats first, second;
  test::renderFrame(r, cam, &first);
  test::renderFrame(r, cam, &second);
  std::vector<std::string> names;
  for (const auto& [name, s] : second.stageSeconds) names.push_back(name);
  const std::vector<std::string> expected = {"cull",        "plane",    "near",      "unfinished",
                                             "oor_project", "pvl_find", "pvl_render"};
  EXPECT_EQ(names, expected);
  const FrameStats setup = r.setupStats();
  ASSERT_EQ(setup.stageSeconds.size(), 1u);
  EXPECT_EQ(setup.stageSeconds[0].first, "build");
  EXPECT_GT(setup.shared.value("octree_nodes", 0.0), 0.0);
  // Figures every rank computes alike are shared; this rank's share of the work is counted.
  for (const char* key :
       {"plane_depth", "plane_reused", "near_triangles", "far_triangles", "unfinished_pixels"})
    EXPECT_TRUE(second.shared.contains(key)) << key;
  for (const char* key : {"rays_cast", "rays_hit", "octree_nodes_visited", "pvl_size"})
    EXPECT_TRUE(second.counts.contains(key)) << key;
  EXPECT_TRUE(second.counts.contains("hit_placements_resolved"));  // Embree's rays (the default)
  EXPECT_FALSE(second.counts.contains("ray_triangle_tests"));
  LzbOptions walking;
  walking.farRays = FarRays::kWalk;
  LzbRenderer walker(scene, test::renderOptions("lzb", 2), walking);
  FrameStats walked;
  test::renderFrame(walker, cam, &walked);
  for (const char* key : {"ray_triangle_tests", "octree_leaves_visited", "instance_walks"})
    EXPECT_TRUE(walked.counts.contains(key)) << key;  // the paper's walk reports its own work
  EXPECT_EQ(first.shared.value("plane_reused", -1.0), 0.0);
  EXPECT_EQ(second.shared.value("plane_reused", -1.0), 1.0);  // same view: the plane is reused
  EXPECT_EQ(second.shared.value("plane_depth", 0.0), first.shared.value("plane_depth", 1.0));
  const double pixels = 96.0 * 64.0;
  EXPECT_GT(second.shared.value("unfinished_pixels", 0.0), 0.0);
  EXPECT_LE(second.counts.value("rays_cast", 0.0), second.shared.value("unfinished_pixels", 0.0));
  EXPECT_LT(second.shared.value("unfinished_pixels", 0.0), pixels);
}

}  // namespace
}  // namespace lzb::localz
