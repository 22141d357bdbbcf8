// Surfelization: the raster way finds exactly the cells a triangle overlaps, samples lie on their
// triangle inside their cell, collisions split by the paper's rule, z-buffer shots find the cells
// of a convex object's surface, and nothing depends on the thread count.
#include "src/surfels/surfelize.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <set>

#include "src/octree/tri_box_overlap.hpp"
#include "src/surfels/surfel_renderer.hpp"

namespace lzb::surfels {
namespace {

Mesh randomTriangles(int n, uint64_t seed) {
  Mesh m;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  while (int(m.size()) < n) {
    const glm::vec3 c(u(rng), u(rng), u(rng));
    const float s = 0.6f * (u(rng) + 1.0f);
    m.add(c, c + s * glm::vec3(u(rng), u(rng), u(rng)), c + s * glm::vec3(u(rng), u(rng), u(rng)),
          packRgba8(200, 100, 50));
  }
  return m;
}

glm::dvec3 toGrid(const Mesh& m, uint32_t t, int k, const Domain& d, int grid) {
  return (glm::dvec3(m.vertex(t, k)) - d.origin) / d.side * double(grid);
}

TEST(Surfelize, RasterFindsExactlyTheCellsEachTriangleOverlaps) {
  const Mesh m = randomTriangles(40, 3);
  const Domain d = Domain::around(m);
  constexpr int kGrid = 16;
  const std::vector<Candidate> c = rasterCandidates(m, d, kGrid, 2);
  std::set<std::pair<uint64_t, uint32_t>> got, want;
  for (const Candidate& x : c) got.insert({x.cell, x.triangle});
  for (uint32_t t = 0; t < m.size(); ++t)
    for (int z = 0; z < kGrid; ++z)
      for (int y = 0; y < kGrid; ++y)
        for (int x = 0; x < kGrid; ++x) {
          const glm::dvec3 lo(x, y, z);
          if (triBoxOverlap(Bounds{lo, lo + 1.0}, toGrid(m, t, 0, d, kGrid),
                            toGrid(m, t, 1, d, kGrid), toGrid(m, t, 2, d, kGrid)))
            want.insert({uint64_t(x) + kGrid * (uint64_t(y) + kGrid * uint64_t(z)), t});
        }
  // Cells a triangle only grazes (clipping leaves nothing) may be left out; none may be added.
  for (const auto& p : got) EXPECT_TRUE(want.count(p)) << "cell " << p.first << " tri " << p.second;
  EXPECT_GE(double(got.size()), 0.995 * double(want.size()));
}

TEST(Surfelize, SamplesLieOnTheirTriangleInsideTheirCellNearestTheCentre) {
  const Mesh m = randomTriangles(30, 5);
  const Domain d = Domain::around(m);
  constexpr int kGrid = 8;
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const Candidate& c : rasterCandidates(m, d, kGrid, 1)) {
    const glm::dvec3 cell(double(c.cell % kGrid), double(c.cell / kGrid % kGrid),
                          double(c.cell / (kGrid * kGrid)));
    const glm::dvec3 s(c.sample);
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(s[k], cell[k] - 1e-5);
      EXPECT_LE(s[k], cell[k] + 1.0 + 1e-5);
    }
    const glm::dvec3 a = toGrid(m, c.triangle, 0, d, kGrid), b = toGrid(m, c.triangle, 1, d, kGrid),
                     e = toGrid(m, c.triangle, 2, d, kGrid);
    const glm::dvec3 n = glm::normalize(glm::cross(b - a, e - a));
    EXPECT_NEAR(glm::dot(n, s - a), 0.0, 1e-4);  // on the triangle's plane
    // No random point of the triangle inside the cell is nearer the centre.
    const glm::dvec3 centre = cell + 0.5;
    for (int i = 0; i < 200; ++i) {
      double r1 = u(rng), r2 = u(rng);
      if (r1 + r2 > 1.0) r1 = 1.0 - r1, r2 = 1.0 - r2;
      const glm::dvec3 p = a + r1 * (b - a) + r2 * (e - a);
      if (glm::all(glm::greaterThanEqual(p, cell)) && glm::all(glm::lessThanEqual(p, cell + 1.0))) {
        EXPECT_GE(glm::dot(p - centre, p - centre), double(c.dist2) - 1e-4);
      }
    }
  }
}

