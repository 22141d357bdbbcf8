// Procedural surfaces: deterministic noise, and the tessellation layout that maps (u, v) to the
// triangle holding it.
#include <gtest/gtest.h>

#include <cmath>

#include "src/core/error.hpp"
#include "src/core/procedural.hpp"
#include "src/core/scene.hpp"

namespace lzb {
namespace {

TEST(Procedural, NoiseIsDeterministicBoundedAndSeeded) {
  double lo = 1.0, hi = -1.0;
  for (int k = 0; k < 2000; ++k) {
    const glm::dvec3 p(0.173 * k, 0.37, -0.091 * k);
    const double n = fractalNoise(p, 5, 7);
    EXPECT_EQ(n, fractalNoise(p, 5, 7));
    lo = std::min(lo, n);
    hi = std::max(hi, n);
  }
  EXPECT_GE(lo, -1.0);
  EXPECT_LE(hi, 1.0);
  EXPECT_GT(hi - lo, 0.5);  // it varies
  EXPECT_NE(fractalNoise({1.3, 0.37, 2.1}, 5, 7), fractalNoise({1.3, 0.37, 2.1}, 5, 8));
}

// On an undisplaced plane the tessellation is exact, so the triangle the layout names for (u, v)
// must contain the surface point p(u, v).
TEST(Procedural, LayoutNamesTheTriangleContainingTheParameterPoint) {
  ProceduralSpec spec;
  spec.amplitude = 0.0;
  spec.tess = 7;
  Mesh mesh;
  const ProceduralSurface s = tessellate(spec, mesh, "test");
  ASSERT_EQ(mesh.size(), size_t(2 * 7 * 7));
  for (int k = 0; k < 5000; ++k) {
    const double u = std::fmod(0.6180339887 * k, 1.0), v = std::fmod(0.7548776662 * k + 0.1, 1.0);
    const uint32_t t = s.triangleAt(u, v);
    const glm::dvec3 p = spec.position(u, v);
    const glm::dvec3 a(mesh.vertex(t, 0)), b(mesh.vertex(t, 1)), c(mesh.vertex(t, 2));
    // barycentrics in the x-z plane
    const double det = (b.x - a.x) * (c.z - a.z) - (c.x - a.x) * (b.z - a.z);
    const double l1 = ((p.x - a.x) * (c.z - a.z) - (c.x - a.x) * (p.z - a.z)) / det;
    const double l2 = ((b.x - a.x) * (p.z - a.z) - (p.x - a.x) * (b.z - a.z)) / det;
    EXPECT_GE(l1, -1e-6) << u << " " << v;
    EXPECT_GE(l2, -1e-6) << u << " " << v;
    EXPECT_LE(l1 + l2, 1.0 + 1e-6) << u << " " << v;
  }
}

// The sphere's pole rows lose their degenerate halves; the layout then names the other half, and
// every normal points outwards.
TEST(Procedural, SpherePolesAndOutwardNormals) {
  ProceduralSpec spec;
  spec.kind = ProceduralKind::kSphere;
  spec.size = 1.0;
  spec.amplitude = 0.1;
  spec.tess = 16;
  Mesh mesh;
  const ProceduralSurface s = tessellate(spec, mesh, "test");
  EXPECT_EQ(mesh.size(), size_t(2 * 16 * 16 - 2 * 16));
  for (uint32_t t : s.slotTriangle) EXPECT_LT(t, mesh.size());
  for (size_t t = 0; t < mesh.size(); ++t) {
    const glm::dvec3 centre =
        (glm::dvec3(mesh.vertex(t, 0)) + glm::dvec3(mesh.vertex(t, 1)) + glm::dvec3(mesh.vertex(t, 2))) / 3.0;
    EXPECT_GT(glm::dot(glm::dvec3(mesh.normal(t)), centre), 0.0) << t;
  }
}

TEST(Procedural, TessOutOfRangeIsAnInputError) {
  ProceduralSpec spec;
  spec.tess = 0;
  Mesh mesh;
  EXPECT_THROW(tessellate(spec, mesh, "here"), InputError);
  spec.tess = kMaxTess + 1;
  EXPECT_THROW(tessellate(spec, mesh, "here"), InputError);
}

}  // namespace
}  // namespace lzb
