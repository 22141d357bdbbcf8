#include "src/scene/mesh_file.hpp"

#include <assimp/material.h>
#include <assimp/scene.h>

#include <algorithm>
#include <array>
#include <assimp/Importer.hpp>
#include <cmath>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <string>
#include <vector>

#include "src/core/error.hpp"
#include "src/scene/file_check.hpp"
#include "src/scene/mesh_builder.hpp"
#include "src/scene/mesh_faces.hpp"
#include "src/scene/mesh_stream.hpp"

namespace lzb {

namespace {

glm::dmat4 toGlm(const aiMatrix4x4& m) {
  // assimp matrices are row-major (a1..a4 is the first row); glm is column-major.
  glm::dmat4 r;
  const ai_real* rows[4] = {&m.a1, &m.b1, &m.c1, &m.d1};
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) r[col][row] = double(rows[row][col]);
  return r;
}

bool finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// An aiMesh with the transform into the frame its triangles are stored in.
struct MeshUse {
  const aiMesh* mesh;
  glm::dmat4 transform;
};

// Where to store `uses` around (mesh_faces.hpp): the origin, or the centre of their bounds when
// that lies far away relative to their size (float positions far from 0 lose their low bits; the
// offset then goes into a double-precision instance translation instead).
glm::dvec3 originOf(const std::vector<MeshUse>& uses) {
  Bounds b;
  for (const MeshUse& u : uses)
    for (unsigned i = 0; i < u.mesh->mNumVertices; ++i) {
      const aiVector3D& v = u.mesh->mVertices[i];
      const glm::dvec3 p = storedVertex(u.transform, v.x, v.y, v.z, glm::dvec3(0.0));
      if (finite(p)) b.extend(p);
    }
  return storageOrigin(b);
}

class FileLoader {
 public:
  FileLoader(Scene& scene, const std::filesystem::path& path, const std::optional<Rgba8>& color)
      : scene_(scene), path_(path), where_(path.string()), override_(color) {}

  uint32_t load();

 private:
  void validate(const aiScene& ai);
  void walk(const aiNode& node, const glm::dmat4& parent);
  // Stores the triangles of `uses` around `origin` into mesh (polygons split, colours chosen,
  // dropped triangles counted).
  void build(const std::vector<MeshUse>& uses, const glm::dvec3& origin, Mesh& mesh);
  Rgba8 materialColor(unsigned index) const;

  Scene& scene_;
  std::filesystem::path path_;
  std::string where_;
  std::optional<Rgba8> override_;
  const aiScene* ai_ = nullptr;
  LoadStats stats_;
  std::vector<int> uses_;          // per aiMesh: how many aiNodes reference it
  std::vector<int64_t> meshNode_;  // per aiMesh used several times: its node, -1 not built yet,
                                   // -2 no valid triangle
  std::vector<glm::dvec3> meshOrigin_;  // and the origin its triangles are stored around
  std::vector<MeshUse> baked_;          // meshes used once, into the file's frame
  std::vector<Instance> instances_;     // meshes used several times
};

void FileLoader::validate(const aiScene& ai) {
  for (unsigned m = 0; m < ai.mNumMeshes; ++m) {
    const aiMesh& mesh = *ai.mMeshes[m];
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      require(face.mNumIndices > 0, where_, [&] {
        return "malformed or truncated: face " + std::to_string(f) + " of mesh " +
               std::to_string(m) + " has no vertices";
      });
      for (unsigned k = 0; k < face.mNumIndices; ++k)
        require(face.mIndices[k] < mesh.mNumVertices, where_, [&] {
          return "malformed: face " + std::to_string(f) + " of mesh " + std::to_string(m) +
                 " uses vertex " + std::to_string(face.mIndices[k]) + " of " +
                 std::to_string(mesh.mNumVertices);
        });
    }
  }
}

