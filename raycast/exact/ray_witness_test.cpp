// The ray witness: triangles visible in a corner of a pixel are witnessed, hidden ones and ones
// outside the pixel are not, and the 17 reference samples miss what it proves.
#include "raycast/exact/ray_witness.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "raycast/exact/raycast_renderer.hpp"
#include "tests/support/scenes.hpp"

namespace lzb {
namespace {

// An 8 x 8 image of the plane z = 0 seen from z = 10, near 1, far 30.
Camera testCamera() {
  CameraSpec s;
  s.position = {0.0, 0.0, 10.0};
  s.lookAt = {0.0, 0.0, 0.0};
  s.up = {0.0, 1.0, 0.0};
  s.fovyDegrees = 45.0;
  s.nearPlane = 1.0;
  s.farPlane = 30.0;
  return Camera(s, 8, 8);
}

// The world point seen at pixel coordinates (px, py) at view depth `depth`.
glm::vec3 at(const Camera& cam, double px, double py, double depth) {
  return glm::vec3(cam.position() + depth * cam.pixelDirection(px, py));
}

const Rgba8 kGrey = packRgba8(128, 128, 128);

// A triangle in pixel coordinates at one depth.
void addTriangle(Mesh& mesh, const Camera& cam, glm::dvec2 a, glm::dvec2 b, glm::dvec2 c,
                 double depth) {
  ASSERT_TRUE(mesh.add(at(cam, a.x, a.y, depth), at(cam, b.x, b.y, depth), at(cam, c.x, c.y, depth),
                       kGrey));
}

// Triangle IDs of the scene below.
enum : uint64_t {
  kBackground = 0,  // covers the image at depth 12
  kOccluder,        // covers the image where x + y <= 7.78, at depth 8 (pixel (3, 3) but a corner)
  kHidden,          // inside pixel (1, 1) at depth 11, behind the occluder
  kLonely,          // inside pixel (6, 1) at depth 7, in front of the occluder
  kBeyondFar,       // covers pixel (1, 6) at depth 40, beyond far
  kNearCrossing,    // covers pixel (6, 6) from behind the eye to depth 5
  kSliver,          // the first triangle of an instance: pokes into pixel (5, 5)'s corner
};

Scene witnessScene(const Camera& cam) {
  Scene s;
  s.source = "witness";
  const uint32_t root = s.addNode("root");
  const uint32_t child = s.addNode("sliver");
  Mesh& m = s.nodes[root].mesh;
  addTriangle(m, cam, {-20, -20}, {40, -20}, {-20, 40}, 12.0);
  addTriangle(m, cam, {-20, -20}, {27.78, -20}, {-20, 27.78}, 8.0);
  addTriangle(m, cam, {1.2, 1.2}, {1.8, 1.3}, {1.4, 1.8}, 11.0);
  addTriangle(m, cam, {6.2, 1.2}, {6.8, 1.3}, {6.4, 1.8}, 7.0);
  addTriangle(m, cam, {0.0, 5.0}, {4.0, 5.0}, {0.0, 9.0}, 40.0);
  // One corner behind the eye (depth -2) on the view axis, the others at depth 5: in the image,
  // where y >= 6.5 and y <= x (its near-plane edge is outside the image). Projected without
  // clipping, the corner behind the eye would land at pixel (4, 4) and miss pixel (7, 7).
  m.add(at(cam, 6.5, 6.5, 5.0), at(cam, 9.0, 6.5, 5.0),
               glm::vec3(cam.position() - 2.0 * cam.forward()), kGrey);
  // The sliver, in its own frame shifted by -1 in x, placed back by the instance: in the image it
  // reaches pixel (5, 5) only where x >= 5, y >= 5, x + y <= 10.05 (legs 0.05, 0.00125 px^2),
  // clear of every one of the pixel's 17 reference samples, in front of the occluder.
  const glm::dvec3 shift(1.0, 0.0, 0.0);
  const auto local = [&](double px, double py) { return at(cam, px, py, 7.0) - glm::vec3(shift); };
  s.nodes[child].mesh.add(local(4.5, 4.5), local(5.15, 4.9), local(4.9, 5.15), kGrey);
  s.nodes[root].instances.push_back({child, glm::translate(glm::dmat4(1.0), shift)});
  s.finalize();
  return s;
}

class RayWitnessTest : public ::testing::Test {
 protected:
  RayWitnessTest()
      : cam_(testCamera()), scene_(witnessScene(cam_)), embree_(scene_, {}),
        witness_(scene_, embree_, cam_) {}
  // The first hit through pixel coordinates (px, py).
  uint64_t seen(double px, double py) const {
    return embree_.intersect(cam_.position(), cam_.pixelDirection(px, py), cam_.nearPlane(),
                             cam_.farPlane()).id;
  }
  // True when one of pixel (x, y)'s 17 reference samples (centre, 4 x 4 strata) sees `id`.
  bool seenBySeventeen(int x, int y, uint64_t id) const {
    bool any = seen(x + 0.5, y + 0.5) == id;
    for (int b = 0; b < 4; ++b)
      for (int a = 0; a < 4; ++a) any |= seen(x + (a + 0.5) / 4, y + (b + 0.5) / 4) == id;
    return any;
  }
  Camera cam_;
  Scene scene_;
  EmbreeScene embree_;
  RayWitness witness_;
};

TEST_F(RayWitnessTest, TheSceneIsAsDescribed) {
  ASSERT_EQ(scene_.expandedTriangles(), 7u);
  EXPECT_EQ(seen(0.5, 0.5), kOccluder);
  EXPECT_EQ(seen(7.2, 7.8), kBackground);
  EXPECT_EQ(seen(6.45, 1.45), kLonely);
  EXPECT_EQ(seen(6.9, 6.6), kNearCrossing);
  EXPECT_EQ(seen(5.02, 5.02), kSliver);
  EXPECT_EQ(witness_.name(), "rays");
}

TEST_F(RayWitnessTest, ATriangleVisibleOnlyInACornerOfAPixelIsWitnessed) {
  // The background shows in pixel (3, 3) only where x + y > 7.78 (legs 0.22): no sample there.
  EXPECT_FALSE(seenBySeventeen(3, 3, kBackground));
  EXPECT_TRUE(witness_.visibleInPixel(3, 3, kBackground));
  EXPECT_TRUE(witness_.visibleInPixel(3, 3, kOccluder));
  // A sub-pixel triangle reaching into a corner, placed through an instance.
  EXPECT_FALSE(seenBySeventeen(5, 5, kSliver));
  EXPECT_TRUE(witness_.visibleInPixel(5, 5, kSliver));
  EXPECT_TRUE(witness_.visibleInPixel(4, 4, kSliver));
}

TEST_F(RayWitnessTest, AFullyOccludedTriangleIsNotWitnessed) {
  EXPECT_FALSE(witness_.visibleInPixel(1, 1, kHidden));
  EXPECT_FALSE(witness_.visibleInPixel(1, 1, kBackground));  // behind the occluder everywhere
  EXPECT_TRUE(witness_.visibleInPixel(1, 1, kOccluder));
}

TEST_F(RayWitnessTest, ATriangleOutsideThePixelIsNotWitnessed) {
  EXPECT_TRUE(witness_.visibleInPixel(6, 1, kLonely));
  EXPECT_FALSE(witness_.visibleInPixel(5, 1, kLonely));
  EXPECT_FALSE(witness_.visibleInPixel(6, 2, kLonely));
  EXPECT_FALSE(witness_.visibleInPixel(3, 3, kSliver));
  EXPECT_FALSE(witness_.visibleInPixel(6, 5, kSliver));
}

TEST_F(RayWitnessTest, OnlyTheDepthsBetweenNearAndFarCount) {
  EXPECT_FALSE(witness_.visibleInPixel(1, 6, kBeyondFar));
  // The part in front of the near plane is witnessed, the rest is clipped away.
  EXPECT_TRUE(witness_.visibleInPixel(6, 6, kNearCrossing));
  EXPECT_TRUE(witness_.visibleInPixel(7, 7, kNearCrossing));
}

TEST_F(RayWitnessTest, AnIdOutsideTheSceneIsNotWitnessed) {
  EXPECT_FALSE(witness_.visibleInPixel(3, 3, 7));
  EXPECT_FALSE(witness_.visibleInPixel(3, 3, kNoId));
}

TEST(WitnessScene, SharesTheRaycastReferencesEmbreeSceneElseBuildsItsOwn) {
  const Camera cam = testCamera();
  const Scene scene = witnessScene(cam);
  RenderOptions options;
  options.method = "raycast";
  options.threads = 1;
  const RaycastRenderer raycast(scene, options);
  const WitnessScene shared(scene, &raycast, options);
  EXPECT_TRUE(shared.sharedWithReference());
  EXPECT_EQ(shared.buildSeconds(), 0.0);
  const WitnessScene own(scene, nullptr, options);
  EXPECT_FALSE(own.sharedWithReference());
  EXPECT_GT(own.buildSeconds(), 0.0);
  for (const WitnessScene* w : {&shared, &own}) {
    EXPECT_TRUE(w->witness(cam).visibleInPixel(5, 5, kSliver));
    EXPECT_FALSE(w->witness(cam).visibleInPixel(1, 1, kHidden));
  }
}

// Its own scene is built as the raycast reference would be under the render's options: compact
// leaves under --bvh compact (fewer bytes on a soup large enough for leaves to dominate).
TEST(WitnessScene, BuildsItsOwnSceneUnderTheRendersBvh) {
  const Scene scene = test::soupScene(20000, 0.05, 9);
  RenderOptions fast, compact;
  compact.compactBvh = true;
  const WitnessScene a(scene, nullptr, fast), b(scene, nullptr, compact);
  EXPECT_LT(b.embree().buildStats().bytes, a.embree().buildStats().bytes * 3 / 4);
}

}  // namespace
}  // namespace lzb
