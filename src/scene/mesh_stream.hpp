#pragma once
// A mesh file read for streaming, never whole: its vertices held (12 bytes a vertex, 24 with
// colours), its faces read from the file in chunks on every pass. PLY (binary, or ASCII),
// OFF and OBJ, each only where it is certain to give the triangles `loadScene` makes of the file
// (assimp 5.2 and mesh_file.cpp), bit for bit and in their ID order, with the loaded scene's
// placement (recentred far geometry). For builders that cannot hold the scene: the sample tree's
// external build, a rank's share under --distribute data (chunked_scene.hpp).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "src/core/bounds.hpp"
#include "src/core/scene.hpp"
#include "src/scene/mesh_builder.hpp"
#include "src/scene/mesh_faces.hpp"

namespace lzb {

// Why a file is left to the loader: read on, a streaming reader might not give its triangles.
struct NotStreamed {
  std::string why;
};

// The vertices a streamed file holds, and the frame its triangles are stored in.
struct HeldVertices {
  std::vector<glm::vec3> positions, colours;  // colours: components as the file gives them, or none
  glm::dvec3 origin{0.0};                     // the storage origin (mesh_faces.hpp)
  glm::dmat4 placement{1.0};  // stored frame -> world, as the loaded scene places it

  // Sets the origin and placement from the bounds of the finite positions (as the loader does).
  void place(const Bounds& finite);
  uint64_t bytes() const { return (positions.capacity() + colours.capacity()) * sizeof(glm::vec3); }
};

// Faces given as indices into held vertices, split and coloured as the loader splits them
// (mesh_faces.hpp), handed out in meshes of about `chunk` triangles.
class FaceChunks {
 public:
  FaceChunks(const HeldVertices& held, const std::function<void(const Mesh&)>& out, size_t chunk);
  // One face; its indices are below positions.size().
  void face(const std::vector<uint32_t>& index);
  // Hands out the last chunk; returns what was kept and dropped.
  LoadStats finish();
  // The triangles not handed out yet, taken whole (for a caller that keeps every triangle).
  Mesh take() { return std::exchange(mesh_, Mesh()); }

 private:
  const HeldVertices& held_;
  const std::function<void(const Mesh&)>& out_;
  size_t chunk_;
  LoadStats stats_;
  Mesh mesh_;
  MeshBuilder builder_{mesh_, stats_};
  FaceSplitter splitter_;
};

class MeshStream {
 public:
  // Opens `path` by its extension (.ply, .off, .obj) and reads it once: the vertices held, every
  // face checked and split (the counts of kept and dropped triangles). Returns nullptr with `why`
  // set for a format not streamed or a file that the loader might read otherwise than the reader
  // would: the caller then loads it (after this reading). Throws InputError naming the file for
  // a missing, unreadable, truncated or malformed one, as the loader would refuse it.
  static std::unique_ptr<MeshStream> open(const std::filesystem::path& path, std::string& why);
  // Whether `path` names a format open() reads (by its extension, in any case).
  static bool streams(const std::filesystem::path& path);
  virtual ~MeshStream();

  const std::string& where() const { return where_; }
  uint64_t triangles() const { return stats_.loaded; }
  const LoadStats& stats() const { return stats_; }
  uint64_t heldBytes() const { return held_.bytes(); }
  const glm::dmat4& placement() const { return held_.placement; }
  // The box of the triangles' vertices in the stored frame (the loaded node's own box).
  const Bounds& storedBounds() const { return storedBounds_; }
  // Hands out the triangles in file order (the loaded scene's ID order) in meshes of about
  // `chunk` triangles, in the stored frame. Throws InputError if the file changed under it.
  void forEachChunk(const std::function<void(const Mesh&)>& out, size_t chunk = 1 << 16) const;
  // Adds the nodes the loader makes for this file to `scene`: the file's node, named after it,
  // and the node its triangles go to (a "/recentred" child placed by placement() when that is
  // not the identity, else the file's node). Returns {file, holder}.
  std::pair<uint32_t, uint32_t> addNodes(Scene& scene) const;

 protected:
  explicit MeshStream(const std::filesystem::path& path);
  // Reads every face from the file into `faces` (a pass after open's).
  virtual void readFaces(FaceChunks& faces) const = 0;
  // Open's reading of the faces: every one checked and split, the triangles counted.
  void countFaces();
  // After open's reading: refuses a file without a valid triangle, as the loader does.
  void requireTriangles() const;

  std::filesystem::path path_;
  std::string where_;
  HeldVertices held_;
  LoadStats stats_;
  Bounds storedBounds_;
  // Open's reading hands its chunks here: they extend storedBounds_.
  const std::function<void(const Mesh&)> boundStored_;
};

}  // namespace lzb