Rgba8 FileLoader::materialColor(unsigned index) const {
  if (index >= ai_->mNumMaterials) return kDefaultMeshColor;
  const aiMaterial* mat = ai_->mMaterials[index];
  // Importers invent a white or grey material when the file has none: those mean "no colour".
  aiString name;
  if (mat->Get(AI_MATKEY_NAME, name) != AI_SUCCESS || name.length == 0 ||
      std::string(name.C_Str()) == AI_DEFAULT_MATERIAL_NAME)
    return kDefaultMeshColor;
  aiColor4D c;
  if (aiGetMaterialColor(mat, AI_MATKEY_BASE_COLOR, &c) == AI_SUCCESS ||
      aiGetMaterialColor(mat, AI_MATKEY_COLOR_DIFFUSE, &c) == AI_SUCCESS)
    return packRgb({c.r, c.g, c.b});
  return kDefaultMeshColor;
}

void FileLoader::build(const std::vector<MeshUse>& uses, const glm::dvec3& origin, Mesh& out) {
  MeshBuilder builder(out, stats_);
  FaceSplitter face;
  for (const MeshUse& use : uses) {
    const aiMesh& mesh = *use.mesh;
    if (!mesh.HasPositions()) {
      stats_.degenerate += mesh.mNumFaces;
      continue;
    }
    const Rgba8 plain = override_ ? *override_ : materialColor(mesh.mMaterialIndex);
    const bool vertexColors = mesh.HasVertexColors(0) && !override_;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& aface = mesh.mFaces[f];
      face.polygon.clear();
      for (unsigned k = 0; k < aface.mNumIndices; ++k) {
        const aiVector3D& v = mesh.mVertices[aface.mIndices[k]];
        face.polygon.push_back(storedVertex(use.transform, v.x, v.y, v.z, origin));
      }
      const auto rgb = [&](uint32_t k) {
        const aiColor4D& c = mesh.mColors[0][aface.mIndices[k]];
        return glm::vec3(c.r, c.g, c.b);
      };
      face.split(builder, stats_, [&](const std::array<uint32_t, 3>& t) {
        return vertexColors ? meanColour(rgb(t[0]), rgb(t[1]), rgb(t[2])) : plain;
      });
    }
  }
}

void FileLoader::walk(const aiNode& node, const glm::dmat4& parent) {
  const glm::dmat4 m = parent * toGlm(node.mTransformation);
  for (unsigned i = 0; i < node.mNumMeshes; ++i) {
    const unsigned k = node.mMeshes[i];
    if (k >= ai_->mNumMeshes)
      throw InputError(where_ + ": malformed: node references a missing mesh");
    if (uses_[k] == 1) {
      baked_.push_back({ai_->mMeshes[k], m});
      continue;
    }
    if (meshNode_[k] == -1) {
      const std::vector<MeshUse> local = {{ai_->mMeshes[k], glm::dmat4(1.0)}};
      const glm::dvec3 origin = originOf(local);
      Mesh mesh;
      build(local, origin, mesh);
      if (mesh.empty()) {
        meshNode_[k] = -2;
        continue;
      }
      const std::string meshName = ai_->mMeshes[k]->mName.C_Str();
      const std::string name =
          path_.stem().string() + "/" + (meshName.empty() ? "mesh" + std::to_string(k) : meshName);
      const uint32_t id = scene_.addNode(name);
      scene_.nodes[id].mesh = std::move(mesh);
      meshNode_[k] = id;
      meshOrigin_[k] = origin;
    }
    if (meshNode_[k] >= 0)
      instances_.push_back(
          {uint32_t(meshNode_[k]), m * glm::translate(glm::dmat4(1.0), meshOrigin_[k])});
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) walk(*node.mChildren[c], m);
}

