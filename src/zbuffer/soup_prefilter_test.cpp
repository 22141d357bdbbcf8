// The float pre-pass rejects only triangles the exact set-up drops too, and most sub-pixel ones.
#include "src/zbuffer/soup_prefilter.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "src/zbuffer/native_raster.hpp"
#include "tests/support/cameras.hpp"

namespace lzb {
namespace {

constexpr int kW = 64, kH = 48;

// The exact set-up's verdict for one triangle wholly in front (native_raster.cpp's path).
bool exactSetsUp(const Camera& camera, const glm::vec3* corner) {
  ScreenVertex v[3];
  for (int k = 0; k < 3; ++k) {
    const glm::dvec3 p = camera.project(glm::dvec3(corner[k]));
    v[k] = {p.x, p.y, p.z};
  }
  RasterTriangle t;
  return setupTriangle(v, 1, kW, kH, t);
}

// Tiny triangles scattered over the view (and beyond it, and grazing pixel centres), near and far
// from the origin: every rejected one is one the exact set-up drops, and most are rejected (3 *
// 10^4 away too, where float resolves only ~10^-3 of a unit: the eye is held as two floats).
TEST(SoupPrefilter, RejectsOnlyWhatTheExactSetUpDrops) {
  for (const double offset : {0.0, 100.0, 3.0e4}) {
    const glm::dvec3 at(offset, 0.5 * offset, -offset);
    const Camera camera =
        test::lookAtCamera(at + glm::dvec3(0.3, 0.2, 5.0), at, 0.1, 100.0, kW, kH);
    const glm::dmat3 toView =
        glm::transpose(glm::dmat3(camera.right(), camera.up(), camera.forward()));
    const SoupPrefilter pre(camera.position(), toView, camera.pixelsPerUnitAt(1.0), kW, kH,
                            camera.nearPlane(), 8192.0);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> where(-3.0, 3.0), size(0.0, 0.02), depth(-20.0, 4.0);
    std::vector<glm::vec3> corners;
    for (int t = 0; t < 40000; ++t) {
      const glm::dvec3 c = at + glm::dvec3(where(rng), where(rng), depth(rng));
      for (int k = 0; k < 3; ++k)
        corners.push_back(glm::vec3(c + glm::dvec3(size(rng), size(rng), size(rng))));
    }
    uint64_t rejected = 0, kept = 0;
    for (size_t t = 0; t + 8 <= corners.size() / 3; t += 8) {
      const unsigned keep = pre.mayCover8(&corners[3 * t]);
      for (size_t j = 0; j < 8; ++j) {
        const glm::vec3* tri = &corners[3 * (t + j)];
        const bool inFront = camera.viewDepth(glm::dvec3(tri[0])) > camera.nearPlane() &&
                             camera.viewDepth(glm::dvec3(tri[1])) > camera.nearPlane() &&
                             camera.viewDepth(glm::dvec3(tri[2])) > camera.nearPlane();
        if (keep >> j & 1) {
          ++kept;
        } else {
          ++rejected;
          ASSERT_TRUE(inFront) << "offset " << offset << ", triangle " << t + j;
          ASSERT_FALSE(exactSetsUp(camera, tri)) << "offset " << offset << ", triangle " << t + j;
        }
      }
    }
    EXPECT_GT(rejected, 4 * kept) << "offset " << offset;
  }
}

// A triangle whose corner lies a hair off a pixel centre, and one through it: both passed on.
TEST(SoupPrefilter, PassesTrianglesGrazingAPixelCentre) {
  const Camera camera = test::lookAtCamera({0, 0, 10}, {0, 0, 0}, 0.1, 100.0, kW, kH);
  const glm::dmat3 toView =
      glm::transpose(glm::dmat3(camera.right(), camera.up(), camera.forward()));
  const SoupPrefilter pre(camera.position(), toView, camera.pixelsPerUnitAt(1.0), kW, kH,
                          camera.nearPlane(), 8192.0);
  // World units per pixel at depth 10, and the world point of pixel centre (20.5, 10.5).
  const double unit = 1.0 / camera.pixelsPerUnitAt(10.0);
  const glm::dvec3 centre((20.5 - 0.5 * kW) * unit, (0.5 * kH - 10.5) * unit, 0.0);
  std::vector<glm::vec3> corners;
  for (const double gap : {1e-6, 0.0, -1e-6, 0.3, 0.3, 0.3, 0.3, 0.3}) {
    const glm::dvec3 a = centre + glm::dvec3(gap * unit, 0, 0);
    corners.push_back(glm::vec3(a));
    corners.push_back(glm::vec3(a + glm::dvec3(0.2 * unit, 0.0, 0.0)));
    corners.push_back(glm::vec3(a + glm::dvec3(0.0, 0.2 * unit, 0.0)));
  }
  const unsigned keep = pre.mayCover8(corners.data());
  for (int t = 0; t < 3; ++t) EXPECT_TRUE(keep >> t & 1) << t;
  EXPECT_FALSE(keep >> 3 & 1);  // 0.3 pixel away from every centre: no doubt
  EXPECT_FALSE(exactSetsUp(camera, &corners[9]));
}

}  // namespace
}  // namespace lzb
