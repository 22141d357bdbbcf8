#include "src/cli/export_command.hpp"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <vector>

#include "src/core/atomic_file.hpp"
#include "src/core/error.hpp"
#include "src/scene/load.hpp"

namespace lzb {

namespace {

#pragma pack(push, 1)
struct PlyFace {
  uint8_t count = 3;
  int32_t index[3];
  uint8_t rgb[3];
};
#pragma pack(pop)

// Each placed mesh's shared vertices, once.
uint64_t placedVertices(const Scene& scene, const std::vector<DrawItem>& items) {
  uint64_t vertices = 0;
  for (const DrawItem& item : items) vertices += scene.nodes[item.node].mesh.positions.size();
  return vertices;
}

void writePly(const Scene& scene, const std::vector<DrawItem>& items,
              const std::filesystem::path& path) {
  const uint64_t triangles = scene.expandedTriangles();
  const uint64_t vertices = placedVertices(scene, items);
  std::ofstream out(path, std::ios::binary);
  out << "ply\nformat binary_little_endian 1.0\ncomment lzb export of " << scene.source
      << "\nelement vertex " << vertices
      << "\nproperty float x\nproperty float y\nproperty float z\n"
      << "element face " << triangles
      << "\nproperty list uchar int vertex_indices\nproperty uchar red\nproperty uchar green\n"
         "property uchar blue\nend_header\n";
  for (const DrawItem& item : items) {
    const Mesh& mesh = scene.nodes[item.node].mesh;
    for (const glm::vec3& p : mesh.positions) {
      const glm::vec3 w(item.transform * glm::dvec4(glm::dvec3(p), 1.0));
      out.write(reinterpret_cast<const char*>(&w), sizeof(w));
    }
  }
  int32_t base = 0;
  for (const DrawItem& item : items) {
    const Mesh& mesh = scene.nodes[item.node].mesh;
    for (size_t t = 0; t < mesh.size(); ++t) {
      PlyFace f;
      for (int k = 0; k < 3; ++k) f.index[k] = base + int32_t(mesh.indices[3 * t + size_t(k)]);
      for (int k = 0; k < 3; ++k) f.rgb[k] = channel(mesh.color(t), k);
      out.write(reinterpret_cast<const char*>(&f), sizeof(f));
    }
    base += int32_t(mesh.positions.size());
  }
  require(bool(out), path.string(), "write failed");
}

}  // namespace

void addExportOptions(CLI::App& c, ExportArgs& a) {
  c.add_option("scene", a.scene, "mesh file, scene.toml or builtin:NAME?key=value")->required();
  c.add_option("out", a.out, "the PLY file to write")->required();
  c.add_option("--max-triangles", a.maxTriangles, "refuse larger expanded scenes")
      ->capture_default_str();
  c.add_flag("--quiet,-q", a.quiet, "no progress lines");
}

int runExport(const ExportArgs& a, const mpi::Group& g) {
  const Scene scene = loadScene(a.scene, a.quiet || !g.root());
  require(scene.expandedTriangles() <= a.maxTriangles, a.scene,
          std::to_string(scene.expandedTriangles()) + " triangles expanded, more than --max-triangles " +
              std::to_string(a.maxTriangles));
  const std::vector<DrawItem> items = flattenScene(scene);
  require(placedVertices(scene, items) <= uint64_t(INT32_MAX), a.scene,
          "more than 2^31 - 1 vertices placed: a PLY face indexes them with int");
  if (!g.root()) return 0;
  writeAtomically(a.out, [&](const std::filesystem::path& tmp) { writePly(scene, items, tmp); });
  if (!a.quiet)
    std::printf("lzb: %llu triangles written to %s\n",
                (unsigned long long)scene.expandedTriangles(), a.out.c_str());
  return 0;
}

}  // namespace lzb
