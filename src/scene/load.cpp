#include "src/scene/load.hpp"

#include <malloc.h>  // malloc_trim (glibc)

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>

#include "src/core/error.hpp"
#include "src/scene/builtin.hpp"
#include "src/scene/mesh_file.hpp"
#include "src/scene/toml_scene.hpp"

namespace lzb {

namespace {

bool endsWithToml(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return s.size() >= 5 && s.compare(s.size() - 5, 5, ".toml") == 0;
}

}  // namespace

Scene loadScene(const std::string& spec, bool quiet) {
  require(!spec.empty(), "scene", "no scene given");
  Scene scene;
  const std::string prefix = "builtin:";
  if (spec.rfind(prefix, 0) == 0) {
    scene.source = spec;
    const Generated g = addBuiltin(scene, spec.substr(prefix.size()));
    scene.root = g.root;
    scene.camera = g.camera;
    scene.finalize();
  } else if (endsWithToml(spec)) {
    scene = loadTomlScene(spec);
  } else {
    scene.source = spec;
    scene.root = addMeshFile(scene, spec);
    scene.finalize();
  }
  require(scene.expandedTriangles() > 0, spec, "the scene has no triangles");
  if (!quiet) warnDropped(spec, scene.stats);
  releaseSlack(scene);
  return scene;
}

TomlOutline loadSceneDeferred(const std::string& spec, bool quiet, bool deferProcedural) {
  if (spec.rfind("builtin:", 0) == 0 || !endsWithToml(spec)) return {loadScene(spec, quiet), {}};
  TomlOutline outline = loadTomlOutline(spec, deferProcedural);
  require(outline.scene.expandedTriangles() > 0, spec, "the scene has no triangles");
  if (!quiet) warnDropped(spec, outline.scene.stats);
  releaseSlack(outline.scene);
  return outline;
}

void releaseSlack(Scene& scene) {
  for (Node& node : scene.nodes) {
    node.mesh.positions.shrink_to_fit();
    node.mesh.indices.shrink_to_fit();
    node.mesh.uniformColors();
    node.mesh.colors.shrink_to_fit();
  }
  // The loader's freed memory (assimp's copy of the file, grown arrays) would otherwise stay
  // resident in the heap, while the methods' structures (Embree's BVH) are mapped elsewhere.
  malloc_trim(0);
}

void warnDropped(const std::string& spec, const LoadStats& s) {
  if (s.degenerate > 0 || s.nonFinite > 0)
    std::cerr << "warning: " << spec << ": dropped " << s.degenerate << " degenerate and "
              << s.nonFinite << " non-finite triangles (" << s.loaded << " kept)\n";
}

}  // namespace lzb
