// The sample tree's own shading: the inputs come from the stored positions, a pixel's triangle is
// always kept, a splat and its triangle get one colour, and the colours are the scene shading's
// (shadeFromIds) up to the rounding of a normal.
#include "src/sampletree/tree_shading.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <stdexcept>

#include "src/core/shading.hpp"
#include "tests/support/cameras.hpp"
#include "src/sampletree/sampletree_renderer.hpp"
#include "src/scene/load.hpp"

namespace lzb::sampletree {
namespace {

TEST(TreeShading, InputsComeFromTheStoredPositions) {
  const ShadingInputs s = shadingInputs({0, 0, 0}, {2, 0, 0}, {0, 0, -3});
  EXPECT_FLOAT_EQ(s.normal.x, 0.0f);
  EXPECT_FLOAT_EQ(s.normal.y, 1.0f);  // cross((2,0,0), (0,0,-3)) points up
  EXPECT_FLOAT_EQ(s.normal.z, 0.0f);
  EXPECT_FLOAT_EQ(s.point.x, 2.0f / 3.0f);
  EXPECT_FLOAT_EQ(s.point.z, -1.0f);
  // Collapsed by rounding: a fixed normal, never NaN.
  const ShadingInputs flat = shadingInputs({1, 1, 1}, {1, 1, 1}, {2, 2, 2});
  EXPECT_EQ(flat.normal, glm::vec3(0.0f, 1.0f, 0.0f));
}

// Three triangles with IDs 10, 11, 12 facing +z; the framebuffer shows 11 and 12 only.
struct Soup {
  std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0},  {0, 0, 1}, {1, 0, 1},
                                      {0, 1, 1}, {0, 0, 2}, {1, 0, 2}, {0, 1, 2}};
  std::vector<uint64_t> ids = {10, 11, 12};
  std::vector<Rgba8> colours = {packRgba8(200, 0, 0), packRgba8(0, 200, 0), packRgba8(0, 0, 200)};
  SoupRange all{0, 3};
  ColouredSoup view() const { return {positions, ids, colours, {&all, 1}}; }
};

TEST(TreeShading, KeepsWhatTheFrameShowsAndShadesItByTheOneRule) {
  const Soup soup;
  Framebuffer fb(4, 1);
  fb.clear();
  fb.id = {11, kNoId, 12, 12};
  const Camera camera = test::lookAtCamera({0.3, 0.3, 9.0}, {0.3, 0.3, 0.0}, 0.1, 100.0, 4, 1);
  const Light light;
  TreeShading shading;
  shading.keepShown(fb, soup.view(), 2);
  EXPECT_EQ(shading.kept(), 2u);  // not 10: no pixel shows it
  shading.shade(camera, light, fb, 2);
  const Rgba8 green = shade(soup.colours[1], {0, 0, 1}, true, lightDirection(light), float(light.ambient));
  EXPECT_EQ(fb.color[0], green);
  EXPECT_EQ(fb.color[1], kBackground);
  EXPECT_NE(fb.color[2], kBackground);
  EXPECT_EQ(fb.color[2], fb.color[3]);
  // A pixel showing a triangle no soup gave: a logic error, never a silent colour.
  fb.id[1] = 10;
  EXPECT_THROW(shading.shade(camera, light, fb, 1), std::logic_error);
  shading.begin();
  EXPECT_EQ(shading.kept(), 0u);
}

TEST(TreeShading, ASplatAndItsTriangleGetOneColour) {
  const Soup soup;
  SampleTree table;
  TreeNode n;
  n.representativeId = 11;
  n.representativeColour = soup.colours[1];
  const ShadingInputs s = shadingInputs(soup.positions[3], soup.positions[4], soup.positions[5]);
  for (int k = 0; k < 3; ++k) n.representativePoint[k] = s.point[k], n.representativeNormal[k] = s.normal[k];
  table.nodes = {n};
  Framebuffer a(1, 1), b(1, 1);
  a.clear(), b.clear();
  a.id = b.id = {11};
  const Camera camera = test::lookAtCamera({0.3, 5.0, 9.0}, {0.3, 0.3, 1.0}, 0.1, 100.0, 1, 1);
  TreeShading splat, drawn;
  const uint32_t node = 0;
  splat.addRepresentatives(table, {&node, 1});
  drawn.keepShown(b, soup.view(), 1);
  splat.shade(camera, Light{}, a, 1);
  drawn.shade(camera, Light{}, b, 1);
  EXPECT_EQ(a.color, b.color);
}

// The tree's colours against the scene's shading of the same IDs: normals from world positions
// instead of transformed node-frame normals differ by rounding only.
TEST(TreeShading, ColoursAreTheSceneShadingsUpToRounding) {
  const Scene scene = loadScene("builtin:city?blocks=2", true);
  const Bounds b = scene.bounds();
  const Camera camera =
      test::lookAtCamera(b.center() + glm::dvec3(0.3, 0.5, 1.2) * b.diagonal(), b.center(),
                         0.01 * b.diagonal(), 10 * b.diagonal(), 160, 120);
  RenderOptions options;
  options.threads = 2;
  SampleTreeRenderer r(scene, options, SampleTreeOptions{});
  Framebuffer tree(160, 120);
  tree.clear();
  FrameStats stats;
  r.render(camera, 0, {}, tree, stats);
  Framebuffer byScene = tree;
  shadeFromIds(scene, camera, byScene);
  size_t covered = 0, off = 0;
  for (size_t i = 0; i < tree.size(); ++i) {
    if (tree.id[i] == kNoId) continue;
    ++covered;
    int worst = 0;
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(int(channel(tree.color[i], c)) - int(channel(byScene.color[i], c))));
    EXPECT_LE(worst, 2) << "pixel " << i;
    off += worst > 0;
  }
  EXPECT_GT(covered, 1000u);
  EXPECT_LT(double(off), 0.05 * double(covered));
}

}  // namespace
}  // namespace lzb::sampletree
