#include "raycast/exact/embree_scene.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>

#include "tests/support/brute_force.hpp"
#include "tests/support/cameras.hpp"
#include "tests/support/scenes.hpp"

namespace lzb {
namespace {

using test::BruteHit;
using test::WorldTriangle;

// The known quad seen from a camera: hit iff the plane point lies in the quad, ID by the side of
// the diagonal, depth the analytic view depth (t of origin + t * dir on z = 0).
void checkQuad(const CameraSpec& spec) {
  const Scene scene = test::quadScene();
  EmbreeScene embree(scene, {});
  const Camera cam(spec, 64, 48);
  int hits = 0;
  for (int y = 0; y < cam.height(); ++y)
    for (int x = 0; x < cam.width(); ++x) {
      const glm::dvec3 d = cam.pixelDirection(x + 0.5, y + 0.5);
      const RayHit h = embree.intersect(cam.position(), d, cam.nearPlane(), cam.farPlane());
      const double t = -cam.position().z / d.z;
      const glm::dvec3 p = cam.position() + t * d;
      const double inside =
          std::min({1.0 - std::abs(p.x), 1.0 - std::abs(p.y), std::abs(p.x - p.y)});
      if (std::abs(inside) < 1e-5) continue;  // on an edge: either answer is right
      if (std::abs(p.x) > 1.0 || std::abs(p.y) > 1.0) {
        EXPECT_FALSE(h.hit()) << x << "," << y;
        continue;
      }
      ASSERT_TRUE(h.hit()) << x << "," << y;
      EXPECT_EQ(h.id, p.y < p.x ? 0u : 1u) << x << "," << y;
      EXPECT_NEAR(h.t, t, 2e-7 * t) << x << "," << y;
      ++hits;
    }
  EXPECT_GT(hits, 500);
}

TEST(EmbreeScene, KnownQuadHeadOn) {
  CameraSpec spec;
  spec.position = {0.1, -0.05, 2.0};
  spec.lookAt = {0.1, -0.05, 0.0};
  spec.fovyDegrees = 60.0;
  spec.nearPlane = 0.5;
  spec.farPlane = 10.0;
  checkQuad(spec);
}

TEST(EmbreeScene, KnownQuadOblique) {
  CameraSpec spec;
  spec.position = {0.4, -2.5, 1.5};
  spec.lookAt = {0.1, 0.2, 0.0};
  spec.up = {0, 0, 1};
  spec.nearPlane = 0.5;
  spec.farPlane = 10.0;
  checkQuad(spec);
}

TEST(EmbreeScene, NearAndFarPlanesClipByDepth) {
  const Scene scene = test::quadScene();
  EmbreeScene embree(scene, {});
  const glm::dvec3 o(0.2, 0.3, 2.0), d(0.1, 0.05, -1.0);  // depth of the quad: exactly 2
  EXPECT_TRUE(embree.intersect(o, d, 1.999, 2.001).hit());
  EXPECT_FALSE(embree.intersect(o, d, 2.001, 5.0).hit());
  EXPECT_FALSE(embree.intersect(o, d, 0.5, 1.999).hit());
  EXPECT_FLOAT_EQ(embree.intersect(o, d, 0.5, 5.0).t, 2.0f);
}

// Every hit names the triangle a double-precision brute force over the flattened scene finds;
// where they differ the ray is a near tie or grazes an edge.
void compareWithBruteForce(const Scene& scene, const EmbreeSceneOptions& options, int samples) {
  const std::vector<WorldTriangle> tris = test::worldTriangles(scene);
  ASSERT_EQ(tris.size(), scene.expandedTriangles());
  EmbreeScene embree(scene, options);
  const Camera cam = test::closeCamera(scene, 320, 240);
  std::mt19937_64 rng(11);
  // The middle of the image, where the triangles are (and gaps between them).
  std::uniform_real_distribution<double> px(0.25 * cam.width(), 0.75 * cam.width()),
      py(0.25 * cam.height(), 0.75 * cam.height());
  int hits = 0, differ = 0;
  for (int i = 0; i < samples; ++i) {
    const glm::dvec3 d = cam.pixelDirection(px(rng), py(rng));
    const RayHit h = embree.intersect(cam.position(), d, cam.nearPlane(), cam.farPlane());
    const BruteHit b = test::bruteForce(tris, cam.position(), d, cam.nearPlane(), cam.farPlane());
    if (h.hit()) {
      // The ID resolves to a stored triangle, placed where the brute force put it.
      const auto ref = scene.resolve(h.id);
      ASSERT_TRUE(ref.has_value());
      const Mesh& mesh = scene.nodes[ref->node].mesh;
      const glm::dvec3 v0(ref->transform *
                          glm::dvec4(glm::dvec3(mesh.vertex(ref->triangle, 0)), 1));
      const WorldTriangle* tri = test::findTriangle(tris, h.id);
      ASSERT_NE(tri, nullptr);
      EXPECT_EQ(v0, tri->a);
      ++hits;
    }
    if (h.id == b.id) {
      if (h.hit()) {
        EXPECT_NEAR(h.t, b.t, 1e-5 * b.t);
      }
      continue;
    }
    ++differ;
    if (h.hit() && b.id != kNoId) {
      const BruteHit mine =
          test::mollerTrumbore(*test::findTriangle(tris, h.id), cam.position(), d);
      EXPECT_NEAR(mine.t, b.t, 1e-5 * b.t) << "not a tie at sample " << i;
      EXPECT_GT(mine.margin, -1e-5) << "ray passes outside the reported triangle, sample " << i;
    } else {
      EXPECT_LT(std::abs(b.margin), 1e-5) << "missed a clear hit at sample " << i;
    }
  }
  EXPECT_GT(hits, samples / 4);
  EXPECT_LE(differ, samples / 100);
}

TEST(EmbreeScene, NestedInstancesMatchBruteForce) {
  const Scene scene = test::nestedScene();
  EmbreeScene embree(scene, {});
  EXPECT_EQ(embree.buildStats().levels, 4u);  // one per node, however often instanced
  EXPECT_EQ(embree.buildStats().instances, 10u);
  EXPECT_EQ(embree.buildStats().triangles, scene.uniqueTriangles());
  compareWithBruteForce(scene, {}, 400);
}

TEST(EmbreeScene, NestedInstancesMatchBruteForceMediumQuality) {
  EmbreeSceneOptions options;
  options.highQuality = false;
  compareWithBruteForce(test::nestedScene(3), options, 400);
}

// Packets (down through the instance levels) give exactly the single-ray hits.
void expectBatchEqualsSingle(const Scene& scene, const Camera& cam) {
  EmbreeScene embree(scene, {});
  std::vector<Ray> rays;
  for (int y = 0; y < cam.height(); ++y)
    for (int x = 0; x < cam.width(); ++x)
      rays.push_back(
          {cam.position(), cam.pixelDirection(x + 0.5, y + 0.5), cam.nearPlane(), cam.farPlane()});
  rays.pop_back();  // a partial last packet
  std::vector<RayHit> hits(rays.size());
  embree.intersect(rays, hits);
  int covered = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const RayHit one = embree.intersect(rays[i].origin, rays[i].dir, rays[i].tnear, rays[i].tfar);
    EXPECT_EQ(hits[i].id, one.id) << i;
    if (one.hit()) {
      EXPECT_EQ(hits[i].t, one.t) << i;
    }
    covered += one.hit();
  }
  EXPECT_GT(covered, int(rays.size()) / 5);
}

TEST(EmbreeScene, BatchEqualsSingleRays) {
  const Scene scene = test::nestedScene();
  expectBatchEqualsSingle(scene, test::closeCamera(scene, 40, 30));
}

// The nested scene seen through `cam`, and again 1e7 away (alone, and beside a copy at the
// origin, which makes the root frame 1e7 wide): the same IDs and depths.
void expectSameFarAway(const Scene& near, const Camera& cam, const glm::dvec3& shift,
                       bool withCopyAtOrigin) {
  Scene far = test::translated(near, shift);
  if (withCopyAtOrigin) {
    far.nodes[far.root].instances.push_back({near.root, glm::dmat4(1.0)});
    far.finalize();
  }
  EmbreeScene a(near, {}), b(far, {});
  CameraSpec spec = cam.spec();
  spec.position += shift;
  spec.lookAt += shift;
  const Camera camFar(spec, cam.width(), cam.height());
  int differ = 0, covered = 0;
  for (int y = 0; y < cam.height(); ++y)
    for (int x = 0; x < cam.width(); ++x) {
      const RayHit ha = a.intersect(cam.position(), cam.pixelDirection(x + 0.5, y + 0.5),
                                    cam.nearPlane(), cam.farPlane());
      const RayHit hb = b.intersect(camFar.position(), camFar.pixelDirection(x + 0.5, y + 0.5),
                                    camFar.nearPlane(), camFar.farPlane());
      covered += ha.hit();
      if (ha.id != hb.id) {
        ++differ;
        continue;
      }
      if (ha.hit()) {
        EXPECT_NEAR(hb.t, ha.t, 1e-5 * ha.t);
      }
    }
  EXPECT_GT(covered, cam.width() * cam.height() / 10);
  EXPECT_LE(differ, 2);
}

TEST(EmbreeScene, FarFromOriginMatchesOrigin) {
  const Scene near = test::nestedScene();
  CameraSpec spec = test::closeSpec(near);
  spec.position = spec.lookAt + 0.3 * (spec.position - spec.lookAt);  // closer still
  spec.nearPlane = 1e-3;
  const Camera cam(spec, 160, 120);
  expectSameFarAway(near, cam, {1.0e7, -2.5e7, 1.0e7}, false);
  expectSameFarAway(near, cam, {1.0e7, -2.5e7, 1.0e7}, true);
  expectSameFarAway(near, cam, {-3.0e7, 0.0, 0.0}, true);
}

TEST(EmbreeScene, RootMeshFarFromOriginMatchesBruteForce) {
  // Triangles stored in float at 1e7 in the root frame (no instance): recentred before Embree.
  Scene scene;
  scene.addNode("far mesh");
  std::mt19937_64 rng(5);
  Mesh local;
  test::addRandomTriangles(local, 200, 0.5, rng);
  const glm::vec3 at(1.0e7f, 2.0e7f, -1.0e7f);
  for (size_t t = 0; t < local.size(); ++t)
    scene.nodes[0].mesh.add(at + 4.0f * local.vertex(t, 0), at + 4.0f * local.vertex(t, 1),
                            at + 4.0f * local.vertex(t, 2), local.color(t));
  scene.finalize();
  compareWithBruteForce(scene, {}, 300);
}

TEST(EmbreeScene, RaysThroughSharedEdgesDoNotLeak) {
  const Scene scene = test::quadScene();
  EmbreeScene embree(scene, {});
  // Dyadic directions: in float the rays pass exactly through the diagonal (the last one lies in
  // the plane x = y that holds the edge, the others are axis-parallel or oblique).
  const glm::dvec3 dirs[] = {{0, 0, -1}, {0.25, -0.125, -1}, {1.0 / 1024, 0, -1}, {0.5, 0.5, -1}};
  for (int k = -63; k <= 63; ++k) {
    const glm::dvec3 p(k / 64.0, k / 64.0, 0.0);  // exactly on the shared diagonal
    for (const glm::dvec3& d : dirs) {
      const glm::dvec3 o = p - 2.0 * d;
      const RayHit h = embree.intersect(o, d, 0.1, 10.0);
      ASSERT_TRUE(h.hit()) << "leak at k=" << k << " dir " << d.x << "," << d.y;
      EXPECT_LE(h.id, 1u);
      EXPECT_NEAR(h.t, 2.0, 1e-6);
    }
  }
}

TEST(EmbreeScene, RaysThroughASharedVertexDoNotLeak) {
  // A fan of 8 triangles around the origin; rays through the centre from many directions.
  Scene scene;
  scene.addNode("fan");
  for (int i = 0; i < 8; ++i) {
    const double a0 = i * 0.7853981633974483, a1 = (i + 1) * 0.7853981633974483;
    scene.nodes[0].mesh.add({0, 0, 0}, {float(std::cos(a0)), float(std::sin(a0)), 0},
                            {float(std::cos(a1)), float(std::sin(a1)), 0}, test::grey(50));
  }
  scene.finalize();
  EmbreeScene embree(scene, {});
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const glm::dvec3 d(u(rng), u(rng), -1.0);
    const RayHit h = embree.intersect(-d, d, 0.0, 3.0);
    ASSERT_TRUE(h.hit()) << "leak through the vertex, ray " << i;
    EXPECT_LT(h.id, 8u);
  }
}

