#include "src/core/camera.hpp"

#include <gtest/gtest.h>

#include "src/core/error.hpp"

namespace lzb {
namespace {

CameraSpec lookDownMinusZ() {
  CameraSpec s;
  s.position = {0, 0, 0};
  s.lookAt = {0, 0, -1};
  s.up = {0, 1, 0};
  s.fovyDegrees = 90.0;
  s.nearPlane = 0.1;
  s.farPlane = 100.0;
  return s;
}

TEST(Camera, PixelDirectionHasUnitForwardComponentAndHitsImageCorners) {
  Camera cam(lookDownMinusZ(), 200, 100);
  const glm::dvec3 centre = cam.pixelDirection(100, 50);
  EXPECT_NEAR(centre.x, 0.0, 1e-15);
  EXPECT_NEAR(centre.y, 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(glm::dot(cam.pixelDirection(3.5, 7.5), cam.forward()), 1.0);
  // 90 degree vertical fov: the top edge is at 45 degrees, the right edge at aspect * 1.
  const glm::dvec3 topLeft = cam.pixelDirection(0, 0);
  EXPECT_NEAR(topLeft.y, 1.0, 1e-12);
  EXPECT_NEAR(topLeft.x, -2.0, 1e-12);
}

TEST(Camera, ProjectInvertsPixelDirection) {
  CameraSpec s = lookDownMinusZ();
  s.position = {1e7, -3e6, 42.0};  // far from the origin: double precision keeps pixels exact
  s.lookAt = s.position + glm::dvec3(0.3, -0.2, -1.0);
  Camera cam(s, 640, 480);
  for (double px : {0.5, 100.25, 639.5})
    for (double py : {0.5, 240.0, 479.5}) {
      const glm::dvec3 p = cam.position() + 37.0 * cam.pixelDirection(px, py);
      const glm::dvec3 q = cam.project(p);
      EXPECT_NEAR(q.x, px, 1e-6);
      EXPECT_NEAR(q.y, py, 1e-6);
      EXPECT_NEAR(q.z, 37.0, 1e-6);
      EXPECT_NEAR(cam.viewDepth(p), 37.0, 1e-6);
    }
}

TEST(Camera, ViewMatrixMapsForwardToMinusZ) {
  CameraSpec s = lookDownMinusZ();
  s.position = {5, 6, 7};
  s.lookAt = {8, 2, -1};
  Camera cam(s, 64, 64);
  const glm::dvec4 p = cam.view() * glm::dvec4(cam.position() + 3.0 * cam.forward(), 1.0);
  EXPECT_NEAR(p.x, 0.0, 1e-12);
  EXPECT_NEAR(p.y, 0.0, 1e-12);
  EXPECT_NEAR(p.z, -3.0, 1e-12);
}

TEST(Camera, RejectsBadFields) {
  CameraSpec s = lookDownMinusZ();
  s.nearPlane = 0.0;
  EXPECT_THROW(Camera(s, 64, 64), InputError);
  s.nearPlane = -1.0;
  EXPECT_THROW(Camera(s, 64, 64), InputError);
  s = lookDownMinusZ();
  s.farPlane = s.nearPlane;
  EXPECT_THROW(Camera(s, 64, 64), InputError);
  s = lookDownMinusZ();
  EXPECT_THROW(Camera(s, 0, 64), InputError);
  EXPECT_THROW(Camera(s, 64, 1 << 20), InputError);
  s.up = {0, 0, 1};  // parallel to the view direction
  EXPECT_THROW(Camera(s, 64, 64), InputError);
  s = lookDownMinusZ();
  s.fovyDegrees = 180.0;
  EXPECT_THROW(Camera(s, 64, 64), InputError);
  try {
    s = lookDownMinusZ();
    s.nearPlane = -2;
    Camera(s, 64, 64, "scene.toml: camera");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("camera.near"), std::string::npos) << e.what();
  }
}

TEST(Frustum, ClassifiesBoxes) {
  Camera cam(lookDownMinusZ(), 64, 64);
  const Frustum f = cam.frustum();
  Bounds inside{{-0.5, -0.5, -5.5}, {0.5, 0.5, -4.5}};
  Bounds behind{{-1, -1, 1}, {1, 1, 2}};
  Bounds beyondFar{{-1, -1, -300}, {1, 1, -200}};
  Bounds straddling{{-100, -1, -5}, {0, 1, -4}};
  Bounds leftOfFrustum{{-30, -1, -6}, {-20, 1, -5}};  // x < -z: outside the 90 degree fov
  EXPECT_EQ(f.classify(inside), Cull::kInside);
  EXPECT_EQ(f.classify(behind), Cull::kOutside);
  EXPECT_EQ(f.classify(beyondFar), Cull::kOutside);
  EXPECT_EQ(f.classify(straddling), Cull::kIntersects);
  EXPECT_EQ(f.classify(leftOfFrustum), Cull::kOutside);
  EXPECT_EQ(f.classify(Bounds{}), Cull::kOutside);
}

TEST(Frustum, AgreesWithProjectionOnRandomPoints) {
  CameraSpec s = lookDownMinusZ();
  s.position = {1, 2, 3};
  s.lookAt = {-2, 0, -5};
  s.fovyDegrees = 50;
  Camera cam(s, 320, 200);
  const Frustum f = cam.frustum();
  uint64_t state = 12345;
  auto next = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return double(state >> 11) / double(1ull << 53);
  };
  int agree = 0, total = 2000;
  for (int i = 0; i < total; ++i) {
    glm::dvec3 p(next() * 40 - 20, next() * 40 - 20, next() * 40 - 30);
    const glm::dvec3 q = cam.project(p);
    const bool inImage = q.z >= s.nearPlane && q.z <= s.farPlane && q.x >= 0 && q.x <= 320 &&
                         q.y >= 0 && q.y <= 200;
    agree += inImage == f.contains(p);
  }
  EXPECT_EQ(agree, total);
}

TEST(CameraPath, CircleKeepsDistanceAndHeight) {
  Scene scene;
  CameraSpec base = lookDownMinusZ();
  base.position = {10, 4, 0};
  base.lookAt = {0, 1, 0};
  for (int f = 0; f < 8; ++f) {
    CameraSpec c = pathCamera(scene, base, f, 8);
    EXPECT_NEAR(glm::length(c.position - c.lookAt), glm::length(base.position - base.lookAt), 1e-9);
    EXPECT_NEAR(c.position.y, 4.0, 1e-12);
  }
  EXPECT_NEAR(pathCamera(scene, base, 4, 8).position.x, -10.0, 1e-9);
}

TEST(CameraPath, KeyframesAreInterpolated) {
  Scene scene;
  CameraSpec a = lookDownMinusZ(), b = lookDownMinusZ();
  b.position = {10, 0, 0};
  b.lookAt = {10, 0, -1};
  scene.keyframes = {a, b};
  EXPECT_NEAR(pathCamera(scene, a, 0, 5).position.x, 0.0, 1e-12);
  EXPECT_NEAR(pathCamera(scene, a, 2, 5).position.x, 5.0, 1e-12);
  EXPECT_NEAR(pathCamera(scene, a, 4, 5).position.x, 10.0, 1e-12);
}

TEST(CameraFraming, NearPlaneStaysPositiveInsideBounds) {
  Bounds b{{-1, -1, -1}, {1, 1, 1}};
  CameraSpec s = lookDownMinusZ();  // camera at the centre of the bounds
  s.nearPlane = s.farPlane = 0.0;
  s = withClipPlanes(s, b);
  EXPECT_GT(s.nearPlane, 0.0);
  EXPECT_GT(s.farPlane, s.nearPlane);
  CameraSpec framed = frameBounds(b);
  Camera cam(framed, 64, 64);
  for (int i = 0; i < 8; ++i) {  // every corner is inside the frustum
    EXPECT_TRUE(cam.frustum().contains(b.corner(i))) << i;
  }
}

}  // namespace
}  // namespace lzb
