#pragma once
// The triangles a sample tree is built from, as a stream: world vertices, colour and expanded ID,
// in expanded-ID order, the same on every pass. The external construction (external_build.hpp)
// reads it several times instead of holding it; the in-memory one gathers it (tree_input.hpp).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <span>
#include <string>

#include <glm/glm.hpp>

#include "src/core/color.hpp"
#include "src/core/scene.hpp"
#include "src/core/scene_outline.hpp"
#include "src/sampletree/scratch_file.hpp"

namespace lzb::sampletree {

// One triangle as streamed and as spilled to disk (48 bytes, no padding).
struct StreamTriangle {
  glm::vec3 v[3];
  Rgba8 colour;
  uint64_t id;
};
static_assert(sizeof(StreamTriangle) == 48, "spill files keep triangles byte for byte");

using TriangleSink = std::function<void(std::span<const StreamTriangle>)>;

class TriangleStream {
 public:
  virtual ~TriangleStream() = default;
  // The input, for messages.
  virtual const std::string& where() const = 0;
  // Triangles a pass is expected to give (for progress lines; a pass counts the real number).
  virtual uint64_t expected() const = 0;
  // Hands every triangle to sink, in batches, in expanded-ID order.
  virtual void forEach(const TriangleSink& sink) const = 0;
  // True when every pass makes the triangles anew (a generator): a copy on disk reads faster.
  virtual bool regenerates() const { return false; }
  // The outline of the scene the triangles make, as loadScene would give it (kept in the store so
  // a render need not load the scene); valid after one pass.
  virtual SceneOutline outline() const = 0;
};

// A loaded scene's expanded triangles, instances flattened.
class SceneStream : public TriangleStream {
 public:
  explicit SceneStream(const Scene& scene) : scene_(scene) {}
  const std::string& where() const override { return scene_.source; }
  uint64_t expected() const override { return scene_.expandedTriangles(); }
  void forEach(const TriangleSink& sink) const override;
  SceneOutline outline() const override { return outlineOf(scene_); }

 private:
  const Scene& scene_;
};

// One node's meshes handed out in chunks on every pass (no instances: the IDs count up from 0),
// placed into the world by `placement` as the loaded node is, so the world vertices are
// SceneStream's bit for bit (even -0.0 becomes +0.0 the same way). A generator (builtin:landscape)
// makes them anew each pass: regenerates() lets the build copy them once. A streaming file reader
// (src/scene/ply_stream.hpp) reads them again: that costs less disk than a 48-byte-a-triangle copy.
class MeshChunkStream : public TriangleStream {
 public:
  // Hands out the chunks, returns the triangles kept and dropped.
  using Source = std::function<LoadStats(const std::function<void(const Mesh&)>&)>;
  enum class Kind { kGenerator, kFile };
  // base: the outline's source, light and camera (the counts and bounds come from a pass).
  MeshChunkStream(SceneOutline base, uint64_t expected, Source source, Kind kind,
                  const glm::dmat4& placement = glm::dmat4(1.0))
      : outline_(std::move(base)), expected_(expected), source_(std::move(source)), kind_(kind),
        placement_(placement) {}
  const std::string& where() const override { return outline_.source; }
  uint64_t expected() const override { return expected_; }
  void forEach(const TriangleSink& sink) const override;
  bool regenerates() const override { return kind_ == Kind::kGenerator; }
  SceneOutline outline() const override;

 private:
  mutable SceneOutline outline_;
  mutable Bounds nodeBounds_;  // the node's own frame, as Scene::finalize bounds it
  mutable bool passed_ = false;
  uint64_t expected_;
  Source source_;
  Kind kind_;
  glm::dmat4 placement_;
};

// Another stream read ahead by a thread of its own, a few batches at most, so producing the
// triangles (a generator, a file) overlaps with what the sink does with them.
class ReadAheadStream : public TriangleStream {
 public:
  explicit ReadAheadStream(const TriangleStream& in, size_t batches = 4) : in_(in), depth_(batches) {}
  const std::string& where() const override { return in_.where(); }
  uint64_t expected() const override { return in_.expected(); }
  void forEach(const TriangleSink& sink) const override;
  SceneOutline outline() const override { return in_.outline(); }

 private:
  const TriangleStream& in_;
  size_t depth_;
};

// Another stream copied to a scratch file on its first pass and read back from it on the later
// ones (for a generator: 48 bytes a triangle on disk instead of generating it again).
class CopiedStream : public TriangleStream {
 public:
  CopiedStream(const TriangleStream& in, std::filesystem::path copy);
  ~CopiedStream() override;
  const std::string& where() const override { return in_.where(); }
  uint64_t expected() const override { return in_.expected(); }
  void forEach(const TriangleSink& sink) const override;
  SceneOutline outline() const override { return in_.outline(); }
  // Removes the copy (no pass may follow).
  void drop();

 private:
  const TriangleStream& in_;
  std::unique_ptr<ScratchFile> copy_;
  mutable bool copied_ = false;
};

}  // namespace lzb::sampletree