// The hits of `rays`, one at a time or as packets.
std::vector<RayHit> castAll(const EmbreeScene& embree, const std::vector<Ray>& rays, bool packets) {
  std::vector<RayHit> hits(rays.size());
  if (packets)
    embree.intersect(rays, hits);
  else
    for (size_t i = 0; i < rays.size(); ++i)
      hits[i] = embree.intersect(rays[i].origin, rays[i].dir, rays[i].tnear, rays[i].tfar);
  return hits;
}

// Rays down onto z = 0 over [-0.9, 0.9]^2 (dyadic origins: every copy of a triangle gives them
// the same t), one at a time and as packets: the IDs found.
constexpr int kSide = 31;
std::vector<uint64_t> idsOfRaysDown(const EmbreeScene& embree, bool packets) {
  std::vector<Ray> rays;
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x)
      rays.push_back({{(x - 15) / 16.0, (y - 15) / 16.0, 2.0}, {0.0, 0.0, -1.0}, 0.1, 10.0});
  std::vector<uint64_t> ids;
  for (const RayHit& h : castAll(embree, rays, packets)) {
    EXPECT_FLOAT_EQ(h.t, 2.0f);  // within 4 ulps: Embree's reciprocal is approximate
    ids.push_back(h.id);
  }
  return ids;
}

