#include "src/zbuffer/depth_mapping.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace lzb {
namespace {

Camera camera(double n, double f) {
  CameraSpec spec;
  spec.position = {1.0, 2.0, 3.0};
  spec.lookAt = {0.0, 0.0, 0.0};
  spec.nearPlane = n;
  spec.farPlane = f;
  spec.fovyDegrees = 50.0;
  return Camera(spec, 64, 48);
}

// Window z of a camera-space point at view depth d, and its clip w.
glm::dvec2 windowZ(const glm::dmat4& p, double d) {
  const glm::dvec4 clip = p * glm::dvec4(0.3 * d, -0.2 * d, -d, 1.0);
  return {clip.z / clip.w, clip.w};
}

TEST(DepthMapping, ReversedZMapsNearToOneAndFarToZero) {
  for (auto [n, f] : {std::pair{0.1, 100.0}, std::pair{1e-3, 1e6}, std::pair{5.0, 5.5}}) {
    const glm::dmat4 p = reversedZProjection(camera(n, f));
    EXPECT_NEAR(windowZ(p, n).x, 1.0, 1e-12);
    EXPECT_NEAR(windowZ(p, f).x, 0.0, 1e-12);
    // w_clip is the view depth, which the fragment shader reads back as 1 / gl_FragCoord.w.
    EXPECT_DOUBLE_EQ(windowZ(p, 0.5 * (n + f)).y, 0.5 * (n + f));
    // Farther is smaller (GL_ZERO_TO_ONE keeps [0, 1]: inside the clip volume).
    EXPECT_GT(windowZ(p, n * 1.01).x, windowZ(p, n * 1.02).x);
  }
}

TEST(DepthMapping, ReversedZMatchesTheGlProjectionInXAndY) {
  const Camera c = camera(0.5, 50.0);
  const glm::dmat4 p = reversedZProjection(c), gl = c.projection();
  for (int col = 0; col < 4; ++col)
    for (int row : {0, 1, 3}) EXPECT_NEAR(p[col][row], gl[col][row], 1e-12) << col << "," << row;
}

TEST(DepthMapping, StorageScaleIsAPowerOfTwoKeepingFarBelowHalf) {
  for (double f : {1.0, 0.75, 100.0, 1024.0, 1e6, 3e30}) {
    const float s = depthStorageScale(f);
    int e = 0;
    EXPECT_EQ(std::frexp(s, &e), 0.5f) << f;  // exactly a power of two
    EXPECT_LE(f * double(s), 0.5) << f;
    EXPECT_GT(f * double(s), 0.125) << f;  // no precision thrown away
  }
}

}  // namespace
}  // namespace lzb
