#include "src/core/shading.hpp"

#include <gtest/gtest.h>

#include "src/core/camera.hpp"
#include "src/core/framebuffer.hpp"

namespace lzb {
namespace {

// Two triangles facing the camera and one turned away, each its own colour.
Scene threeTriangles() {
  Scene s;
  s.root = s.addNode("root");
  Mesh& m = s.nodes[s.root].mesh;
  m.add({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, packRgba8(200, 10, 10, 255));
  m.add({0, 0, -1}, {1, 0, -1}, {1, 1, -1}, packRgba8(10, 200, 10, 255));
  m.add({0, 0, -2}, {0, 1, -2}, {1, 0, -2}, packRgba8(10, 10, 200, 255));
  s.finalize();
  return s;
}

TEST(Shading, ListedPixelsGetTheWholeFramesColoursAndNoOthersChange) {
  const Scene scene = threeTriangles();
  CameraSpec spec;
  spec.position = {0.3, 0.3, 5.0};
  spec.lookAt = {0.3, 0.3, 0.0};
  spec.nearPlane = 0.1;
  spec.farPlane = 100.0;
  const Camera camera(spec, 8, 4);
  Framebuffer whole;
  whole.resize(8, 4);
  for (size_t i = 0; i < whole.size(); ++i) whole.id[i] = i % 4 == 3 ? kNoId : i % 3;
  shadeFromIds(scene, camera, whole);
  ASSERT_NE(whole.color[0], whole.color[1]);  // the triangles really shade apart
  ASSERT_NE(whole.color[1], whole.color[2]);

  const Rgba8 untouched = packRgba8(1, 2, 3, 4);
  std::vector<Rgba8> colors(whole.size(), untouched);
  const std::vector<uint32_t> listed = {0, 2, 3, 5, 6, 7, 30, 31};
  shadePixels(scene, camera, listed, whole.id, colors);
  size_t next = 0;
  for (uint32_t i = 0; i < whole.size(); ++i)
    if (next < listed.size() && listed[next] == i)
      EXPECT_EQ(colors[i], whole.color[listed[next++]]) << "pixel " << i;
    else
      EXPECT_EQ(colors[i], untouched) << "pixel " << i;
}

}  // namespace
}  // namespace lzb
