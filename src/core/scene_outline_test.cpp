#include "src/core/scene_outline.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "src/core/error.hpp"

namespace lzb {
namespace {

// A scene with every part an outline keeps: a placed instance (bounds through a transform), a
// camera, keyframes, an image size, a light and dropped triangles.
Scene outlinedScene() {
  Scene s;
  s.source = "outline test";
  const uint32_t leaf = s.addNode("leaf");
  s.nodes[leaf].mesh.add({0.1f, -0.0f, 1.0f / 3.0f}, {1, 0, 0}, {0, 1, 0}, 0xff102030u);
  s.root = s.addNode("root");
  s.nodes[s.root].instances.push_back({leaf, glm::translate(glm::dmat4(1.0), {1e7, 0.3, -2.0})});
  s.nodes[s.root].instances.push_back({leaf, glm::dmat4(1.0)});
  CameraSpec c;
  c.position = {1.0 / 3.0, 2.0, 7.0};
  c.fovyDegrees = 37.5;
  s.camera = c;
  s.keyframes = {c, CameraSpec{}};
  s.width = 320;
  s.light.direction = {0.1, 0.2, 0.7};
  s.light.ambient = 0.125;
  s.stats.degenerate = 3;
  s.finalize();
  return s;
}

TEST(SceneOutline, TextRoundTripsEveryFieldExactly) {
  const Scene s = outlinedScene();
  const SceneOutline o = parseOutline(outlineText(outlineOf(s)), "test");
  EXPECT_EQ(o.source, s.source);
  EXPECT_EQ(o.bounds.lo, s.bounds().lo);  // bit for bit: the camera frames the scene alike
  EXPECT_EQ(o.bounds.hi, s.bounds().hi);
  EXPECT_EQ(o.uniqueTriangles, 1u);
  EXPECT_EQ(o.expandedTriangles, 2u);
  EXPECT_EQ(o.nodes, 2u);
  EXPECT_EQ(o.instanceDepth, 1);
  EXPECT_EQ(o.stats.degenerate, 3u);
  EXPECT_EQ(o.light.direction, s.light.direction);
  EXPECT_EQ(o.light.ambient, 0.125);
  ASSERT_TRUE(o.camera.has_value());
  EXPECT_EQ(o.camera->position, s.camera->position);
  EXPECT_EQ(o.camera->fovyDegrees, 37.5);
  ASSERT_EQ(o.keyframes.size(), 2u);
  EXPECT_EQ(o.keyframes[1].up, CameraSpec{}.up);
  EXPECT_EQ(o.width, 320);
  EXPECT_FALSE(o.height.has_value());
  EXPECT_EQ(outlineText(o), outlineText(outlineOf(s)));
}

TEST(SceneOutline, SceneFromOutlineFramesLikeTheScene) {
  const Scene s = outlinedScene();
  const Scene o = sceneFromOutline(outlineOf(s));
  EXPECT_EQ(o.expandedTriangles(), s.expandedTriangles());
  EXPECT_EQ(o.bounds().lo, s.bounds().lo);
  EXPECT_EQ(o.bounds().hi, s.bounds().hi);
  EXPECT_EQ(o.uniqueTriangles(), 0u);  // no triangles: only the method holding them renders it
  EXPECT_FALSE(o.resolve(0).has_value());
  EXPECT_EQ(o.keyframes.size(), 2u);
  EXPECT_EQ(o.light.ambient, s.light.ambient);
}

TEST(SceneOutline, SceneArgumentsNameOneSceneByTextOrFile) {
  EXPECT_TRUE(namesSameScene("builtin:city?blocks=2", "builtin:city?blocks=2"));
  EXPECT_FALSE(namesSameScene("builtin:city?blocks=2", "builtin:city?blocks=3"));
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "lzb_outline_names";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "a.ply") << "x";
  std::ofstream(dir / "b.ply") << "x";
  EXPECT_TRUE(namesSameScene((dir / "a.ply").string(), (dir / "." / "a.ply").string()));
  EXPECT_FALSE(namesSameScene((dir / "a.ply").string(), (dir / "b.ply").string()));
  EXPECT_FALSE(namesSameScene((dir / "gone.ply").string(), (dir / "." / "gone.ply").string()));
  std::filesystem::remove_all(dir);
}

TEST(SceneOutline, MalformedTextIsAnInputErrorNamingWhere) {
  for (const std::string text : {"", "{", "{\"source\": \"x\"}", "[1, 2]"}) {
    try {
      parseOutline(text, "store.lzbt");
      FAIL() << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("store.lzbt"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace lzb