// The least ID of the quad whose triangle `first` (below the diagonal) or first + 1 holds ray i;
// on the diagonal both hold it.
uint64_t quadTriangle(size_t i, uint64_t first) {
  return i / kSide <= i % kSide ? first : first + 1;
}

// The depth composite keeps the least (depth, ID); Embree alone keeps whichever of equal-t hits
// its traversal meets last. 300 copies of one quad (IDs 40..639, after 40 random triangles that
// spread the BVH) fill many leaves with one box: every ray must name the first copy.
TEST(EmbreeScene, TiesAtEqualDepthGoToTheLeastId) {
  Scene scene;
  scene.addNode("copies");
  std::mt19937_64 rng(3);
  Mesh& mesh = scene.nodes[0].mesh;
  test::addRandomTriangles(mesh, 40, 0.2, rng);
  for (glm::vec3& p : mesh.positions) p.z -= 3.0f;  // behind z = 0: no ray meets them first
  for (int copy = 0; copy < 300; ++copy) test::addQuad(mesh);
  scene.finalize();
  for (bool packets : {false, true}) {
    const std::vector<uint64_t> ids = idsOfRaysDown(EmbreeScene(scene, {}), packets);
    for (size_t i = 0; i < ids.size(); ++i) EXPECT_EQ(ids[i], quadTriangle(i, 40)) << "ray " << i;
  }
}

