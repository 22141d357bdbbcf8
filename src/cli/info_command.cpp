#include "src/cli/info_command.hpp"

#include <algorithm>
#include <cstdio>
#include <optional>

#include "src/cli/methods.hpp"
#include "src/cli/report.hpp"
#include "src/core/error.hpp"
#include "src/core/system.hpp"
#include "src/core/timer.hpp"
#include "src/octree/octree.hpp"
#include "src/regions/memory_estimate.hpp"
#include "src/regions/share.hpp"
#include "src/regions/sliced_share.hpp"
#include "src/regions/streamed_share.hpp"
#include "src/scene/load.hpp"

namespace lzb {

void addInfoOptions(CLI::App& c, InfoArgs& a) {
  c.add_option("scene", a.scene, "mesh file, scene.toml, or builtin:NAME?key=value")->required();
  c.add_option("--max-depth", a.maxDepth, "octree maximum depth")->capture_default_str();
  c.add_option("--leaf-size", a.leafSize, "octree maximum entries per leaf")->capture_default_str();
  c.add_option("--method", a.method, "the method whose peak memory per rank is estimated")
      ->capture_default_str();
  c.add_option("--ranks", a.ranks, "the ranks the estimate is for")->capture_default_str();
  c.add_option("--bvh", a.bvh, "the estimate under render's --bvh: fast | compact")
      ->capture_default_str();
  c.add_option("--distribute", a.distribute,
               "replicate: every rank holds the whole scene | data: each holds its regions' share")
      ->capture_default_str();
  c.add_option("--regions", a.regions, "--distribute data: the regions (0: from the scene's size)")
      ->capture_default_str();
  c.add_flag("--json", a.json, "print JSON instead of text");
  c.add_flag("--quiet,-q", a.quiet, "no progress lines");
}

namespace {

void printEstimate(const nlohmann::json& e) {
  const auto& ranks = e["ranks"];
  std::printf(
      "estimate:   --method %s (%.0f bytes a triangle held), %zu rank(s), --distribute %s (one "
      "process may use %.0f MiB here, ranks on one machine divide it)\n",
      e["method"].get<std::string>().c_str(), e["bytes_per_triangle"].get<double>(), ranks.size(),
      e["distribute"].get<std::string>().c_str(), e["usable_bytes"].get<double>() / 1048576.0);
  constexpr size_t kListed = 8;
  for (size_t r = 0; r < std::min(ranks.size(), kListed); ++r)
    std::printf("  rank %zu: %llu triangles, peak %.0f MiB\n", r,
                (unsigned long long)ranks[r]["triangles"].get<uint64_t>(),
                ranks[r]["peak_bytes"].get<double>() / 1048576.0);
  if (ranks.size() > kListed) std::printf("  ... (--json lists every rank)\n");
}

// The estimated peak of each rank (memory_estimate.hpp), frame buffers excluded, from the
// triangles each would hold.
// loadBytes: what a rank holds while it reads its slice of the file (sliced_share.hpp), beside
// the method's base; its peak is the larger of that and the method's on its share.
nlohmann::json rankEstimates(const InfoArgs& a, const std::vector<uint64_t>& held,
                             uint64_t unique, uint64_t loadBytes = 0) {
  nlohmann::json ranks = nlohmann::json::array();
  const bool compact = regions::parseCompactBvh(a.bvh, "--bvh");
  const uint64_t loadPeak = regions::methodPeakBytes(a.method, 0, compact) + loadBytes;
  for (int r = 0; r < a.ranks; ++r) {
    // An instanced share holds at most the scene's unique triangles.
    const uint64_t triangles = std::min(held[size_t(r)], unique);
    nlohmann::json rank = {
        {"rank", r},
        {"triangles", triangles},
        {"peak_bytes",
         std::max(regions::methodPeakBytes(a.method, triangles, compact), loadPeak)}};
    if (loadBytes) rank["load_peak_bytes"] = loadPeak;
    ranks.push_back(rank);
  }
  // The model's slope: the method's set-up and frames, scene model included.
  const double perTriangle = double(regions::methodPeakBytes(a.method, 1, compact) -
                                    regions::methodPeakBytes(a.method, 0, compact));
  return {{"method", a.method},         {"bvh", a.bvh},   {"bytes_per_triangle", perTriangle},
          {"distribute", a.distribute}, {"ranks", ranks}, {"usable_bytes", usableMemoryBytes()}};
}

nlohmann::json rankEstimates(const InfoArgs& a, const Scene& scene) {
  std::vector<uint64_t> held(size_t(a.ranks), scene.uniqueTriangles());
  const Method& method = methodNamed(a.method, "--method");
  if (regions::parseDistribution(a.distribute, "--distribute") == regions::Distribution::kData)
    held = regions::trianglesPerRank(scene, a.regions, regions::partsFor(method),
                                     method.samplesProceduralObjects(), a.ranks);
  return rankEstimates(a, held, scene.uniqueTriangles());
}

// The text report's lines on dropped triangles and bounds, held or streamed.
void printDroppedAndBounds(const SceneOutline& s) {
  std::printf("dropped:    %llu degenerate, %llu non-finite\n",
              (unsigned long long)s.stats.degenerate, (unsigned long long)s.stats.nonFinite);
  const Bounds& b = s.bounds;
  std::printf("bounds:     [%g, %g, %g] - [%g, %g, %g]\n", b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y,
              b.hi.z);
}

// A scene's figures and estimate from its outline and the triangles each rank would hold, the
// scene never held whole (how: what the report's "streamed" says): no octrees, no scene model.
int infoWithoutHolding(const InfoArgs& a, const mpi::Group& g, const SceneOutline& outline,
                       const std::vector<uint64_t>& held, const std::string& how, double seconds,
                       uint64_t loadBytes = 0) {
  nlohmann::json info = sceneSummary(outline);
  info["streamed"] = how;
  info["memory"] = {{"peak_resident_bytes", peakMemoryBytes()}};
  info["seconds"] = {{"centres", seconds}};
  info["estimate"] = rankEstimates(a, held, outline.uniqueTriangles, loadBytes);
  if (!g.root()) return 0;
  if (a.json) {
    std::printf("%s\n", info.dump(2).c_str());
    return 0;
  }
  std::printf("scene:      %s (%s; no octrees)\n", outline.source.c_str(), how.c_str());
  std::printf("triangles:  %llu unique, %llu expanded\n",
              (unsigned long long)outline.uniqueTriangles,
              (unsigned long long)outline.expandedTriangles);
  printDroppedAndBounds(outline);
  std::printf("memory:     peak resident %.1f MB\n", double(peakMemoryBytes()) / 1e6);
  printEstimate(info["estimate"]);
  return 0;
}

}  // namespace

int runInfo(const InfoArgs& a, const mpi::Group& g) {
  require(a.maxDepth >= 0 && a.maxDepth <= 32, "--max-depth", "must be in [0, 32]");
  require(a.leafSize >= 1, "--leaf-size", "must be >= 1");
  const Method& method = methodNamed(a.method, "--method");
  regions::parseCompactBvh(a.bvh, "--bvh");
  require(a.ranks >= 1 && a.ranks <= 1 << 20, "--ranks", "must be in [1, 2^20]");
  require(a.regions <= 65536, "--regions", "must be in [0, 65536]");
  require(regions::parseDistribution(a.distribute, "--distribute") != regions::Distribution::kAuto,
          "--distribute", "info estimates replicate or data, not auto");
  const bool talk = g.root() && !a.quiet;
  const bool data =
      regions::parseDistribution(a.distribute, "--distribute") == regions::Distribution::kData;
  Stopwatch clock;
  // Under data, as the ranks read it: a streamed scene once for its centres, a TOML scene's
  // streamed files and generators per file, never the whole scene held.
  if (const std::optional<ChunkedScene> chunked =
          data ? regions::openSharedStream(a.scene, method.samplesProceduralObjects(), !talk)
               : std::nullopt) {
    SceneOutline outline;
    const std::vector<uint64_t> held = regions::streamedTrianglesPerRank(
        *chunked, a.regions, regions::partsFor(method), a.ranks, outline);
    // A binary PLY of triangles: the ranks read it in slices, each holding its slice's load.
    const std::optional<uint64_t> faces = regions::slicedFaces(a.scene);
    return infoWithoutHolding(
        a, g, outline, held,
        faces ? "read in slices by the ranks; here streamed once for its centres, never held"
              : "streamed: read once for its centres, never held",
        clock.seconds(), faces ? regions::slicedLoadBytes(*faces, a.ranks) : 0);
  }
  TomlOutline read =
      data ? loadSceneDeferred(a.scene, !talk, !method.samplesProceduralObjects()) : TomlOutline{};
  if (read.read)
    return infoWithoutHolding(
        a, g, outlineOf(read.scene),
        regions::trianglesPerRank(read.scene, a.regions, regions::partsFor(method),
                                  method.samplesProceduralObjects(), a.ranks, read.read),
        "its streamed files and generators read for their centres, never held", clock.seconds());
  const Scene scene = data ? std::move(read.scene) : loadScene(a.scene, !talk);
  const double loadSeconds = clock.lap();

  OctreeParams params;
  params.maxDepth = a.maxDepth;
  params.maxLeafEntries = uint32_t(a.leafSize);
  params.progress = talk;
  // One octree per node that holds triangles or instances: what the methods build.
  nlohmann::json octrees = nlohmann::json::array();
  uint64_t octreeBytes = 0;
  for (uint32_t i = 0; i < scene.nodes.size(); ++i) {
    const Node& node = scene.nodes[i];
    if (node.mesh.empty() && node.instances.empty()) continue;
    const Octree tree(scene, i, params);
    nlohmann::json s = tree.stats().toJson();
    s["node"] = node.name;
    s["triangles"] = node.mesh.size();
    s["instances"] = node.instances.size();
    octreeBytes += tree.stats().memoryBytes;
    octrees.push_back(std::move(s));
  }
  const double octreeSeconds = clock.lap();

  const SceneOutline outline = outlineOf(scene);
  nlohmann::json info = sceneSummary(outline);
  info["instances"] = 0;
  for (const Node& n : scene.nodes)
    info["instances"] = info["instances"].get<uint64_t>() + n.instances.size();
  info["octrees"] = octrees;
  const uint64_t held = scene.heldBytes();
  const double heldPerTriangle =
      double(held) / double(std::max<uint64_t>(scene.uniqueTriangles(), 1));
  info["memory"] = {{"scene_bytes", held},
                    {"scene_bytes_per_triangle", heldPerTriangle},
                    {"octree_bytes", octreeBytes},
                    {"peak_resident_bytes", peakMemoryBytes()}};
  info["seconds"] = {{"load", loadSeconds}, {"octrees", octreeSeconds}};
  info["estimate"] = rankEstimates(a, scene);
  if (!g.root()) return 0;
  if (a.json) {
    std::printf("%s\n", info.dump(2).c_str());
    return 0;
  }
  std::printf("scene:      %s\n", scene.source.c_str());
  std::printf("triangles:  %llu unique, %llu expanded (%llu nodes, %llu instances)\n",
              (unsigned long long)scene.uniqueTriangles(),
              (unsigned long long)scene.expandedTriangles(), (unsigned long long)scene.nodes.size(),
              (unsigned long long)info["instances"].get<uint64_t>());
  std::printf("nesting:    %d instance levels (at most %d)\n", scene.instanceDepth,
              kMaxInstanceDepth);
  printDroppedAndBounds(outline);
  // A line per octree for the first few; the rest only in the JSON and the memory total.
  constexpr size_t kListed = 6;
  for (size_t i = 0; i < std::min(octrees.size(), kListed); ++i) {
    const auto& o = octrees[i];
    std::printf(
        "octree %-12s %llu nodes, %llu leaves, depth %d, %.1f mean / %llu max entries per leaf, "
        "%.1f MB, %.2f s\n",
        o["node"].get<std::string>().c_str(), (unsigned long long)o["nodes"].get<uint64_t>(),
        (unsigned long long)o["leaves"].get<uint64_t>(), o["max_depth"].get<int>(),
        o["mean_leaf_entries"].get<double>(),
        (unsigned long long)o["max_leaf_entries"].get<uint64_t>(),
        o["memory_bytes"].get<double>() / 1e6, o["build_seconds"].get<double>());
  }
  if (octrees.size() > kListed)
    std::printf("  ... and %zu more octrees (--json lists them all)\n", octrees.size() - kListed);
  std::printf(
      "memory:     scene %.1f MB (%.1f bytes a unique triangle), octrees %.1f MB, peak "
      "resident %.1f MB\n",
      double(held) / 1e6, heldPerTriangle, double(octreeBytes) / 1e6,
      double(peakMemoryBytes()) / 1e6);
  printEstimate(info["estimate"]);
  return 0;
}

}  // namespace lzb
