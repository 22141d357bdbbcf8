#include "src/scene/mesh_stream.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>

#include "src/core/error.hpp"
#include "src/scene/mesh_file.hpp"
#include "src/scene/obj_stream.hpp"
#include "src/scene/off_stream.hpp"
#include "src/scene/ply_stream.hpp"

namespace lzb {

void HeldVertices::place(const Bounds& finite) {
  origin = storageOrigin(finite);
  // The loaded scene: the file's node placed at the origin, or its recentred geometry translated.
  placement = origin == glm::dvec3(0.0) ? glm::dmat4(1.0)
                                        : glm::dmat4(1.0) * glm::translate(glm::dmat4(1.0), origin);
}

FaceChunks::FaceChunks(const HeldVertices& held, const std::function<void(const Mesh&)>& out,
                       size_t chunk)
    : held_(held), out_(out), chunk_(chunk) {}

void FaceChunks::face(const std::vector<uint32_t>& index) {
  splitter_.polygon.clear();
  for (const uint32_t i : index) {
    const glm::vec3& v = held_.positions[i];
    splitter_.polygon.push_back(storedVertex(glm::dmat4(1.0), v.x, v.y, v.z, held_.origin));
  }
  const std::vector<glm::vec3>& c = held_.colours;
  splitter_.split(builder_, stats_, [&](const std::array<uint32_t, 3>& t) {
    return c.empty() ? kDefaultMeshColor
                     : meanColour(c[index[t[0]]], c[index[t[1]]], c[index[t[2]]]);
  });
  if (mesh_.size() >= chunk_) {
    out_(mesh_);
    mesh_ = Mesh();
  }
}

LoadStats FaceChunks::finish() {
  if (!mesh_.empty()) out_(mesh_);
  mesh_ = Mesh();
  return stats_;
}

MeshStream::MeshStream(const std::filesystem::path& path)
    : path_(path), where_(path.string()), boundStored_([this](const Mesh& m) {
        for (const glm::vec3& p : m.positions) storedBounds_.extend(glm::dvec3(p));
      }) {
  std::error_code ec;
  require(std::filesystem::exists(path, ec), where_, "file not found");
  require(std::filesystem::is_regular_file(path, ec), where_, "not a regular file");
  require(bool(std::ifstream(path, std::ios::binary)), where_, "cannot be read (permission?)");
}

MeshStream::~MeshStream() = default;

namespace {

std::string lowerExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

}  // namespace

bool MeshStream::streams(const std::filesystem::path& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".ply" || ext == ".off" || ext == ".obj";
}

std::unique_ptr<MeshStream> MeshStream::open(const std::filesystem::path& path, std::string& why) {
  const std::string ext = lowerExtension(path);
  if (ext == ".ply") return PlyMeshStream::open(path, why);
  if (ext == ".off") return OffMeshStream::open(path, why);
  if (ext == ".obj") return ObjMeshStream::open(path, why);
  why = "a format read whole (not PLY, OFF or OBJ)";
  return nullptr;
}

std::pair<uint32_t, uint32_t> MeshStream::addNodes(Scene& scene) const {
  const std::string name = path_.stem().string();
  const uint32_t file = scene.addNode(name);
  if (held_.placement == glm::dmat4(1.0)) return {file, file};
  const uint32_t holder = scene.addNode(name + "/recentred");  // stored recentred, as loaded
  scene.nodes[file].instances.push_back({holder, held_.placement});
  return {file, holder};
}

void MeshStream::forEachChunk(const std::function<void(const Mesh&)>& out, size_t chunk) const {
  FaceChunks faces(held_, out, chunk);
  LoadStats pass;
  try {
    readFaces(faces);
    pass = faces.finish();
  } catch (const NotStreamed&) {
    pass.loaded = ~uint64_t(0);  // the first reading found none: the file changed
  }
  require(pass.loaded == stats_.loaded, where_, "changed while it was read");
}

void MeshStream::countFaces() {
  FaceChunks faces(held_, boundStored_, size_t(1) << 16);
  readFaces(faces);
  stats_ = faces.finish();
}

void MeshStream::requireTriangles() const {
  require(stats_.loaded > 0, where_,
          "no valid triangles (" + std::to_string(stats_.degenerate) + " degenerate, " +
              std::to_string(stats_.nonFinite) + " non-finite dropped)");
}

}  // namespace lzb