// The same through instances: the root's own quad, then two instances of a node of 50 quads,
// all in one place; the root's triangles come first in the expanded IDs.
TEST(EmbreeScene, TiesAcrossInstancesGoToTheLeastId) {
  Scene scene;
  scene.root = scene.addNode("root");
  const uint32_t copies = scene.addNode("copies");
  for (int copy = 0; copy < 50; ++copy) test::addQuad(scene.nodes[copies].mesh);
  scene.nodes[scene.root].instances.push_back({copies, glm::dmat4(1.0)});
  scene.nodes[scene.root].instances.push_back({copies, glm::dmat4(1.0)});
  scene.finalize();
  for (bool packets : {false, true}) {
    const std::vector<uint64_t> ids = idsOfRaysDown(EmbreeScene(scene, {}), packets);
    for (size_t i = 0; i < ids.size(); ++i) EXPECT_EQ(ids[i], quadTriangle(i, 0)) << "ray " << i;
  }
  test::addQuad(scene.nodes[scene.root].mesh);
  scene.finalize();
  for (bool packets : {false, true}) {
    const std::vector<uint64_t> ids = idsOfRaysDown(EmbreeScene(scene, {}), packets);
    for (size_t i = 0; i < ids.size(); ++i) EXPECT_EQ(ids[i], quadTriangle(i, 0)) << "ray " << i;
  }
}