// Two sheets closer than a cell, facing apart: split keeps a surfel for each side in every cell
// both pass through, average merges them.
TEST(Surfelize, CollisionsSplitWhenNormalsDifferAndAverageOtherwise) {
  Mesh m;
  const Rgba8 c = packRgba8(180, 180, 180);
  m.add({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, c);                     // facing +z
  m.add({0, 0, 0.001f}, {0, 1, 0.001f}, {1, 0, 0.001f}, c);      // facing -z, a thousandth above
  m.add({0.9f, 0.9f, 0.3f}, {1, 0.9f, 0.3f}, {1, 1, 0.31f}, c);  // moves the sheets off a cell face
  const OctahedralNormals normals(6);
  SurfelizeParams p;
  p.grid = 32;
  std::map<uint64_t, std::set<uint32_t>> byCell;
  for (const Candidate& x : rasterCandidates(m, Domain::around(m), p.grid, 1))
    byCell[x.cell].insert(x.triangle);
  uint64_t both = 0;
  for (const auto& [cell, tris] : byCell) both += tris.count(0) && tris.count(1);
  ASSERT_GT(both, 100u);
  p.split = true;
  const SurfelLevel split = surfelize(m, normals, p);
  p.split = false;
  const SurfelLevel merged = surfelize(m, normals, p);
  EXPECT_EQ(split.cells, byCell.size());
  EXPECT_EQ(merged.cells, byCell.size());
  EXPECT_EQ(split.splitCells, both);
  EXPECT_EQ(split.collector.size(), split.cells + both);
  EXPECT_EQ(merged.collector.size(), merged.cells);
  EXPECT_EQ(merged.splitCells, 0u);
  // Split surfels keep their side's normal and triangle.
  const SurfelCollector& s = split.collector;
  for (uint32_t key = 0; key < s.keys(); ++key)
    for (uint64_t i = s.start(key); i < s.start(key + 1); ++i) {
      const uint32_t t = s.triangle(i);
      if (t == 2) continue;
      const glm::vec3 n = normals.decode(s.surfel(key, i).normal);
      EXPECT_GT(n.z * (t == 0 ? 1.0f : -1.0f), 0.99f);
    }
}

// Which cells shots must find: a plane at distance r from a cell's centre meets the cell's
// inscribed ball (radius 1/2) in a disc of radius sqrt(1/4 - r^2); seen from the nearest of the 26
// directions (at most acos(1 / |(1, sqrt 2 - 1, sqrt 3 - sqrt 2)|) = 27.6 degrees off the normal)
// it stays an ellipse of minor radius >= 0.886 sqrt(1/4 - r^2), which holds a pixel centre of the
// 0.5-cell lattice once that is >= 0.5 / sqrt 2: so r^2 <= 0.0909. A cell the surface only grazes
// (larger r) may be missed, as two pixels a cell cannot sample every sliver.
TEST(Surfelize, ShotsFindTheSurfaceCellsOfAConvexObject) {
  const Mesh sphere = uvSphere(32, 16);
  const Domain d = Domain::around(sphere);
  const double cosWorst =
      1.0 / glm::length(glm::dvec3(1.0, std::sqrt(2.0) - 1.0, std::sqrt(3.0) - std::sqrt(2.0)));
  const double r2Max = 0.25 - std::pow(0.5 / std::sqrt(2.0) / cosWorst, 2.0);
  EXPECT_NEAR(r2Max, 0.0909, 1e-4);
  for (int grid : {16, 64}) {
    std::map<uint64_t, float> raster;  // cell -> the surface's nearest approach to its centre
    for (const Candidate& c : rasterCandidates(sphere, d, grid, 2)) {
      auto [it, fresh] = raster.emplace(c.cell, c.dist2);
      if (!fresh) it->second = std::min(it->second, c.dist2);
    }
    std::set<uint64_t> shots;
    for (const Candidate& c : shotCandidates(sphere, d, grid, 2)) shots.insert(c.cell);
    size_t inRaster = 0, central = 0, centralShot = 0;
    for (uint64_t cell : shots) inRaster += raster.count(cell);
    EXPECT_EQ(inRaster, shots.size()) << "grid " << grid << ": shots found cells off the surface";
    for (const auto& [cell, r2] : raster)
      if (r2 <= r2Max) {
        ++central;
        centralShot += shots.count(cell);
      }
    EXPECT_EQ(centralShot, central) << "grid " << grid;
    // Not vacuous: the centres within r of the surface fill a shell of volume about 2 r area.
    double area = 0.0;
    for (uint32_t t = 0; t < sphere.size(); ++t) {
      const glm::dvec3 a = toGrid(sphere, t, 0, d, grid), b = toGrid(sphere, t, 1, d, grid),
                       c = toGrid(sphere, t, 2, d, grid);
      area += 0.5 * glm::length(glm::cross(b - a, c - a));
    }
    EXPECT_GT(double(central), 0.5 * 2.0 * std::sqrt(r2Max) * area) << "grid " << grid;
    std::printf("grid %d: raster %zu cells, shots %zu, crossed within r^2 <= %.4f: %zu\n", grid,
                raster.size(), shots.size(), r2Max, central);
  }
}

void expectSameLevel(const SurfelLevel& a, const SurfelLevel& b) {
  ASSERT_EQ(a.collector.size(), b.collector.size());
  for (uint32_t key = 0; key <= a.collector.keys(); ++key)
    ASSERT_EQ(a.collector.start(key), b.collector.start(key));
  for (uint64_t i = 0; i < a.collector.size(); ++i) {
    ASSERT_EQ(a.collector.data(i), b.collector.data(i));
    ASSERT_EQ(a.collector.triangle(i), b.collector.triangle(i));
  }
}

TEST(Surfelize, TheSameSurfelsForAnyThreadCount) {
  const Mesh m = randomTriangles(300, 8);
  for (Surfelizer how : {Surfelizer::kRaster, Surfelizer::kShots})
    for (CollectorQuality q : {CollectorQuality::kLow, CollectorQuality::kHigh}) {
      const OctahedralNormals normals(CollectorLayout::of(q).normalLevels);
      SurfelizeParams p;
      p.method = how;
      p.quality = q;
      p.grid = 64;
      p.threads = 1;
      const SurfelLevel one = surfelize(m, normals, p);
      p.threads = 2;
      const SurfelLevel two = surfelize(m, normals, p);
      EXPECT_GT(one.collector.size(), 1000u);
      expectSameLevel(one, two);
    }
}

}  // namespace
}  // namespace lzb::surfels
