#include "src/scene/chunked_scene.hpp"

#include <cstdio>
#include <filesystem>

#include "src/scene/builtin.hpp"
#include "src/scene/load.hpp"
#include "src/scene/mesh_stream.hpp"

namespace lzb {

std::optional<ChunkedScene> openGeneratedScene(const std::string& spec) {
  if (spec.rfind("builtin:", 0) != 0) return std::nullopt;
  std::optional<BuiltinChunks> chunks = builtinChunks(spec.substr(std::string("builtin:").size()));
  if (!chunks) return std::nullopt;
  ChunkedScene c;
  c.base.source = spec;
  c.base.camera = chunks->camera;
  c.triangles = chunks->triangles;
  c.generated = true;
  c.procedural = chunks->procedural;
  c.chunks = std::move(chunks->generate);
  return c;
}

namespace {

std::optional<ChunkedScene> streamedMesh(const std::string& spec, bool quiet) {
  std::string why;
  std::shared_ptr<const MeshStream> mesh = MeshStream::open(spec, why);
  if (!mesh) {
    if (!quiet)
      std::fprintf(stderr, "note: %s: loaded whole, not streamed (%s)\n", spec.c_str(),
                   why.c_str());
    return std::nullopt;
  }
  if (!quiet) warnDropped(spec, mesh->stats());
  ChunkedScene c;
  c.base.source = spec;
  c.triangles = mesh->triangles();
  c.placement = mesh->placement();
  c.heldBytes = mesh->heldBytes();
  c.chunks = [mesh](const std::function<void(const Mesh&)>& out) {
    mesh->forEachChunk(out);
    return mesh->stats();
  };
  return c;
}

}  // namespace

std::optional<ChunkedScene> openChunkedScene(const std::string& spec, bool quiet) {
  if (spec.rfind("builtin:", 0) == 0) return openGeneratedScene(spec);
  if (MeshStream::streams(spec)) return streamedMesh(spec, quiet);
  return std::nullopt;
}

}  // namespace lzb