// Rays from z = 2 down to z = 0 through the points (x, y) / 32, |x|, |y| <= 60: grid vertices,
// edge midpoints and cell centres of a grid of cell 1/16; dyadic, so exact in float, and oblique
// (a ray with a zero direction component on a box face falls out of Embree's slab test). The
// hits, one ray at a time or as packets.
std::vector<glm::dvec2> gridPoints() {
  std::vector<glm::dvec2> points;
  for (int y = -60; y <= 60; ++y)
    for (int x = -60; x <= 60; ++x) points.push_back(glm::dvec2(x, y) / 32.0);
  return points;
}

std::vector<RayHit> raysDown(const EmbreeScene& embree, const std::vector<glm::dvec2>& points,
                             bool packets) {
  std::vector<Ray> rays;
  const glm::dvec3 dir(1.0 / 64.0, -1.0 / 32.0, -1.0);
  for (const glm::dvec2& p : points)
    rays.push_back({glm::dvec3(p, 0.0) - 2.0 * dir, dir, 0.1, 10.0});
  return castAll(embree, rays, packets);
}

// The least ID of the triangles (in z = 0) holding p, edges and corners included; kNoId if none.
uint64_t leastHolding(const std::vector<WorldTriangle>& tris, const glm::dvec2& p) {
  const auto side = [&](const glm::dvec3& a, const glm::dvec3& b) {
    return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);  // exact: dyadic inputs
  };
  uint64_t least = kNoId;
  for (const WorldTriangle& t : tris) {
    const double e0 = side(t.a, t.b), e1 = side(t.b, t.c), e2 = side(t.c, t.a);
    if ((e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0))
      least = std::min(least, t.id);
  }
  return least;
}

// Every ray names the least ID of the triangles holding its point: at a shared edge or vertex
// (equal t: every triangle lies in z = 0 with the same area, so the same rounding) the least of
// them, as the depth composite would keep; Embree alone keeps whichever it met last.
void expectLeastAtSharedEdges(const Scene& scene) {
  const std::vector<WorldTriangle> tris = test::worldTriangles(scene);
  const std::vector<glm::dvec2> points = gridPoints();
  const EmbreeScene embree(scene, {});
  for (bool packets : {false, true}) {
    const std::vector<RayHit> hits = raysDown(embree, points, packets);
    int shared = 0;
    for (size_t i = 0; i < points.size(); ++i) {
      const uint64_t least = leastHolding(tris, points[i]);
      if (least == kNoId) continue;
      EXPECT_FLOAT_EQ(hits[i].t, 2.0f) << i;
      EXPECT_EQ(hits[i].id, least)
          << "ray through (" << points[i].x << ", " << points[i].y << "), packets " << packets;
      shared += (i % 2 == 0);
    }
    EXPECT_GT(shared, 1000);
  }
}

// A grid of 32 x 32 cells of 1/16 (two triangles each, 2,048), in shuffled ID order so that
// neighbours sit in different leaves: the rays through its vertices meet six triangles each.
TEST(EmbreeScene, TiesAtSharedEdgesAndVerticesGoToTheLeastId) {
  std::vector<std::array<glm::vec3, 3>> cells;
  for (int j = -16; j < 16; ++j)
    for (int i = -16; i < 16; ++i) {
      const glm::vec3 a(i / 16.0f, j / 16.0f, 0), b((i + 1) / 16.0f, j / 16.0f, 0),
          c((i + 1) / 16.0f, (j + 1) / 16.0f, 0), d(i / 16.0f, (j + 1) / 16.0f, 0);
      cells.push_back({a, b, c});
      cells.push_back({a, c, d});
    }
  std::shuffle(cells.begin(), cells.end(), std::mt19937_64(4));
  Scene scene;
  scene.addNode("grid");
  for (const auto& t : cells) scene.nodes[0].mesh.add(t[0], t[1], t[2], test::grey(90));
  scene.finalize();
  expectLeastAtSharedEdges(scene);
}

