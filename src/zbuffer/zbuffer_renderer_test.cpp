#include "src/zbuffer/zbuffer_renderer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <optional>
#include <random>
#include <set>

#include "src/core/shading.hpp"
#include "tests/support/cameras.hpp"
#include "tests/support/render.hpp"

namespace lzb {
namespace {

const Rgba8 kGrey = packRgba8(180, 180, 180);

// Where the ray through a pixel centre meets a triangle's plane: t (== view depth, as the ray's
// direction has forward component 1) and the smallest barycentric (< 0: outside).
struct PlaneHit {
  double t, minBary;
};

PlaneHit hitTriangle(const Camera& camera, int x, int y, const glm::dvec3& a, const glm::dvec3& b,
                     const glm::dvec3& c) {
  const glm::dvec3 o = camera.position(), d = camera.pixelDirection(x + 0.5, y + 0.5);
  const glm::dvec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
  const double inv = 1.0 / glm::dot(e1, p);
  const glm::dvec3 s = o - a, q = glm::cross(s, e1);
  const double u = glm::dot(s, p) * inv, v = glm::dot(d, q) * inv;
  return {glm::dot(e2, q) * inv, std::min({u, v, 1.0 - u - v})};
}

PlaneHit hitId(const Scene& scene, const Camera& camera, int x, int y, uint64_t id) {
  const auto ref = scene.resolve(id);
  EXPECT_TRUE(ref.has_value()) << id;
  const Mesh& m = scene.nodes[ref->node].mesh;
  auto world = [&](int k) {
    return glm::dvec3(ref->transform * glm::dvec4(glm::dvec3(m.vertex(ref->triangle, k)), 1.0));
  };
  return hitTriangle(camera, x, y, world(0), world(1), world(2));
}

// Every covered pixel's centre lies on the triangle its ID names, at the stored depth.
void expectPixelsShowTheirTriangles(const Scene& scene, const Camera& camera,
                                    const Framebuffer& fb) {
  for (int y = 0; y < fb.height; ++y)
    for (int x = 0; x < fb.width; ++x) {
      const size_t i = fb.index(x, y);
      if (!fb.covered(i)) {
        EXPECT_EQ(fb.depth[i], kEmptyDepth);
        continue;
      }
      const PlaneHit h = hitId(scene, camera, x, y, fb.id[i]);
      EXPECT_GT(h.minBary, -1e-3) << "pixel " << x << "," << y << " id " << fb.id[i];
      EXPECT_NEAR(fb.depth[i], h.t, 1e-5 * h.t) << "pixel " << x << "," << y;
    }
}

void addQuad(Mesh& m, double halfSize, double z, Rgba8 color = kGrey) {
  const float s = float(halfSize), zf = float(z);
  ASSERT_TRUE(m.add({-s, -s, zf}, {s, -s, zf}, {s, s, zf}, color));
  ASSERT_TRUE(m.add({-s, -s, zf}, {s, s, zf}, {-s, s, zf}, color));
}

// count triangles around the origin in a cube of side `extent`, each with edges about `size`.
void addSoup(Mesh& m, size_t count, float extent, float size, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> pos(-0.5f * extent, 0.5f * extent), off(-size, size);
  std::uniform_int_distribution<int> channel(40, 255);
  while (m.size() < count) {
    const glm::vec3 c(pos(rng), pos(rng), pos(rng));
    m.add(c + glm::vec3(off(rng), off(rng), off(rng)), c + glm::vec3(off(rng), off(rng), off(rng)),
          c + glm::vec3(off(rng), off(rng), off(rng)),
          packRgba8(uint8_t(channel(rng)), uint8_t(channel(rng)), uint8_t(channel(rng))));
  }
}

TEST(ZBufferRenderer, SingleTriangleHasItsIdAndAnalyticDepth) {
  Scene scene;
  scene.addNode("tri");
  // Tilted, so depth varies across the triangle and perspective-correctness is tested.
  const glm::dvec3 a(-2.0, -1.5, -4.0), b(2.5, -1.0, -7.0), c(0.3, 2.0, -5.0);
  ASSERT_TRUE(scene.nodes[0].mesh.add(glm::vec3(a), glm::vec3(b), glm::vec3(c), kGrey));
  scene.finalize();
  const Camera camera = test::lookAtCamera({0.4, 0.3, 1.0}, {0.0, 0.0, -5.0}, 0.5, 50.0, 80, 60);
  const Framebuffer fb = test::zbufferFrame(scene, camera, {}, /*shade=*/true);
  int inside = 0, outside = 0;
  const Rgba8 shaded = shadeTriangle(scene, 0, 0, glm::dmat4(1.0), camera.position());
  for (int y = 0; y < fb.height; ++y)
    for (int x = 0; x < fb.width; ++x) {
      const size_t i = fb.index(x, y);
      const PlaneHit h = hitTriangle(camera, x, y, a, b, c);
      if (h.minBary > 1e-3) {
        ++inside;
        ASSERT_EQ(fb.id[i], 0u) << x << "," << y;
        EXPECT_NEAR(fb.depth[i], h.t, 1e-5 * h.t) << x << "," << y;
        EXPECT_EQ(fb.color[i], shaded);
      } else if (h.minBary < -1e-3) {
        ++outside;
        EXPECT_EQ(fb.id[i], kNoId) << x << "," << y;
        EXPECT_EQ(fb.depth[i], kEmptyDepth);
        EXPECT_EQ(fb.color[i], kBackground);
      }
    }
  EXPECT_GT(inside, 300);
  EXPECT_GT(outside, 300);
  // Row 0 is the top: the apex c (highest y) is near the top of the image.
  const glm::dvec3 apex = camera.project(c);
  EXPECT_LT(apex.y, 0.5 * fb.height);
}

TEST(ZBufferRenderer, NearerQuadWinsInEitherDrawOrder) {
  for (bool nearFirst : {false, true}) {
    Scene scene;
    scene.addNode("quads");
    Mesh& m = scene.nodes[0].mesh;
    addQuad(m, nearFirst ? 0.5 : 2.0, nearFirst ? -4.0 : -5.0);
    addQuad(m, nearFirst ? 2.0 : 0.5, nearFirst ? -5.0 : -4.0);
    scene.finalize();
    const Camera camera = test::lookAtCamera({0.0, 0.0, 0.0}, {0.0, 0.0, -1.0}, 0.1, 100.0, 80, 60);
    const Framebuffer fb = test::zbufferFrame(scene, camera, {}, /*shade=*/true);
    const std::set<uint64_t> nearIds =
        nearFirst ? std::set<uint64_t>{0, 1} : std::set<uint64_t>{2, 3};
    const size_t centre = fb.index(fb.width / 2, fb.height / 2);
    EXPECT_TRUE(nearIds.count(fb.id[centre])) << nearFirst;
    EXPECT_NEAR(fb.depth[centre], 4.0, 4e-5);
    const size_t corner = fb.index(fb.width / 2, 5);  // on the big quad only
    EXPECT_FALSE(nearIds.count(fb.id[corner]));
    EXPECT_NEAR(fb.depth[corner], 5.0, 5e-5);
    expectPixelsShowTheirTriangles(scene, camera, fb);
  }
}

// A small object placed by an instance transform at `offset`, seen from near it.
Scene placedObject(const glm::dvec3& offset) {
  Scene scene;
  const uint32_t root = scene.addNode("root"), object = scene.addNode("object");
  addSoup(scene.nodes[object].mesh, 400, 2.0f, 0.3f, 7);
  scene.nodes[root].instances.push_back(
      {object,
       glm::rotate(glm::translate(glm::dmat4(1.0), offset), 0.4, glm::dvec3(0.0, 1.0, 0.0))});
  scene.root = root;
  scene.finalize();
  return scene;
}

TEST(ZBufferRenderer, FarFromTheOriginMatchesTheOrigin) {
  const glm::dvec3 far(1e7, -1e7, 1e7);  // float spacing there is 1: a float pipeline would fail
  const glm::dvec3 eye(0.5, 1.25, 3.5), at(0.0, 0.25, 0.0);
  const Scene atOrigin = placedObject(glm::dvec3(0.0)), displaced = placedObject(far);
  const Camera c0 = test::lookAtCamera(eye, at, 0.1, 20.0, 96, 72);
  const Camera c1 = test::lookAtCamera(far + eye, far + at, 0.1, 20.0, 96, 72);
  const Framebuffer a = test::zbufferFrame(atOrigin, c0, {}, /*shade=*/true),
                    b = test::zbufferFrame(displaced, c1, {}, /*shade=*/true);
  EXPECT_GT(a.coveredCount(), a.size() / 4);
  size_t differentIds = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    differentIds += a.id[i] != b.id[i];
    if (a.covered(i)) {
      EXPECT_NEAR(b.depth[i], a.depth[i], 1e-6 * a.depth[i]) << i;
    }
  }
  EXPECT_EQ(differentIds, 0u);
  expectPixelsShowTheirTriangles(displaced, c1, b);
}

TEST(ZBufferRenderer, InstancesGetExpandedIdsInSceneOrder) {
  Scene scene;
  const uint32_t root = scene.addNode("root"), quad = scene.addNode("quad");
  ASSERT_TRUE(
      scene.nodes[root].mesh.add({-3, 1.5f, -6}, {-1.5f, 1.5f, -6}, {-2.2f, 2.5f, -6}, kGrey));
  addQuad(scene.nodes[quad].mesh, 1.0, 0.0);
  const glm::dmat4 left = glm::translate(glm::dmat4(1.0), {-1.5, -0.5, -6.0});
  const glm::dmat4 right =
      glm::rotate(glm::translate(glm::dmat4(1.0), {1.5, -0.5, -7.0}), 0.5, glm::dvec3(0, 1, 0));
  scene.nodes[root].instances = {{quad, left}, {quad, right}};
  scene.root = root;
  scene.finalize();
  ASSERT_EQ(scene.expandedTriangles(), 5u);
  const Camera camera = test::lookAtCamera({0.0, 0.0, 0.0}, {0.0, 0.0, -1.0}, 0.1, 100.0, 80, 60);
  const Framebuffer fb = test::zbufferFrame(scene, camera, {}, /*shade=*/true);
  std::set<uint64_t> seen;
  for (uint64_t id : fb.id)
    if (id != kNoId) seen.insert(id);
  EXPECT_EQ(seen, (std::set<uint64_t>{0, 1, 2, 3, 4}));
  expectPixelsShowTheirTriangles(scene, camera, fb);
  // The pixel over each instance's centre names a triangle of that instance.
  for (const auto& [place, firstId] : {std::pair{left, 1u}, std::pair{right, 3u}}) {
    const glm::dvec3 p = camera.project(glm::dvec3(place * glm::dvec4(0, 0, 0, 1)));
    const uint64_t id = fb.id[fb.index(int(p.x), int(p.y))];
    EXPECT_TRUE(id == firstId || id == firstId + 1) << id;
    const auto ref = scene.resolve(id);
    ASSERT_TRUE(ref);
    EXPECT_EQ(ref->node, quad);
    EXPECT_EQ(ref->transform, place);
  }
}

// A soup scene of several instances, two of them coincident (exact depth ties across ranks).
Scene sharedScene() {
  Scene scene;
  const uint32_t root = scene.addNode("root"), soup = scene.addNode("soup");
  addSoup(scene.nodes[root].mesh, 50, 3.0f, 0.6f, 11);
  addSoup(scene.nodes[soup].mesh, 300, 2.0f, 0.5f, 12);
  const glm::dmat4 twice = glm::rotate(glm::dmat4(1.0), 0.7, glm::dvec3(0.2, 1.0, 0.1));
  scene.nodes[root].instances = {{soup, glm::translate(glm::dmat4(1.0), {-0.8, 0.2, 0.3})},
                                 {soup, twice},
                                 {soup, twice},
                                 {soup, glm::translate(glm::dmat4(1.0), {0.9, -0.3, -0.4})}};
  scene.root = root;
  scene.finalize();
  return scene;
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

TEST(ZBufferRenderer, RankSharesCompositeToTheSingleRender) {
  const Scene scene = sharedScene();
  const Camera camera = test::lookAtCamera({2.5, 2.0, 4.0}, {0.0, 0.0, 0.0}, 0.5, 20.0, 120, 90);
  FrameStats whole;
  const Framebuffer single = test::zbufferFrame(scene, camera, {}, /*shade=*/true, &whole);
  EXPECT_GT(single.coveredCount(), single.size() / 3);
  for (int size : {2, 3}) {
    Framebuffer composite(camera.width(), camera.height());
    double drawn = 0.0;
    for (int rank = 0; rank < size; ++rank) {
      FrameStats stats;
      const Framebuffer part =
          test::zbufferFrame(scene, camera, {}, /*shade=*/true, &stats, {rank, size});
      EXPECT_LT(part.coveredCount(), single.coveredCount());  // the work really is split
      drawn += stats.counts["triangles_drawn"].get<double>();
      compositeNearer(composite, part);
    }
    EXPECT_EQ(drawn, whole.counts["triangles_drawn"].get<double>());
    EXPECT_TRUE(sameBits(composite.depth, single.depth)) << size;
    EXPECT_EQ(composite.id, single.id) << size;
    EXPECT_EQ(composite.color, single.color) << size;
  }
  // The coincident instances tie exactly; the smaller ID (the first of the two) is kept.
  const uint64_t firstTwin = scene.childOffset(scene.root, 1),
                 secondTwin = scene.childOffset(scene.root, 2);
  size_t fromFirst = 0;
  for (uint64_t id : single.id) {
    EXPECT_FALSE(id >= secondTwin && id < secondTwin + 300) << id;
    fromFirst += id >= firstTwin && id < secondTwin;
  }
  EXPECT_GT(fromFirst, 100u);
}

TEST(ZBufferRenderer, ResolvesSurfacesATenthOfAPercentApartOverAHugeDepthRange) {
  for (bool farFirst : {true, false}) {
    Scene scene;
    scene.addNode("planes");
    Mesh& m = scene.nodes[0].mesh;
    const double nearDepth = 1e4, farDepth = 1e4 * 1.001;
    addQuad(m, farFirst ? 1e4 : 2e3, farFirst ? -farDepth : -nearDepth);
    addQuad(m, farFirst ? 2e3 : 1e4, farFirst ? -nearDepth : -farDepth);
    scene.finalize();
    const Camera camera = test::lookAtCamera({0.0, 0.0, 0.0}, {0.0, 0.0, -1.0}, 1e-3, 1e6, 80, 60);
    const Framebuffer fb = test::zbufferFrame(scene, camera, {}, /*shade=*/true);
    const uint64_t nearQuad = farFirst ? 2 : 0;
    const size_t centre = fb.index(fb.width / 2, fb.height / 2), corner = fb.index(1, 1);
    EXPECT_TRUE(fb.id[centre] == nearQuad || fb.id[centre] == nearQuad + 1) << fb.id[centre];
    EXPECT_NEAR(fb.depth[centre], nearDepth, 1e-5 * nearDepth);
    EXPECT_FALSE(fb.id[corner] == nearQuad || fb.id[corner] == nearQuad + 1) << fb.id[corner];
    EXPECT_NEAR(fb.depth[corner], farDepth, 1e-5 * farDepth);
    expectPixelsShowTheirTriangles(scene, camera, fb);
  }
}

TEST(ZBufferRenderer, ReportsStagesAndCullingCounts) {
  Scene scene;
  const uint32_t root = scene.addNode("root"), quad = scene.addNode("quad");
  addQuad(scene.nodes[quad].mesh, 1.0, 0.0);
  scene.nodes[root].instances = {{quad, glm::translate(glm::dmat4(1.0), {0.0, 0.0, -5.0})},
                                 {quad, glm::translate(glm::dmat4(1.0), {0.0, 0.0, 5.0})}};
  scene.root = root;
  scene.finalize();
  const Camera camera = test::lookAtCamera({0.0, 0.0, 0.0}, {0.0, 0.0, -1.0}, 0.1, 100.0, 80, 60);
  ZBufferRenderer renderer(scene, RenderOptions{});
  EXPECT_NE(renderer.glDescription().find("Core Profile"), std::string::npos);
  EXPECT_FALSE(renderer.decomposition().empty());
  Framebuffer fb(camera.width(), camera.height());
  for (int frame = 0; frame < 2; ++frame) {
    FrameStats stats;
    fb.clear();
    renderer.render(camera, frame, {}, fb, stats);
    ASSERT_EQ(stats.stageSeconds.size(), 3u);
    EXPECT_EQ(stats.stageSeconds[0].first, "upload");
    EXPECT_EQ(stats.stageSeconds[1].first, "draw");
    EXPECT_EQ(stats.stageSeconds[2].first, "readback");
    if (frame == 1) {
      EXPECT_EQ(stats.stageSeconds[0].second, 0.0);  // uploaded once
    }
    EXPECT_EQ(stats.counts["draw_items"].get<double>(), 2.0);
    EXPECT_EQ(stats.counts["draw_items_culled"].get<double>(), 1.0);  // the one behind the camera
    EXPECT_EQ(stats.counts["triangles_drawn"].get<double>(), 2.0);
    EXPECT_GT(fb.coveredCount(), 0u);
  }
  Framebuffer wrong(camera.width() + 1, camera.height());
  FrameStats stats;
  EXPECT_THROW(renderer.render(camera, 0, {}, wrong, stats), std::invalid_argument);
}

}  // namespace
}  // namespace lzb
