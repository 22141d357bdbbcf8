#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <random>

#include "src/octree/octree.hpp"
#include "tests/support/random_geometry.hpp"

namespace lzb {
namespace {

using test::randomMesh;
using test::vertex;

std::map<uint32_t, Cull> cull(const Octree& tree, const Frustum& f, const glm::dmat4& m) {
  std::map<uint32_t, Cull> out;
  tree.cullFrustum(f, m, [&](uint32_t leaf, Cull c) {
    EXPECT_TRUE(out.emplace(leaf, c).second) << "leaf " << leaf << " emitted twice";
  });
  return out;
}

// A camera in world space looking at the node's content placed by m.
Camera cameraAt(std::mt19937_64& rng, const glm::dmat4& m) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), unit(0.0, 1.0);
  const double scale = glm::length(glm::dvec3(m[0]));
  CameraSpec spec;
  spec.lookAt = glm::dvec3(m * glm::dvec4(0.7 * u(rng), 0.7 * u(rng), 0.7 * u(rng), 1.0));
  const glm::dvec3 dir = glm::normalize(glm::dvec3{u(rng), u(rng), u(rng)} + glm::dvec3(1e-3));
  spec.position = spec.lookAt + scale * (0.3 + 3.0 * unit(rng)) * dir;
  spec.up = glm::dvec3{u(rng), u(rng), u(rng)};
  spec.fovyDegrees = 15.0 + 70.0 * unit(rng);
  spec.nearPlane = scale * (0.05 + 0.5 * unit(rng));
  spec.farPlane = spec.nearPlane + scale * (0.5 + 3.0 * unit(rng));
  return Camera(spec, 64 + int(rng() % 64), 48 + int(rng() % 64));
}

// The leaves whose closed boxes contain node-space point p (several on shared faces).
void leavesContaining(const Octree& tree, uint32_t i, const glm::dvec3& p,
                      std::vector<uint32_t>& out) {
  if (!tree.nodeBox(i).contains(p)) return;
  const Octree::Node& n = tree.node(i);
  if (n.leaf()) {
    out.push_back(i);
    return;
  }
  for (uint32_t c = 0; c < 8; ++c) leavesContaining(tree, n.firstChild + c, p, out);
}

TEST(OctreeCull, MatchesPerLeafClassificationAndKeepsEveryVisibleTriangle) {
  const Mesh mesh = randomMesh(4000, 21);
  OctreeParams p;
  p.maxLeafEntries = 20;
  const Octree tree(mesh, {}, p);
  const std::vector<uint32_t> leaves = test::nonEmptyLeaves(tree);
  std::mt19937_64 rng(21);
  uint64_t emittedTotal = 0, culledTotal = 0, insideTotal = 0, visibleChecks = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const glm::dmat4 m =
        trial % 4 == 0 ? glm::dmat4(1.0) : test::randomRigidMotion(rng, trial % 4 == 3);
    const Frustum world = cameraAt(rng, m).frustum();
    const auto got = cull(tree, world, m);
    // Same answer as classifying every leaf box with the node-space frustum.
    const Frustum local = frustumToNodeSpace(world, m);
    for (uint32_t leaf : leaves) {
      const Cull want = local.classify(tree.nodeBox(leaf));
      const auto it = got.find(leaf);
      if (want == Cull::kOutside) {
        EXPECT_TRUE(it == got.end()) << "leaf " << leaf << " should be culled";
        ++culledTotal;
      } else {
        ASSERT_TRUE(it != got.end()) << "leaf " << leaf << " culled wrongly";
        EXPECT_EQ(it->second, want) << "leaf " << leaf;
        insideTotal += want == Cull::kInside;
      }
    }
    for (const auto& [leaf, c] : got) EXPECT_TRUE(tree.node(leaf).leaf() && tree.node(leaf).count);
    emittedTotal += got.size();
    // Brute force in world space: a triangle point inside the frustum keeps its leaves.
    for (uint32_t t = 0; t < mesh.size(); ++t)
      for (int i = 0; i <= 4; ++i)
        for (int j = 0; i + j <= 4; ++j) {
          const glm::dvec3 a = vertex(mesh, t, 0), b = vertex(mesh, t, 1), c = vertex(mesh, t, 2);
          const glm::dvec3 q = a + 0.25 * i * (b - a) + 0.25 * j * (c - a);
          if (!world.contains(glm::dvec3(m * glm::dvec4(q, 1.0)))) continue;
          ++visibleChecks;
          std::vector<uint32_t> at;
          leavesContaining(tree, 0, q, at);
          ASSERT_FALSE(at.empty());
          for (uint32_t leaf : at) {
            const auto e = tree.leafEntries(leaf);
            if (std::binary_search(e.begin(), e.end(), t)) {
              ASSERT_TRUE(got.count(leaf)) << "visible triangle " << t << " culled in " << leaf;
            }
          }
        }
  }
  EXPECT_GT(emittedTotal, 1000u);
  EXPECT_GT(culledTotal, 1000u);
  EXPECT_GT(insideTotal, 100u);
  EXPECT_GT(visibleChecks, 10000u);
}

TEST(OctreeCull, WholeTreeInsideOrOutside) {
  const Mesh mesh = randomMesh(3000, 22);
  OctreeParams p;
  p.maxLeafEntries = 30;
  const Octree tree(mesh, {}, p);
  const glm::dmat4 m = glm::translate(glm::dmat4(1.0), glm::dvec3(100.0, -50.0, 20.0));
  CameraSpec spec;
  spec.lookAt = {100.0, -50.0, 20.0};
  spec.position = spec.lookAt + glm::dvec3(0.0, 0.0, 20.0);
  spec.nearPlane = 1.0;
  spec.farPlane = 100.0;
  const auto all = cull(tree, Camera(spec, 100, 100).frustum(), m);
  EXPECT_EQ(all.size(), tree.stats().nonEmptyLeaves);
  for (const auto& [leaf, c] : all) EXPECT_EQ(c, Cull::kInside);
  spec.lookAt = spec.position + glm::dvec3(0.0, 0.0, 1.0);  // looking away
  EXPECT_TRUE(cull(tree, Camera(spec, 100, 100).frustum(), m).empty());
}

TEST(OctreeCull, FrustumToNodeSpaceKeepsContainment) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  int inside = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const glm::dmat4 m = test::randomRigidMotion(rng, trial % 2 == 1);
    const Frustum world = cameraAt(rng, m).frustum();
    const Frustum local = frustumToNodeSpace(world, m);
    for (int i = 0; i < 2000; ++i) {
      const glm::dvec3 q{u(rng), u(rng), u(rng)};
      const glm::dvec3 w(m * glm::dvec4(q, 1.0));
      for (int k = 0; k < 6; ++k) {
        // Same side of every plane, and a unit normal (distances scale by the uniform scale).
        const double dw = world.planes[k].distance(w), dl = local.planes[k].distance(q);
        EXPECT_NEAR(glm::length(local.planes[k].n), 1.0, 1e-12);
        if (std::abs(dw) > 1e-9) {
          EXPECT_EQ(dw > 0.0, dl > 0.0);
        }
        EXPECT_NEAR(dl * glm::length(glm::dvec3(m[0])), dw, 1e-9 * (1.0 + std::abs(dw)));
      }
      inside += local.contains(q);
    }
  }
  EXPECT_GT(inside, 100);
}

}  // namespace
}  // namespace lzb
