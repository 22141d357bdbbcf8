#include "src/cli/render_setup.hpp"

#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <optional>

#include "mpi/composite.hpp"
#include "mpi/group.hpp"
#include "src/cli/frame_record.hpp"
#include "src/cli/methods.hpp"
#include "src/core/error.hpp"
#include "src/core/system.hpp"
#include "src/core/timer.hpp"
#include "src/image/reference.hpp"
#include "src/regions/memory_estimate.hpp"
#include "src/regions/share.hpp"
#include "src/regions/sliced_share.hpp"
#include "src/regions/streamed_share.hpp"
#include "src/scene/chunked_scene.hpp"
#include "src/scene/load.hpp"

namespace lzb {

namespace fs = std::filesystem;

namespace {

// Bytes a pixel: a frame (depth 4 + colour 4 + ID 8), a 4 x 4 sub-sample render (16 x 16), and
// a reduced ReferenceFrame (centre ID 8 + 16 IDs x 8 + box colour 12).
constexpr uint64_t kFrame = 16, kFine = 16 * 16, kReduced = 8 + 16 * 8 + 12;

// Refuses sub-sample images over the camera's size limit (4W x 4H), naming the option that asks
// for them. A size of 0 (not given: the scene file's or the default) passes here.
void checkSubsampleSizes(const RenderArgs& a, int width, int height) {
  if (!a.reference.empty()) checkSubsampleSize(width, height, "--reference");
  if (a.subsamples) checkSubsampleSize(width, height, "--subsamples");
}

// Bytes every rank holds for one width x height frame, at least (the renderer's own buffers come
// on top): the frame; with --subsamples its sub-sample render while it is reduced to the frame's
// ReferenceFrame, which is kept; with --reference the reference's centre render, sub-sample
// render and reduction, all at once.
uint64_t frameBytes(const RenderArgs& a, int width, int height) {
  uint64_t perPixel = kFrame;
  if (a.subsamples) perPixel += kReduced;
  if (!a.reference.empty())
    perPixel += kFrame + kFine + kReduced;
  else if (a.subsamples)
    perPixel += kFine;
  return perPixel * uint64_t(width) * uint64_t(height);
}

// Refuses, before any allocation, a frame this process cannot hold.
void checkFrameMemory(const RenderArgs& a, int width, int height) {
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  requireMemory(frameBytes(a, width, height),
                a.width || a.height ? "--width/--height" : "image size",
                "a " + size + " frame" + (a.reference.empty() ? "" : " with its --reference") +
                    (a.subsamples ? " and --subsamples" : ""));
}

}  // namespace

uint64_t referenceFrameBytes(int width, int height) {
  return kReduced * uint64_t(width) * uint64_t(height);
}

void validateRenderArgs(const RenderArgs& a) {
  methodNamed(a.method, "--method").validate();
  if (!a.reference.empty()) exactMethodNamed(a.reference, "--reference");
  if (a.subsamples) exactMethodNamed(a.method, "--subsamples");
  checkSubsampleSizes(a, a.width, a.height);
  if (a.width && a.height) checkFrameMemory(a, a.width, a.height);
  require(a.threads >= 0 && a.threads <= 1024, "--threads", "must be in [0, 1024]");
  require(a.frames >= 1 && a.frames <= 1000000, "--frames", "must be in [1, 1000000]");
  parseFrameRange(a.frameRange, a.frames, "--frame-range");
  require(a.stallTimeout >= 0.0 && a.stallTimeout <= 1e9, "--stall-timeout",
          "must be in [0, 1e9] seconds");
  mpi::parseCompositeStrategy(a.composite, "--composite");
  regions::parseCompactBvh(a.bvh, "--bvh");
  if (regions::parseDistribution(a.distribute, "--distribute") == regions::Distribution::kData) {
    require(!methodNamed(a.method, "--method").rendersFromStore(), "--distribute data",
            "cuts the scene into regions, each with structures of its own: a store (--tree) holds "
            "the whole scene's (leave out --tree to build each region's tree in memory)");
  }
  require(a.regions <= 65536, "--regions", "must be in [0, 65536]");
  require(a.fov >= 0.0 && a.fov < 180.0, "--fov", "must be in (0, 180) degrees");
  require(a.nearPlane >= 0.0, "--near", "must be > 0");
  require(a.farPlane >= 0.0, "--far", "must be > 0");
}

void checkOutput(const std::string& out) {
  fs::path existing = fs::absolute(out);
  std::error_code ec;
  while (!fs::exists(existing, ec) && existing.has_parent_path() &&
         existing != existing.parent_path())
    existing = existing.parent_path();
  require(fs::is_directory(existing, ec), "--out " + out, existing.string() + " is not a folder");
  // A probe folder made and removed in the nearest existing ancestor.
  const fs::path probe = existing / (".lzb-write-probe." + std::to_string(::getpid()));
  const bool created = fs::create_directory(probe, ec);
  fs::remove(probe, ec);
  require(created, "--out " + out, "cannot create a folder in " + existing.string());
}

bool createOutput(const std::string& out) {
  std::error_code ec;
  const bool created = fs::create_directories(out, ec);
  require(!ec, "--out " + out, "cannot create the folder: " + ec.message());
  return created;
}

Camera RenderPlan::camera(int f) const {
  const CameraSpec spec = withClipPlanes(pathCamera(scene, base, f, frames), scene.bounds());
  return Camera(spec, width, height, "camera (frame " + std::to_string(f) + ")");
}

namespace {

// This rank's estimated peak holding `triangles` unique triangles: the method's structures and a
// reference's.
uint64_t rankPeakBytes(const RenderArgs& a, uint64_t triangles) {
  const bool compact = regions::parseCompactBvh(a.bvh, "--bvh");
  return regions::methodPeakBytes(a.method, triangles, compact) +
         (a.reference.empty() ? 0 : regions::methodPeakBytes(a.reference, triangles, compact));
}

std::string holding(uint64_t triangles, const RenderArgs& a) {
  return "holding " + std::to_string(triangles) + " triangles with --method " + a.method +
         (a.reference.empty() ? "" : " and --reference " + a.reference);
}

// The scene, or the outline standing for it when the method holds every triangle and no
// reference needs them. A generated scene's size is known, and refused, before it is made; any
// other is refused once loaded, before the method builds on it.
void loadSceneOf(const RenderArgs& a, bool talk, RenderPlan& plan) {
  std::optional<SceneOutline> stored;
  if (a.reference.empty()) stored = methodNamed(a.method, "--method").storedOutline(a.scene);
  if (stored) {
    plan.scene = sceneFromOutline(*stored);
    plan.outline = std::move(*stored);
    plan.sceneLoaded = false;
    return;
  }
  if (const std::optional<ChunkedScene> chunked = openGeneratedScene(a.scene))
    regions::requireEstimate(rankPeakBytes(a, chunked->triangles), a.scene,
                             "every rank " + holding(chunked->triangles, a),
                             ": cut it across ranks with --distribute data");
  plan.scene = loadScene(a.scene, !talk);
  require(plan.scene.expandedTriangles() > 0, a.scene, "the scene has no triangles");
  regions::requireEstimate(rankPeakBytes(a, plan.scene.uniqueTriangles()), a.scene,
                           "every rank " + holding(plan.scene.uniqueTriangles(), a));
  plan.outline = outlineOf(plan.scene);
}

// --distribute data: this rank's part, streamed where the scene can be, else cut from the loaded
// scene; the outline stands for the whole (camera paths and clip planes come out alike). The
// share is refused before its triangles are kept when it would not fit.
void loadShareOf(const RenderArgs& a, bool talk, const mpi::Group& group, RenderPlan& plan) {
  const WorkShare share{group.rank, group.size};
  const Method& method = methodNamed(a.method, "--method");
  const regions::Parts layout = regions::partsFor(method);
  const bool wholeProcedural = method.samplesProceduralObjects();
  // What this rank may use before it loads: a slice's load is freed before the method builds (and
  // its own peak is checked before reading), so its share is weighed against this, not against
  // what the load still maps when the regions are dealt.
  const uint64_t usableBeforeLoad = usableMemoryBytes();
  const auto refuse = [&](uint64_t triangles, const regions::HeldShare& held, uint64_t usable) {
    regions::requireEstimate(rankPeakBytes(a, triangles), a.scene,
                             "rank " + std::to_string(share.rank) + " of " +
                                 std::to_string(share.size) + " " + holding(triangles, a) + " (" +
                                 std::to_string(held.mine.size()) + " of " +
                                 std::to_string(held.regions) + " regions)",
                             ": more ranks hold smaller shares", usable);
  };
  const auto refuseHeld = [&](const regions::HeldShare& held) {
    refuse(held.triangles, held, usableMemoryBytes());
  };
  const auto refuseSliced = [&](const regions::HeldShare& held) {
    refuse(held.triangles, held, usableBeforeLoad);
  };
  if (std::optional<regions::HeldShare> sliced = regions::holdSlicedShare(
          a.scene, group, a.regions, layout, !talk, plan.outline, refuseSliced)) {
    plan.held = std::move(*sliced);
  } else if (const std::optional<ChunkedScene> chunked =
                 regions::openSharedStream(a.scene, wholeProcedural, !talk)) {
    plan.held =
        regions::holdStreamedShare(*chunked, a.regions, share, layout, plan.outline, refuseHeld);
  } else {
    // A TOML scene's streamed mesh files are read per region, never whole; the share is
    // refused before they are, as lzb info estimates it (a placed mesh held whole, so at most
    // the scene's unique triangles).
    const TomlOutline whole = loadSceneDeferred(a.scene, !talk, !wholeProcedural);
    plan.held = regions::holdShare(whole.scene, a.regions, share, layout, wholeProcedural,
                                   whole.read, [&](const regions::HeldShare& held) {
                                     refuse(std::min(held.triangles, whole.scene.uniqueTriangles()),
                                            held, usableMemoryBytes());
                                   });
    plan.outline = outlineOf(whole.scene);
  }
  plan.scene = sceneFromOutline(plan.outline);
}

}  // namespace

bool replicaFits(const RenderArgs& a) {
  if (!a.reference.empty() || methodNamed(a.method, "--method").rendersFromStore()) return true;
  // A PLY read in slices gives its count from its header; a stream reads the file for it.
  if (const std::optional<uint64_t> faces = regions::slicedFaces(a.scene))
    return rankPeakBytes(a, *faces) <= usableMemoryBytes();
  const std::optional<ChunkedScene> chunked = openChunkedScene(a.scene, true);
  return !chunked || rankPeakBytes(a, chunked->triangles) <= usableMemoryBytes();
}

void loadPlan(const RenderArgs& a, bool talk, RenderPlan& plan, const mpi::Group* group,
              regions::Distribution distribution) {
  Stopwatch loadClock;
  if (distribution == regions::Distribution::kData)
    loadShareOf(a, talk, *group, plan);
  else
    loadSceneOf(a, talk, plan);
  plan.loadSeconds = loadClock.seconds();

  plan.options.method = a.method;
  plan.options.threads = a.threads > 0 ? a.threads : coresOwned();
  plan.options.seed = a.seed;
  plan.options.quiet = !talk;
  plan.options.frameGroups = a.frameGroups;
  plan.options.compactBvh = regions::parseCompactBvh(a.bvh, "--bvh");
  useThreads(plan.options.threads);

  plan.width = a.width ? a.width : plan.scene.width.value_or(640);
  plan.height = a.height ? a.height : plan.scene.height.value_or(480);
  plan.frames = a.frames;
  CameraSpec& base = plan.base;
  base = plan.scene.camera ? *plan.scene.camera : frameBounds(plan.scene.bounds());
  if (a.fov > 0.0) base.fovyDegrees = a.fov;
  if (a.nearPlane > 0.0) base.nearPlane = a.nearPlane;
  if (a.farPlane > 0.0) base.farPlane = a.farPlane;
  // Validate the first camera and the sub-sample size before any rendering work starts.
  Camera(withClipPlanes(base, plan.scene.bounds()), plan.width, plan.height, "camera");
  checkSubsampleSizes(a, plan.width, plan.height);
  checkFrameMemory(a, plan.width, plan.height);
}

}  // namespace lzb
