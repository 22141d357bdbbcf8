#include "src/scene/toml_scene.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "src/core/error.hpp"
#include "src/scene/load.hpp"
#include "tests/support/files.hpp"

namespace lzb {
namespace {

using test::errorOf;
using test::ScratchDir;

const char* kTetrahedron =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

std::string joinLines(const std::vector<std::string>& lines) {
  std::string s;
  for (const std::string& l : lines) s += l + "\n";
  return s;
}

const std::vector<std::string> kValid = {
    "root = \"world\"",
    "[image]",
    "width = 320",
    "height = 200",
    "[camera]",
    "position = [0, 5, 20]",
    "look_at = [0, 0, 0]",
    "fov = 50",
    "near = 0.5",
    "[light]",
    "direction = [0, 1, 0]",
    "ambient = 0.1",
    "[[meshes]]",
    "name = \"tet\"",
    "file = \"models/tet.obj\"",
    "color = [1, 0, 0]",
    "[[generators]]",
    "name = \"flake\"",
    "spec = \"sphereflake?depth=1\"",
    "[[nodes]]",
    "name = \"world\"",
    "instances = [",
    "  { node = \"pair\" },",
    "  { node = \"pair\", translate = [100, 0, 0], rotate = { axis = [0, 1, 0], degrees = 90 } },",
    "  { node = \"flake\", matrix = [[1, 0, 0, 0], [0, 1, 0, -50], [0, 0, 1, 0], [0, 0, 0, 1]] },",
    "]",
    "[[nodes]]",
    "name = \"pair\"",
    "instances = [",
    "  { node = \"tet\" },",
    "  { node = \"tet\", translate = [10, 0, 0], scale = 2, rotate = { euler = [0, 0, 0] } },",
    "]",
};

TEST(TomlScene, NestedInstances) {
  ScratchDir dir;
  std::filesystem::create_directories(dir.path() / "models");
  dir.write("models/tet.obj", kTetrahedron);
  const Scene s = loadScene(dir.write("scene.toml", joinLines(kValid)).string(), true);
  // world = 2 x pair (2 x tet of 4) + sphereflake depth 1 (10 spheres of 200).
  EXPECT_EQ(s.expandedTriangles(), 2u * 2u * 4u + 2000u);
  EXPECT_EQ(s.uniqueTriangles(), 4u + 200u);
  ASSERT_TRUE(s.width && s.height);
  EXPECT_EQ(*s.width, 320);
  EXPECT_EQ(*s.height, 200);
  ASSERT_TRUE(s.camera.has_value());
  EXPECT_EQ(s.camera->position, glm::dvec3(0, 5, 20));
  EXPECT_EQ(s.camera->fovyDegrees, 50.0);
  EXPECT_EQ(s.camera->nearPlane, 0.5);
  EXPECT_EQ(s.camera->farPlane, 0.0);  // not given: chosen from the bounds later
  EXPECT_EQ(s.light.direction, glm::dvec3(0, 1, 0));
  EXPECT_EQ(s.light.ambient, 0.1);
  EXPECT_EQ(s.rootNode().name, "world");
  // Colour override on every tetrahedron triangle.
  const auto first = s.resolve(0);
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(s.nodes[first->node].mesh.color(first->triangle), packRgba8(255, 0, 0));
  // Triangle 4 is the second tet of the first pair: scaled by 2, moved by 10.
  const auto scaled = s.resolve(4);
  ASSERT_TRUE(scaled.has_value());
  const Mesh& m = s.nodes[scaled->node].mesh;
  glm::dvec3 lo(1e9);
  for (int k = 0; k < 3; ++k)
    lo = glm::min(lo, glm::dvec3(scaled->transform *
                                 glm::dvec4(glm::dvec3(m.vertex(scaled->triangle, k)), 1.0)));
  EXPECT_NEAR(lo.x, 10.0, 1e-9);
  // Bounds: the rotated pair near x = 100, the flake moved down to y = -50.
  EXPECT_NEAR(s.bounds().hi.x, 102.0, 1e-9);  // the pair spans z in [0, 2], turned onto x
  EXPECT_LT(s.bounds().lo.y, -50.0);
  EXPECT_NEAR(s.bounds().hi.y, 2.0, 1e-9);  // the tets scaled by 2
}

TEST(TomlScene, KeyframesAndGeneratorRoot) {
  ScratchDir dir;
  const auto path = dir.write("frames.toml", joinLines({
                                                 "root = \"board\"",
                                                 "[[generators]]",
                                                 "name = \"board\"",
                                                 "spec = \"builtin:chessboard?n=4\"",
                                                 "[[keyframes]]",
                                                 "position = [0, 10, 50]",
                                                 "look_at = [0, 0, 0]",
                                                 "[[keyframes]]",
                                                 "position = [50, 10, 0]",
                                                 "look_at = [0, 0, 0]",
                                                 "up = [0, 1, 0]",
                                                 "fov = 30",
                                                 "[[keyframes]]",
                                                 "position = [0, 10, -50]",
                                                 "look_at = [0, 1, 0]",
                                             }));
  const Scene s = loadTomlScene(path);
  ASSERT_EQ(s.keyframes.size(), 3u);
  EXPECT_EQ(s.keyframes[1].position, glm::dvec3(50, 10, 0));
  EXPECT_EQ(s.keyframes[1].fovyDegrees, 30.0);
  EXPECT_EQ(s.keyframes[2].lookAt, glm::dvec3(0, 1, 0));
  EXPECT_EQ(s.expandedTriangles(), 32u);
  // No [camera]: the generator's own default view.
  ASSERT_TRUE(s.camera.has_value());
  EXPECT_EQ(s.source, path.string());
}

TEST(TomlScene, ReadmeExampleLoads) {
  // The documented example must stay a valid scene.
  const std::filesystem::path readme = std::filesystem::path(__FILE__).parent_path() / "README.md";
  if (!std::filesystem::exists(readme)) GTEST_SKIP() << "source tree not available";
  std::ifstream in(readme);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t begin = text.find("```toml\n");
  ASSERT_NE(begin, std::string::npos);
  const size_t end = text.find("\n```", begin + 8);
  ASSERT_NE(end, std::string::npos);
  ScratchDir dir;
  std::filesystem::create_directories(dir.path() / "models");
  dir.write("models/bunny.ply",
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
            "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const Scene s = loadTomlScene(dir.write("example.toml", text.substr(begin + 8, end - begin - 8)));
  EXPECT_EQ(s.rootNode().name, "world");
  EXPECT_EQ(s.keyframes.size(), 2u);
  ASSERT_TRUE(s.camera.has_value());
  EXPECT_EQ(s.camera->farPlane, 5000.0);
  // 2 x 4 bunnies of 1 triangle, a sphereflake of depth 2 and a 4 x 4 city.
  EXPECT_GT(s.expandedTriangles(), 8u + 200u * 91u + 16u * 5000u);
}

// ---- errors: each names the file, the line and the field ----

struct ErrorCase {
  std::vector<std::string> lines;
  int line;
  std::string field, what;
};

void expectTomlError(const ErrorCase& c) {
  ScratchDir dir;
  dir.write("tet.obj", kTetrahedron);
  const auto path = dir.write("bad.toml", joinLines(c.lines));
  const std::string e = errorOf([&] { loadScene(path.string(), true); });
  const std::string where = path.string() + ":" + std::to_string(c.line) + ":";
  EXPECT_NE(e.find(where), std::string::npos) << "expected '" << where << "' in: " << e;
  EXPECT_NE(e.find(c.field), std::string::npos) << "expected field '" << c.field << "' in: " << e;
  EXPECT_NE(e.find(c.what), std::string::npos) << "expected '" << c.what << "' in: " << e;
}

const std::vector<std::string> kTetNode = {"[[meshes]]", "name = \"tet\"", "file = \"tet.obj\""};

std::vector<std::string> withTet(std::vector<std::string> lines) {
  lines.insert(lines.end(), kTetNode.begin(), kTetNode.end());
  return lines;
}

TEST(TomlSceneErrors, ParseError) {
  expectTomlError({{"root = \"a\"", "[camera]", "position = [1, 2", "look_at = [0, 0, 0]"},
                   4,
                   "parse error",
                   ""});
}

TEST(TomlSceneErrors, MissingRequiredField) {
  expectTomlError({withTet({"root = \"tet\"", "[camera]", "look_at = [0, 0, 0]"}), 2,
                   "camera.position", "missing required field"});
  expectTomlError(
      {{"[[meshes]]", "name = \"tet\""}, 1, "meshes[0].file", "missing required field"});
  expectTomlError({withTet({}), 1, "root", "missing required field"});
}

TEST(TomlSceneErrors, WrongType) {
  expectTomlError({withTet({"root = \"tet\"", "[image]", "width = \"big\"", "height = 10"}), 3,
                   "image.width", "must be an integer, got a string"});
  expectTomlError(
      {withTet({"root = \"tet\"", "[camera]", "position = [0, 0, \"x\"]", "look_at = [0, 0, 0]"}),
       3, "camera.position[2]", "must be a number"});
  expectTomlError(
      {withTet({"root = \"tet\"", "[light]", "ambient = nan"}), 3, "light.ambient", "finite"});
  expectTomlError({withTet({"root = \"tet\"", "[[nodes]]", "name = \"n\"",
                            "instances = [{ node = \"tet\", scale = [1, 0, 1] }]"}),
                   4, "nodes[0].instances[0].scale", "non-zero"});
}

TEST(TomlSceneErrors, UnknownFieldAndNames) {
  expectTomlError({withTet({"root = \"tet\"", "[camera]", "position = [0, 0, 1]",
                            "look_at = [0, 0, 0]", "fox = 3"}),
                   5, "camera.fox", "unknown field"});
  expectTomlError({withTet({"root = \"tet\"", "[[nodes]]", "name = \"world\"", "instances = [",
                            "  { node = \"tet\" },", "  { node = \"nope\" },", "]"}),
                   6, "nodes[0].instances[1].node", "unknown node 'nope'"});
  expectTomlError({withTet({"root = \"missing\""}), 1, "root", "unknown node 'missing'"});
  expectTomlError({withTet({"root = \"tet\"", "[[nodes]]", "name = \"tet\"", "instances = []"}), 3,
                   "nodes[0].name", "duplicate name"});
}

TEST(TomlSceneErrors, Cycle) {
  expectTomlError(
      {withTet({"root = \"a\"", "[[nodes]]", "name = \"a\"",
                "instances = [{ node = \"tet\" }, { node = \"b\" }]", "[[nodes]]", "name = \"b\"",
                "instances = [", "  { node = \"a\", translate = [1, 0, 0] },", "]"}),
       8, "nodes[1].instances[0].node", "instancing cycle: a -> b -> a"});
  expectTomlError(
      {withTet({"root = \"a\"", "[[nodes]]", "name = \"a\"", "instances = [{ node = \"a\" }]"}), 4,
       "nodes[0].instances[0].node", "cycle"});
}

// A chain of `n` nodes, c0 -> c1 -> ... -> c(n-1) -> tet, rooted at c0.
std::vector<std::string> chainOf(int n) {
  std::vector<std::string> lines = {"root = \"c0\""};
  for (int k = 0; k < n; ++k) {
    const std::string next = k + 1 < n ? "c" + std::to_string(k + 1) : "tet";
    lines.insert(lines.end(), {"[[nodes]]", "name = \"c" + std::to_string(k) + "\"",
                               "instances = [{ node = \"" + next + "\" }]"});
  }
  return withTet(lines);
}

TEST(TomlSceneErrors, ChainsDeeperThan64LevelsAreRefusedAtTheInstance) {
  // c0 .. c64 are 64 instance levels; c64's instance of c65 is the 65th (line 3k + 4 of node k).
  for (int n : {66, 100000})
    expectTomlError({chainOf(n), 3 * 64 + 4, "nodes[64].instances[0].node", "deeper than 64 levels"});
}

TEST(TomlScene, AChainOf63NodesAndItsMeshIsWithinTheBound) {
  ScratchDir dir;
  dir.write("tet.obj", kTetrahedron);
  // 62 instances between the nodes, one to the mesh file's node: 63 levels.
  const Scene s = loadScene(dir.write("chain.toml", joinLines(chainOf(63))).string(), true);
  EXPECT_EQ(s.instanceDepth, 63);
  EXPECT_EQ(s.expandedTriangles(), 4u);
}

TEST(TomlSceneErrors, ExpandedCountsBeyond2To62AreRefused) {
  // Each level instances the one below 10 times: 4 * 10^30 triangles at the root; l17 (4e18)
  // is the last level under 2^62.
  std::vector<std::string> lines = {"root = \"l29\""};
  for (int k = 0; k < 30; ++k) {
    std::string list;
    for (int i = 0; i < 10; ++i)
      list += std::string(i ? ", " : "") + "{ node = \"" + (k ? "l" + std::to_string(k - 1) : "tet") + "\" }";
    lines.insert(lines.end(), {"[[nodes]]", "name = \"l" + std::to_string(k) + "\"", "instances = [" + list + "]"});
  }
  ScratchDir dir;
  dir.write("tet.obj", kTetrahedron);
  const auto path = dir.write("huge.toml", joinLines(withTet(lines)));
  const std::string e = errorOf([&] { loadScene(path.string(), true); });
  EXPECT_NE(e.find(path.string()), std::string::npos) << e;
  EXPECT_NE(e.find("node 'l18' expands to more than 2^62 triangles"), std::string::npos) << e;
}

TEST(TomlSceneErrors, TransformErrors) {
  expectTomlError({withTet({"root = \"n\"", "[[nodes]]", "name = \"n\"",
                            "instances = [{ node = \"tet\", matrix = "
                            "[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,1,1]] }]"}),
                   4, "nodes[0].instances[0].matrix[3]", "affine"});
  expectTomlError({withTet({"root = \"n\"", "[[nodes]]", "name = \"n\"",
                            "instances = [{ node = \"tet\", rotate = { axis = [0, 1, 0] } }]"}),
                   4, "nodes[0].instances[0].rotate.degrees", "missing required field"});
  expectTomlError(
      {withTet({"root = \"n\"", "[[nodes]]", "name = \"n\"",
                "instances = [{ node = \"tet\", translate = [1, 2, 3], matrix = [] }]"}),
       4, "nodes[0].instances[0].matrix", "cannot be combined"});
}

TEST(TomlSceneErrors, MeshAndGeneratorErrorsNameTheLine) {
  expectTomlError({{"root = \"m\"", "[[meshes]]", "name = \"m\"", "file = \"absent.obj\""},
                   4,
                   "meshes[0].file",
                   "absent.obj: file not found"});
  expectTomlError({{"root = \"g\"", "[[generators]]", "name = \"g\"", "spec = \"city?blocks=0\""},
                   4,
                   "generators[0].spec",
                   "blocks"});
  expectTomlError({{"root = \"g\"", "[[generators]]", "name = \"g\"", "spec = \"city?blocks=2\"",
                    "[camera]", "position = [0, 0, 0]", "look_at = [0, 0, 0]"},
                   5,
                   "camera.look_at",
                   "must differ"});
}

TEST(TomlSceneErrors, MissingFile) {
  const std::string e = errorOf([] { loadScene("/nonexistent/dir/scene.toml", true); });
  EXPECT_NE(e.find("/nonexistent/dir/scene.toml: file not found"), std::string::npos) << e;
}

}  // namespace
}  // namespace lzb
