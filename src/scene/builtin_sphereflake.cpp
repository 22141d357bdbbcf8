// sphereflake?depth=D: Haines' sphereflake (SPD "balls"): a sphere with 9 children of a third
// of its radius on its surface, recursively. Built by nested instancing of one 200-triangle unit
// sphere: node flake_k = the sphere + 9 scaled, rotated instances of flake_(k-1). So the stored
// part is 200 triangles and D + 2 nodes, and the expanded count is 200 * (9^(D+1) - 1) / 8.
#include <array>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>

#include "src/scene/builtin_generators.hpp"
#include "src/scene/mesh_builder.hpp"

namespace lzb {

namespace {

constexpr int kSlices = 10;  // around the axis
constexpr int kStacks = 11;  // pole to pole: 2 * kSlices * (kStacks - 1) = 200 triangles
constexpr Rgba8 kColor = packRgba8(214, 196, 160);

// The 9 child directions of SPD's balls.c: a triangle of directions tilted towards +z, repeated
// at three rotations of 120 degrees about z.
std::array<glm::dvec3, 9> childDirections() {
  const double d = 1.0 / std::sqrt(2.0);
  glm::dvec3 trio[3] = {{d, d, 0.0}, {d, 0.0, -d}, {0.0, d, -d}};
  const glm::dmat4 tilt = glm::rotate(glm::dmat4(1.0), std::asin(2.0 / std::sqrt(6.0)),
                                      glm::normalize(glm::dvec3(1.0, -1.0, 0.0)));
  std::array<glm::dvec3, 9> dirs;
  for (int set = 0; set < 3; ++set) {
    const glm::dmat4 spin =
        glm::rotate(glm::dmat4(1.0), set * 2.0 * std::numbers::pi / 3.0, glm::dvec3(0.0, 0.0, 1.0));
    for (int k = 0; k < 3; ++k)
      dirs[size_t(3 * set + k)] =
          glm::normalize(glm::dvec3(spin * tilt * glm::dvec4(trio[k], 0.0)));
  }
  return dirs;
}

// A rotation taking +z to dir (the child's "away from parent" axis).
glm::dmat4 rotateZTo(const glm::dvec3& dir) {
  const glm::dvec3 z(0.0, 0.0, 1.0);
  const glm::dvec3 axis = glm::cross(z, dir);
  const double s = glm::length(axis), c = glm::dot(z, dir);
  if (s < 1e-12)
    return c > 0 ? glm::dmat4(1.0) : glm::rotate(glm::dmat4(1.0), std::numbers::pi, {1, 0, 0});
  return glm::rotate(glm::dmat4(1.0), std::atan2(s, c), axis / s);
}

}  // namespace

Generated generateSphereflake(Scene& scene, BuiltinParams& params) {
  const int64_t depth = params.integer("depth", 3, 0, 16);
  params.finish();
  const uint32_t sphere = scene.addNode("sphereflake/sphere");
  MeshBuilder(scene.nodes[sphere].mesh, scene.stats).sphere(kSlices, kStacks, kColor);

  const std::array<glm::dvec3, 9> dirs = childDirections();
  uint32_t child = 0;
  for (int64_t k = 0; k <= depth; ++k) {
    const uint32_t node = scene.addNode("sphereflake/level" + std::to_string(k));
    scene.nodes[node].instances.push_back({sphere, glm::dmat4(1.0)});
    if (k > 0)
      for (const glm::dvec3& d : dirs) {
        // On the parent's surface: centre at distance 1 + 1/3, radius 1/3, facing away.
        const glm::dmat4 m = glm::translate(glm::dmat4(1.0), d * (4.0 / 3.0)) * rotateZTo(d) *
                             glm::scale(glm::dmat4(1.0), glm::dvec3(1.0 / 3.0));
        scene.nodes[node].instances.push_back({child, m});
      }
    child = node;
  }
  // The flake grows along +z in its own frame; stand it up along +y.
  Generated out;
  out.root = scene.addNode("sphereflake");
  scene.nodes[out.root].instances.push_back(
      {child, glm::rotate(glm::dmat4(1.0), -0.5 * std::numbers::pi, glm::dvec3(1.0, 0.0, 0.0))});
  CameraSpec camera;
  camera.position = {3.2, 2.6, 4.4};
  camera.lookAt = {0.0, 0.35, 0.0};
  camera.fovyDegrees = 45.0;
  out.camera = camera;
  return out;
}

}  // namespace lzb
