// The statistics of sampling: triangles picked in proportion to area (chi-square), uniform points
// on a triangle, and coverage of a screen-filling plane against the coupon-collector expectation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "src/image/metrics.hpp"
#include "src/rzb/box_sampler.hpp"
#include "src/rzb/rzb_renderer.hpp"
#include "src/rzb/sample_scene.hpp"
#include "src/scene/load.hpp"
#include "src/zbuffer/zbuffer_renderer.hpp"
#include "tests/support/cameras.hpp"
#include "tests/support/options.hpp"
#include "tests/support/render.hpp"

namespace lzb::rzb {
namespace {

// Chi-square statistic of observed counts against expected probabilities.
double chiSquare(const std::vector<uint64_t>& observed, const std::vector<double>& p, uint64_t n) {
  double x2 = 0.0;
  for (size_t k = 0; k < observed.size(); ++k) {
    const double e = p[k] * double(n);
    x2 += (double(observed[k]) - e) * (double(observed[k]) - e) / e;
  }
  return x2;
}

// A box over a whole tree, for drawing samples without a camera.
SelectedBox wholeBox(const DistributionTree& tree, uint32_t root) {
  SelectedBox b;
  b.tree = &tree;
  b.node = root;
  b.part = Part::kSubtree;
  b.key = 12345;
  return b;
}

TEST(Sampling, BatchPhiloxEqualsRandom123) {
  const SampleStream stream(99, 12);
  std::vector<uint32_t> w[4];
  for (auto& v : w) v.resize(1000);
  const uint64_t box = 0x0123456789abcdefull, first = (uint64_t(1) << 40) - 500;
  philoxBatch(stream, box, first, 1000, w[0].data(), w[1].data(), w[2].data(), w[3].data());
  for (uint32_t k = 0; k < 1000; ++k) {
    const auto r = stream.draw(box, first + k);
    for (int i = 0; i < 4; ++i) ASSERT_EQ(w[i][k], r[i]) << k << " word " << i;
  }
  // The per-thread batch buffers give the same words.
  const DrawWords d = batchDraws(stream, box, first, 1000);
  for (uint32_t k = 0; k < 1000; ++k)
    for (int i = 0; i < 4; ++i) ASSERT_EQ(d.w[i][k], w[i][k]);
}

TEST(Sampling, TrianglesArePickedInProportionToArea) {
  // 12 triangles with areas 1..12 spread out, so the octree has several nodes; ratio 64 keeps
  // them in one class.
  Scene scene;
  scene.addNode("t");
  Mesh& m = scene.nodes[0].mesh;
  std::vector<double> area;
  for (int k = 1; k <= 12; ++k) {
    const float s = std::sqrt(2.0f * float(k) + 1.0f), x = float(k % 4) * 10.0f, z = float(k / 4) * 10.0f;
    ASSERT_TRUE(m.add({x, 0, z}, {x + s, 0, z}, {x, 0, z + s}, packRgba8(1, 1, 1)));
    area.push_back(triangleArea(m, uint32_t(k - 1)));
  }
  scene.finalize();
  DistributionParams tp;
  tp.areaRatio = 64.0;
  tp.leafEntries = 2;
  const DistributionTree tree(scene, 0, {}, true, {}, tp);
  ASSERT_EQ(tree.classes().size(), 1u);
  ASSERT_GT(tree.nodeCount(), 3u);
  double total = 0.0;
  for (double a : area) total += a;
  std::vector<double> p;
  for (double a : area) p.push_back(a / total);

  const SampleStream stream(3, 0);
  const uint64_t n = 240000;
  std::vector<uint64_t> count(12, 0);
  const SelectedBox box = wholeBox(tree, tree.classes()[0].root);
  auto sink = [&](const glm::dvec3&, const glm::dvec3&, uint64_t id, const DistributionTree*,
                  uint32_t) { ++count[id]; };
  drawBoxSamples(box, stream, 0, n, n, sink);
  // 11 degrees of freedom: P(chi2 > 31.3) = 0.001.
  EXPECT_LT(chiSquare(count, p, n), 31.3);

  // The same through a dirty tree (distribution-tree descent after a remove and re-insert).
  DistributionTree dyn(scene, 0, {}, true, {}, tp);
  dyn.removeTriangle(5);
  dyn.insertTriangle(5);
  std::fill(count.begin(), count.end(), 0);
  const SelectedBox dbox = wholeBox(dyn, dyn.classes()[0].root);
  drawBoxSamples(dbox, stream, 0, n, n, sink);
  EXPECT_LT(chiSquare(count, p, n), 31.3);
}

// The point pass's camera-space path (a CameraSink: back faces tested in each triangle's own
// tree, one transform per instance entry) lands the same samples with the same IDs, within float
// rounding, and drops the same back faces as the box-frame position and normal of every sample.
TEST(Sampling, CameraSinkLandsTheSamplesOfTheBoxFramePath) {
  const Scene scene = loadScene("builtin:forest?trees=16&levels=1", true);
  const RzbParams p;
  RzbRenderer r(scene, test::renderOptions("rzb", 1, 7), p);
  const Camera camera = test::sceneCamera(scene, 160, 120);
  SelectParams sp;
  sp.eps = p.eps;
  sp.samplesPerPixel = p.samplesPerPixel(160.0 * 120.0);
  sp.fallbackPx = p.fallbackThreshold(160.0 * 120.0);
  const SampleStream stream(7, 1);
  const Selection sel = selectBoxes(r.sampleScene(), camera, sp, stream);
  struct Landed {
    uint64_t id;
    glm::vec3 q;
    bool operator<(const Landed& o) const {
      return id != o.id     ? id < o.id
             : q.x != o.q.x ? q.x < o.q.x
             : q.y != o.q.y ? q.y < o.q.y
                            : q.z < o.q.z;
    }
  };
  struct Camera {
    bool dropBackfaces = true;
    std::vector<Landed> out;
    uint64_t back = 0;
    void point(float x, float y, float z, uint64_t id) { out.push_back({id, {x, y, z}}); }
    void backfacing() { ++back; }
  };
  static_assert(CameraSink<Camera>);
  uint64_t leafInstanceBoxes = 0, compared = 0;
  for (const SelectedBox& box : sel.boxes) {
    if (box.fallback || box.samples == 0) continue;
    for (uint32_t i = 0; i < box.tree->instanceCount(); ++i)
      if (box.tree->instanceHot(i).child->instanceCount() == 0) {
        ++leafInstanceBoxes;
        break;
      }
    std::vector<Landed> plain;
    uint64_t plainBack = 0;
    auto sink = [&](const glm::dvec3& q, const glm::dvec3& n, uint64_t id, const DistributionTree*,
                    uint32_t) {
      if (glm::dot(n, box.eyeLocal - q) < 0.0) return void(++plainBack);
      plain.push_back({id, glm::vec3(box.toCamera.point(q))});
    };
    drawBoxSamples(box, stream, 0, box.samples, box.samples, sink);
    Camera cam;
    drawBoxSamples(box, stream, 0, box.samples, box.samples, cam);
    ASSERT_EQ(cam.back, plainBack);
    ASSERT_EQ(cam.out.size(), plain.size());
    std::sort(plain.begin(), plain.end());
    std::sort(cam.out.begin(), cam.out.end());
    for (size_t k = 0; k < plain.size(); ++k) {
      ASSERT_EQ(cam.out[k].id, plain[k].id);
      const float tol = 1e-5f * (1.0f + glm::length(plain[k].q));
      ASSERT_LT(glm::length(cam.out[k].q - plain[k].q), tol) << k;
    }
    compared += plain.size();
  }
  EXPECT_GT(leafInstanceBoxes, 0u);  // the path through instance entries was taken
  EXPECT_GT(compared, 10000u);
}

TEST(Sampling, PointsAreUniformOnTheTriangle) {
  Scene scene;
  scene.addNode("t");
  ASSERT_TRUE(scene.nodes[0].mesh.add({0, 0, 0}, {4, 0, 0}, {1, 3, 0}, packRgba8(1, 1, 1)));
  scene.finalize();
  const DistributionTree tree(scene, 0, {}, true, {}, DistributionParams{});
  // 16 congruent sub-triangles of a 4 x 4 midpoint subdivision in barycentric (u, v): cell
  // (i, j) with its lower and upper halves.
  const int g = 4;
  std::vector<uint64_t> count(size_t(g * g), 0);
  auto sink = [&](const glm::dvec3& p, const glm::dvec3&, uint64_t, const DistributionTree*,
                  uint32_t) {
    // Solve p = v0 + u e1 + v e2 for (u, v).
    const glm::dvec2 e1(4, 0), e2(1, 3);
    const double det = e1.x * e2.y - e1.y * e2.x;
    const double u = (p.x * e2.y - p.y * e2.x) / det, v = (e1.x * p.y - e1.y * p.x) / det;
    const int i = std::min(int(u * g), g - 1), j = std::min(int(v * g), g - 1);
    const double fu = u * g - i, fv = v * g - j;
    const int upper = fu + fv >= 1.0 ? 1 : 0;
    // Index cells row by row: row j has 2 (g - j) - 1 sub-triangles.
    int idx = 0;
    for (int r = 0; r < j; ++r) idx += 2 * (g - r) - 1;
    idx += 2 * i + upper;
    ASSERT_LT(idx, g * g);
    ++count[size_t(idx)];
  };
  const uint64_t n = 320000;
  drawBoxSamples(wholeBox(tree, tree.classes()[0].root), SampleStream(5, 1), 0, n, n, sink);
  // 15 degrees of freedom: P(chi2 > 37.7) = 0.001.
  EXPECT_LT(chiSquare(count, std::vector<double>(size_t(g * g), 1.0 / (g * g)), n), 37.7);
}

// A fronto-parallel plane covering the image: sample density is exactly uniform in the image, so
// the number of empty pixels after N samples landed is the coupon collector's v (1 - 1/v)^N.
TEST(Sampling, CoverageOfAScreenFillingPlaneMatchesTheCouponCollector) {
  Scene scene;
  scene.addNode("plane");
  Mesh& m = scene.nodes[0].mesh;
  const float s = 30.0f;
  ASSERT_TRUE(m.add({-s, -s, 0}, {s, -s, 0}, {s, s, 0}, packRgba8(100, 100, 100)));
  ASSERT_TRUE(m.add({-s, -s, 0}, {s, s, 0}, {-s, s, 0}, packRgba8(100, 100, 100)));
  scene.finalize();
  const Camera camera = test::lookAtCamera({0, 0, 20}, {0, 0, 0}, 1.0, 100.0, 128, 96);
  double lastEmpty = 1e30;
  for (double oversample : {0.25, 0.5, 0.75, 1.0}) {
    RzbParams p;
    p.fallback = false;
    p.oversample = oversample;
    RzbRenderer r(scene, test::renderOptions("rzb", 2, 7), p);
    FrameStats stats;
    const Framebuffer fb = test::renderFrame(r, camera, &stats);
    const double v = double(fb.size());
    const double landed = stats.counts["samples_splatted"].get<double>();
    const double empty = v - double(fb.coveredCount());
    const double expected = v * std::pow(1.0 - 1.0 / v, landed);
    // Density is ln v per pixel times the oversampling, up to the stochastic rounding.
    EXPECT_NEAR(landed / v, oversample * std::log(v), 0.02 * oversample * std::log(v));
    // Empty pixels are roughly Poisson: allow 5 standard deviations.
    EXPECT_NEAR(empty, expected, 5.0 * std::sqrt(expected) + 2.0) << "oversample " << oversample;
    EXPECT_LE(empty, lastEmpty);
    lastEmpty = empty;
  }
}

}  // namespace
}  // namespace lzb::rzb