// 256 instances of the quad [-1, 1]^2 shrunk to 1/4 on a side, tiling [-2, 2]^2 in shuffled
// order: at the edges and corners they share, the least expanded ID, whichever instance Embree
// meets last.
TEST(EmbreeScene, TiesAtEdgesSharedByInstancesGoToTheLeastId) {
  std::vector<glm::dvec3> centres;
  for (int j = -8; j < 8; ++j)
    for (int i = -8; i < 8; ++i) centres.push_back(glm::dvec3(2 * i + 1, 2 * j + 1, 0) / 8.0);
  std::shuffle(centres.begin(), centres.end(), std::mt19937_64(6));
  Scene scene;
  scene.root = scene.addNode("root");
  const uint32_t quad = scene.addNode("quad");
  test::addQuad(scene.nodes[quad].mesh);
  for (const glm::dvec3& c : centres)
    scene.nodes[scene.root].instances.push_back(
        {quad, glm::scale(glm::translate(glm::dmat4(1.0), c), glm::dvec3(0.125, 0.125, 1.0))});
  scene.finalize();
  expectLeastAtSharedEdges(scene);
}

// Embree counts what it allocates (held, and at most while building); compact leaves (indices
// into the shared vertices, still the robust test) hold fewer bytes and give the same IDs, one
// ray at a time and as packets; t is computed otherwise (a quarter of these hits differ, by up
// to ~10 ulps, on this soup's oblique triangles; none over 8 frames of the 10^7 landscape).
TEST(EmbreeScene, CompactLeavesHoldLessAndHitAlike) {
  const Scene scene = test::soupScene(20000, 0.05, 8);
  EmbreeSceneOptions compact;
  compact.compactLeaves = true;
  const EmbreeScene fast(scene, {}), small(scene, compact);
  const EmbreeBuildStats &f = fast.buildStats(), &c = small.buildStats();
  EXPECT_GT(f.bytes, 20000u * 36);  // the leaves hold three vertices a triangle
  EXPECT_GE(f.peakBytes, f.bytes);
  EXPECT_LT(c.bytes, f.bytes * 3 / 4);
  const Camera cam(frameBounds(scene.bounds()), 64, 48);
  std::vector<Ray> rays;
  for (int y = 0; y < cam.height(); ++y)
    for (int x = 0; x < cam.width(); ++x)
      rays.push_back(
          {cam.position(), cam.pixelDirection(x + 0.5, y + 0.5), cam.nearPlane(), cam.farPlane()});
  for (bool packets : {false, true}) {
    const std::vector<RayHit> a = castAll(fast, rays, packets), b = castAll(small, rays, packets);
    int covered = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
      covered += a[i].hit();
      EXPECT_EQ(a[i].id, b[i].id) << i;
      if (a[i].hit()) {
        EXPECT_NEAR(b[i].t, a[i].t, 1e-5 * a[i].t) << i;
      }
    }
    EXPECT_GT(covered, int(rays.size()) / 5);
  }
}

TEST(EmbreeScene, EmptySceneMissesEverything) {
  Scene scene;
  scene.addNode("empty");
  const uint32_t child = scene.addNode("empty child");
  scene.nodes[0].instances.push_back({child, glm::dmat4(1.0)});
  scene.finalize();
  EmbreeScene embree(scene, {});
  EXPECT_FALSE(embree.intersect({0, 0, 5}, {0, 0, -1}, 0.1, 100.0).hit());
}

TEST(EmbreeScene, SingularInstancesAreSkipped) {
  Scene scene = test::quadScene();
  const uint32_t root = scene.addNode("root");
  scene.nodes[root].instances.push_back({0, glm::dmat4(1.0)});
  scene.nodes[root].instances.push_back({0, glm::dmat4(0.0)});
  scene.root = root;
  scene.finalize();
  EmbreeScene embree(scene, {});
  EXPECT_EQ(embree.buildStats().skippedInstances, 1u);
  EXPECT_EQ(embree.intersect({0.5, -0.5, 1}, {0, 0, -1}, 0.1, 10.0).id, 0u);
}

}  // namespace
}  // namespace lzb
