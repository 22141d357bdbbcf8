#include "src/cli/build_tree_command.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "src/core/error.hpp"
#include "src/core/system.hpp"
#include "src/core/timer.hpp"
#include "src/sampletree/external_build.hpp"
#include "src/sampletree/tree_build.hpp"
#include "src/sampletree/tree_store.hpp"
#include "src/scene/chunked_scene.hpp"
#include "src/scene/load.hpp"

namespace lzb {

void addBuildTreeOptions(CLI::App& c, BuildTreeArgs& a) {
  c.add_option("scene", a.scene, "mesh file, scene.toml or builtin:NAME?key=value")->required();
  c.add_option("--out,-o", a.out, "the tree store to write")->required();
  c.add_option("--c", a.c, "sample size constant: p = exp(-exp(-c)) per stopping node")
      ->capture_default_str();
  c.add_option("--seed", a.seed, "seed of the drawings")->capture_default_str();
  c.add_option("--leaf-triangles", a.leafTriangles, "octree cells with more triangles are split")
      ->capture_default_str();
  c.add_option("--threads,-t", a.threads, "threads (0: the cores this process owns)")
      ->capture_default_str();
  c.add_option("--mem-mb", a.memMb,
               "build out of core within this memory budget in MiB (section 5.1: the scene "
               "streamed, cells spilled to scratch files beside --out); 0: in memory")
      ->capture_default_str();
  c.add_flag("--quiet,-q", a.quiet, "no progress lines");
}

namespace {

constexpr double kMaxMemMb = 1048576.0;  // 1 TiB

// The scene as a stream: a streaming generator regenerates it on every pass and a PLY
// file is read again on every pass, neither held whole (src/scene/chunked_scene.hpp); any other
// scene is loaded and its expanded triangles streamed.
struct SceneInput {
  std::optional<Scene> scene;
  std::optional<ChunkedScene> chunked;
  std::unique_ptr<sampletree::TriangleStream> stream;
};

SceneInput openSceneStream(const std::string& spec, bool quiet) {
  SceneInput in;
  in.chunked = openChunkedScene(spec, quiet);
  if (in.chunked) {
    const ChunkedScene& c = *in.chunked;
    in.stream = std::make_unique<sampletree::MeshChunkStream>(
        c.base, c.triangles, c.chunks,
        c.generated ? sampletree::MeshChunkStream::Kind::kGenerator
                    : sampletree::MeshChunkStream::Kind::kFile,
        c.placement);
    return in;
  }
  in.scene = loadScene(spec, quiet);
  in.stream = std::make_unique<sampletree::SceneStream>(*in.scene);
  return in;
}

// The budget left to the build once the input holds what it must while open (a PLY's vertex
// element, a scene loaded whole): --mem-mb bounds the whole process, not the build alone.
uint64_t buildBudget(const SceneInput& in, uint64_t memBytes, const std::string& spec) {
  const uint64_t held = in.chunked ? in.chunked->heldBytes : in.scene->heldBytes();
  require(held < memBytes, "--mem-mb",
          spec + " holds " + std::to_string(held >> 20) + " MiB while it is read (" +
              (in.chunked ? "its vertices" : "the scene, loaded whole") + "), all of the " +
              std::to_string(memBytes >> 20) + " MiB budget and more: raise it");
  return memBytes - held;
}

int runExternalBuild(const BuildTreeArgs& a, const mpi::Group& g,
                     const sampletree::TreeParams& params, int threads) {
  require(std::isfinite(a.memMb) && a.memMb > 0.0 && a.memMb <= kMaxMemMb, "--mem-mb",
          "must be a budget in MiB up to 2^20, got " + std::to_string(a.memMb));
  const uint64_t memBytes = uint64_t(a.memMb * 1024.0 * 1024.0);
  requireMemory(memBytes, "--mem-mb", "the external build");
  if (!g.root()) return 0;  // one rank builds: the passes are bound by the input and the disk
  const std::filesystem::path scratchDir = std::filesystem::absolute(a.out).parent_path();
  require(std::filesystem::is_directory(scratchDir), "--out",
          "the folder " + scratchDir.string() + " does not exist");
  const SceneInput in = openSceneStream(a.scene, a.quiet);
  sampletree::ExternalOptions options =
      sampletree::optionsForMemory(buildBudget(in, memBytes, a.scene), params, threads);
  options.progress = !a.quiet;
  options.scratchDir = scratchDir;
  Stopwatch clock;
  const sampletree::ExternalReport r =
      sampletree::buildTreeExternal(*in.stream, params, options, threads, a.out);
  if (!a.quiet)
    std::printf("lzb: sample tree of %llu triangles in %llu nodes built out of core in %.1f s "
                "(input %.1f s in %d passes, buckets %.1f s, store %.1f s; %llu buckets of at "
                "most %llu triangles, %llu top cells, %llu scratch bytes), %llu bytes written to "
                "%s\n",
                (unsigned long long)r.triangles, (unsigned long long)r.nodes, clock.lap(),
                r.inputSeconds, r.streamPasses, r.bucketSeconds, r.storeSeconds,
                (unsigned long long)r.buckets,
                (unsigned long long)r.largestBucket, (unsigned long long)r.topCells,
                (unsigned long long)r.spillBytes, (unsigned long long)r.storeBytes, a.out.c_str());
  return 0;
}

}  // namespace

int runBuildTree(const BuildTreeArgs& a, const mpi::Group& g) {
  require(a.threads >= 0 && a.threads <= 1024, "--threads", "must be in [0, 1024]");
  const sampletree::TreeParams params{a.c, a.seed, a.leafTriangles};
  sampletree::validateParams(params);
  const int threads = a.threads > 0 ? a.threads : coresOwned();
  if (a.memMb != 0.0) return runExternalBuild(a, g, params, threads);
  const Scene scene = loadScene(a.scene, a.quiet || !g.root());
  Stopwatch clock;
  const sampletree::SampleTree tree = sampletree::buildTree(scene, params, threads);
  const double buildSeconds = clock.lap();
  if (!g.root()) return 0;
  sampletree::writeTree(tree, a.out);
  if (!a.quiet)
    std::printf("lzb: sample tree of %llu triangles in %zu nodes (%.1f s), %llu bytes written to %s\n",
                (unsigned long long)tree.triangles(), tree.nodes.size(), buildSeconds,
                (unsigned long long)sampletree::storeBytes(tree), a.out.c_str());
  return 0;
}

}  // namespace lzb