uint32_t FileLoader::load() {
  std::error_code ec;
  require(std::filesystem::exists(path_, ec), where_, "file not found");
  require(std::filesystem::is_regular_file(path_, ec), where_, "not a regular file");
  require(bool(std::ifstream(path_, std::ios::binary)), where_, "cannot be read (permission?)");
  checkMeshFileComplete(path_);

  Assimp::Importer importer;
  // No post-processing: assimp's Triangulate aborts on some malformed input and FindDegenerates
  // would drop triangles uncounted; both are done here instead.
  ai_ = importer.ReadFile(path_.string(), 0);
  if (!ai_) throw InputError(where_ + ": cannot load mesh: " + importer.GetErrorString());
  require(ai_->mRootNode != nullptr, where_, "malformed: no scene hierarchy");
  validate(*ai_);

  uses_.assign(ai_->mNumMeshes, 0);
  meshNode_.assign(ai_->mNumMeshes, -1);
  meshOrigin_.assign(ai_->mNumMeshes, glm::dvec3(0.0));
  const auto count = [&](const aiNode& node, auto&& self) -> void {
    for (unsigned i = 0; i < node.mNumMeshes; ++i)
      if (node.mMeshes[i] < ai_->mNumMeshes) ++uses_[node.mMeshes[i]];
    for (unsigned c = 0; c < node.mNumChildren; ++c) self(*node.mChildren[c], self);
  };
  count(*ai_->mRootNode, count);
  walk(*ai_->mRootNode, glm::dmat4(1.0));

  const glm::dvec3 origin = originOf(baked_);
  Mesh baked;
  build(baked_, origin, baked);
  const std::string name = path_.stem().string();
  require(!baked.empty() || !instances_.empty(), where_,
          "no valid triangles (" + std::to_string(stats_.degenerate) + " degenerate, " +
              std::to_string(stats_.nonFinite) + " non-finite dropped)");
  scene_.stats.merge(stats_);
  const uint32_t file = scene_.addNode(name);
  if (origin == glm::dvec3(0.0) || baked.empty()) {
    scene_.nodes[file].mesh = std::move(baked);
  } else {
    const uint32_t geometry = scene_.addNode(name + "/recentred");
    scene_.nodes[geometry].mesh = std::move(baked);
    scene_.nodes[file].instances.push_back({geometry, glm::translate(glm::dmat4(1.0), origin)});
  }
  for (const Instance& inst : instances_) scene_.nodes[file].instances.push_back(inst);
  return file;
}

// A file the streaming reader gives exactly as the loader would (mesh_stream.hpp), read into
// the model chunk by chunk: no assimp copy of the file beside the model (on a 10^7-triangle
// binary PLY that copy was the load's peak, ~100 bytes a triangle). Nullopt for any other file,
// and for one the reader refuses, so that the loader reads it and words its errors as always.
std::optional<uint32_t> addStreamedFile(Scene& scene, const std::filesystem::path& path,
                                        const std::optional<Rgba8>& colorOverride) {
  if (!MeshStream::streams(path)) return std::nullopt;
  std::unique_ptr<MeshStream> stream;
  try {
    std::string why;
    stream = MeshStream::open(path, why);
  } catch (const InputError&) {
    return std::nullopt;
  }
  if (!stream) return std::nullopt;
  const auto [file, holder] = stream->addNodes(scene);
  Mesh& mesh = scene.nodes[holder].mesh;
  mesh.indices.reserve(3 * stream->triangles());
  stream->forEachChunk([&](const Mesh& chunk) { mesh.append(chunk); });
  if (colorOverride) mesh.colors.assign(1, *colorOverride);
  scene.stats.merge(stream->stats());
  return file;
}

}  // namespace

uint32_t addMeshFile(Scene& scene, const std::filesystem::path& path,
                     const std::optional<Rgba8>& colorOverride, MeshReader reader) {
  if (reader == MeshReader::kStreamWhereExact)
    if (const std::optional<uint32_t> file = addStreamedFile(scene, path, colorOverride))
      return *file;
  return FileLoader(scene, path, colorOverride).load();
}

}  // namespace lzb
