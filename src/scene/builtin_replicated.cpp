// replicated?mesh=PATH&k=K&levels=L: a mesh file (through the mesh loader) on a k x k grid in
// the x-z plane, the grid itself on a k x k grid, L times: k^(2L) copies by nested instancing.
// Spacing: 1.25 times the mesh's bounds along x and z (a flat side uses a tenth of the largest).
#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>

#include "src/core/camera.hpp"
#include "src/core/error.hpp"
#include "src/scene/builtin_generators.hpp"
#include "src/scene/mesh_file.hpp"

namespace lzb {

namespace {

struct Subtree {
  Bounds bounds;
  uint64_t triangles = 0;
};

// Bounds and expanded count of a node's subtree before the scene is finalized. Mesh files give
// acyclic, shallow subtrees, so plain recursion does.
Subtree subtree(const Scene& scene, uint32_t node) {
  Subtree out;
  const Node& n = scene.nodes[node];
  for (const glm::vec3& p : n.mesh.positions) out.bounds.extend(glm::dvec3(p));
  out.triangles = n.mesh.size();
  for (const Instance& inst : n.instances) {
    const Subtree child = subtree(scene, inst.node);
    out.bounds.extend(child.bounds.transformed(inst.transform));
    out.triangles += child.triangles;
  }
  return out;
}

}  // namespace

Generated generateReplicated(Scene& scene, BuiltinParams& params,
                             const std::filesystem::path& baseDir) {
  const std::string mesh = params.text("mesh", "");
  const int64_t k = params.integer("k", 4, 1, 1024);
  const int64_t levels = params.integer("levels", 1, 0, 32);
  params.finish();
  require(!mesh.empty(), params.where("mesh"), "required: the mesh file to replicate");
  std::filesystem::path path(mesh);
  if (path.is_relative() && !baseDir.empty()) path = baseDir / path;

  uint32_t child = 0;
  try {
    child = addMeshFile(scene, path);
  } catch (const InputError& e) {
    throw InputError(params.where("mesh") + ": " + e.what());
  }
  const Subtree file = subtree(scene, child);
  requireIdSpace(params, "levels", file.triangles, uint64_t(k * k), levels);
  const Bounds& b = file.bounds;
  const glm::dvec3 e = b.extent();
  const double largest = std::max({e.x, e.y, e.z, 1e-30});
  double sx = 1.25 * std::max(e.x, 0.1 * largest), sz = 1.25 * std::max(e.z, 0.1 * largest);
  // Centre the mesh on the origin of the first grid.
  glm::dmat4 centre =
      glm::translate(glm::dmat4(1.0), glm::dvec3(-b.center().x, -b.lo.y, -b.center().z));
  for (int64_t level = 1; level <= levels; ++level) {
    const uint32_t node = scene.addNode("replicated/level" + std::to_string(level));
    for (int64_t j = 0; j < k; ++j)
      for (int64_t i = 0; i < k; ++i) {
        const glm::dvec3 at((double(i) - 0.5 * double(k - 1)) * sx, 0.0,
                            (double(j) - 0.5 * double(k - 1)) * sz);
        scene.nodes[node].instances.push_back(
            {child, glm::translate(glm::dmat4(1.0), at) * centre});
      }
    child = node;
    centre = glm::dmat4(1.0);
    sx *= double(k);
    sz *= double(k);
  }
  Generated out;
  out.root = child;
  if (levels == 0) return out;  // the mesh itself: framed on its bounds by the caller
  // Above the grid's near edge, looking across it.
  const double half = 0.5 * std::max(sx, sz);
  CameraSpec camera;
  camera.position = {0.0, 0.25 * half + e.y * 2.0, 1.1 * half};
  camera.lookAt = {0.0, 0.0, -0.3 * half};
  out.camera = camera;
  return out;
}

}  // namespace lzb
