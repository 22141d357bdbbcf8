#include "src/cli/render_command.hpp"

#include <cstdio>
#include <filesystem>
#include <memory>

#include <unistd.h>

#include "mpi/composite.hpp"
#include "mpi/failure.hpp"
#include "mpi/frame_driver.hpp"
#include "raycast/ray_witness.hpp"
#include "src/cli/frame_transfer.hpp"
#include "src/cli/methods.hpp"
#include "src/cli/report.hpp"
#include "src/core/atomic_file.hpp"
#include "src/core/error.hpp"
#include "src/core/progress.hpp"
#include "src/core/system.hpp"
#include "src/core/timer.hpp"
#include "src/image/frame_io.hpp"
#include "src/image/metrics.hpp"
#include "src/image/reference.hpp"
#include "src/scene/load.hpp"

namespace lzb {

namespace fs = std::filesystem;

void addRenderOptions(CLI::App& c, RenderArgs& a) {
  c.add_option("scene", a.scene,
               "mesh file (OBJ, PLY, OFF, STL, glTF, ...), scene.toml, or builtin:NAME?key=value")
      ->required();
  c.add_option("--method,-m", a.method, "rendering method: " + methodNames())->capture_default_str();
  c.add_option("--reference", a.reference,
               "also render this exact method, at the pixel centres and at 4x4 sub-samples per "
               "pixel, and report accuracy against it: a pixel is correct when its triangle is "
               "one the reference sees at the pixel's centre or one of its 16 sub-samples, or "
               "when a ray through the pixel sees that triangle first (the ray witness; it "
               "traces the raycast reference's Embree scene, else one built at set-up; "
               "src/image/README.md): " + methodNames(true) + "; width and height at most 4096");
  c.add_flag("--subsamples", a.subsamples,
             "also render each frame at 4x4 sub-samples per pixel and store their triangle IDs "
             "and box-filtered colour in the EXR, making it a reference for `lzb compare` "
             "(exact methods only; width and height at most 4096)");
  c.add_option("--out,-o", a.out, "output folder for frame_NNNN.png/.exr and report.json")
      ->capture_default_str();
  c.add_option("--composite", a.composite,
               "how ranks composite at the root: reduce (MPI_Reduce of keys) | bswap (binary "
               "swap) | direct (direct send of stripes) | tiles (touched tiles to the root)")
      ->capture_default_str();
  c.add_option("--frame-groups", a.frameGroups,
               "frame-parallel batches: the ranks form this many groups, frame f goes to group f "
               "mod G, each group splits its frame; the first rank writes every frame")
      ->capture_default_str();
  c.add_option("--threads,-t", a.threads, "threads per rank (0: the cores this rank owns)")
      ->capture_default_str();
  c.add_option("--seed", a.seed, "seed of all randomness (runs repeat exactly)")->capture_default_str();
  c.add_option("--width", a.width, "image width (default: the scene file's, else 640)")
      ->check(CLI::Range(1, 16384));
  c.add_option("--height", a.height, "image height (default: the scene file's, else 480)")
      ->check(CLI::Range(1, 16384));
  c.add_option("--frames", a.frames,
               "frames along the camera path (scene keyframes, else a circle around the centre)")
      ->capture_default_str();
  c.add_option("--fov", a.fov, "vertical field of view in degrees (0: the scene's, else 45)")
      ->capture_default_str();
  c.add_option("--near", a.nearPlane, "near plane distance (0: the scene's, else from the bounds)")
      ->capture_default_str();
  c.add_option("--far", a.farPlane, "far plane distance (0: the scene's, else from the bounds)")
      ->capture_default_str();
  c.add_flag("--quiet,-q", a.quiet, "no progress lines");
  for (const auto& m : methods()) m->addOptions(c);
}

namespace {

// Refuses sub-sample images over the camera's size limit (4W x 4H), naming the option that asks
// for them. A size of 0 (not given: the scene file's or the default) passes here.
void checkSubsampleSizes(const RenderArgs& a, int width, int height) {
  if (!a.reference.empty()) checkSubsampleSize(width, height, "--reference");
  if (a.subsamples) checkSubsampleSize(width, height, "--subsamples");
}

// Bytes every rank holds for one width x height frame, at least (the renderer's own buffers come
// on top): the frame (depth 4 + colour 4 + ID 8 bytes a pixel); with --subsamples its 4 x 4
// sub-sample render (16 x 16 bytes a pixel) while it is reduced to the frame's ReferenceFrame
// (centre ID 8 + 16 IDs x 8 + box colour 12 bytes), which is kept; with --reference the
// reference's centre render (16), sub-sample render (256) and reduction (148), all at once.
uint64_t frameBytes(const RenderArgs& a, int width, int height) {
  constexpr uint64_t kFrame = 16, kFine = 16 * 16, kReduced = 8 + 16 * 8 + 12;
  uint64_t perPixel = kFrame;
  if (a.subsamples) perPixel += kReduced;
  if (!a.reference.empty()) perPixel += kFrame + kFine + kReduced;
  else if (a.subsamples) perPixel += kFine;
  return perPixel * uint64_t(width) * uint64_t(height);
}

// Refuses, before any allocation, a frame this process cannot hold.
void checkFrameMemory(const RenderArgs& a, int width, int height) {
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  requireMemory(frameBytes(a, width, height), a.width || a.height ? "--width/--height" : "image size",
                "a " + size + " frame" + (a.reference.empty() ? "" : " with its --reference") +
                    (a.subsamples ? " and --subsamples" : ""));
}

void validate(const RenderArgs& a) {
  methodNamed(a.method, "--method").validate();
  if (!a.reference.empty()) exactMethodNamed(a.reference, "--reference");
  if (a.subsamples) exactMethodNamed(a.method, "--subsamples");
  checkSubsampleSizes(a, a.width, a.height);
  if (a.width && a.height) checkFrameMemory(a, a.width, a.height);
  require(a.threads >= 0 && a.threads <= 1024, "--threads", "must be in [0, 1024]");
  require(a.frames >= 1 && a.frames <= 1000000, "--frames", "must be in [1, 1000000]");
  mpi::parseCompositeStrategy(a.composite, "--composite");
  require(a.fov >= 0.0 && a.fov < 180.0, "--fov", "must be in (0, 180) degrees");
  require(a.nearPlane >= 0.0, "--near", "must be > 0");
  require(a.farPlane >= 0.0, "--far", "must be > 0");
}

// --out must name an existing writable folder or one that can be created; checked before any
// work and without creating anything (a probe folder is made and removed in the nearest existing
// ancestor), so bad input leaves nothing behind.
void checkOutput(const std::string& out) {
  fs::path existing = fs::absolute(out);
  std::error_code ec;
  while (!fs::exists(existing, ec) && existing.has_parent_path() && existing != existing.parent_path())
    existing = existing.parent_path();
  require(fs::is_directory(existing, ec), "--out " + out,
          existing.string() + " is not a folder");
  const fs::path probe = existing / (".lzb-write-probe." + std::to_string(::getpid()));
  const bool created = fs::create_directory(probe, ec);
  fs::remove(probe, ec);
  require(created, "--out " + out, "cannot create a folder in " + existing.string());
}

void createOutput(const std::string& out) {
  std::error_code ec;
  fs::create_directories(out, ec);
  require(!ec, "--out " + out, "cannot create the folder: " + ec.message());
}

// Renders `exact` at the 4x4 sub-samples of `camera` (every rank its share) and reduces them with
// its centre render `centres` at the root; elsewhere returns an empty frame. The 4W x 4H image
// (16 bytes per sub-sample) is freed on return.
ReferenceFrame renderSubsamples(const mpi::FrameDriver& driver, Renderer& exact,
                                const Camera& camera, int f, const Framebuffer& centres,
                                double& seconds) {
  Framebuffer fine;
  const nlohmann::json stats = driver.render(exact, subsampleCamera(camera), f, fine);
  if (!driver.group().root()) return {};
  seconds = stats["seconds"].get<double>();
  return reduceReference(centres, fine);
}

// What a run's frames are judged against: an exact method and, at the root, the ray witness.
struct Judge {
  Renderer* reference = nullptr;
  std::unique_ptr<WitnessScene> witness;  // the root's only: it alone compares
};

// Renders the reference of frame f (centres, then sub-samples) and adds the test image's
// accuracy against it, witnessed by rays, to the frame's entry at the root.
void addAccuracy(const mpi::FrameDriver& driver, const Judge& judge, const Camera& camera, int f,
                 const Framebuffer& image, nlohmann::json& frame) {
  Framebuffer centres;
  const nlohmann::json stats = driver.render(*judge.reference, camera, f, centres);
  double subsampleSeconds = 0.0;
  const ReferenceFrame exact =
      renderSubsamples(driver, *judge.reference, camera, f, centres, subsampleSeconds);
  if (!driver.group().root()) return;
  Stopwatch clock;
  const RayWitness witness = judge.witness->witness(camera);
  frame["accuracy"] = toJson(compare(image, exact, &witness));
  frame["accuracy_seconds"] = clock.seconds();
  frame["reference_seconds"] = stats["seconds"];
  frame["reference_subsample_seconds"] = subsampleSeconds;
}

// Renders frame f on the ranks of the driver's group: its root gets the image, the report entry
// and, with --subsamples, the frame's own sub-samples.
FrameResult renderFrame(const RenderArgs& a, const mpi::FrameDriver& driver, const Camera& camera,
                        Renderer& renderer, const Judge& judge, int f) {
  FrameResult r;
  r.entry = driver.render(renderer, camera, f, r.image);
  if (a.subsamples) {
    double seconds = 0.0;
    r.own = renderSubsamples(driver, renderer, camera, f, r.image, seconds);
    if (driver.group().root()) r.entry["subsample_seconds"] = seconds;
  }
  if (judge.reference) addAccuracy(driver, judge, camera, f, r.image, r.entry);
  return r;
}

// The frame loop: frames are dealt to the frame groups round-robin (frame f to group f mod G),
// every rank of a group renders its share of the group's frame, and the job's root writes every
// frame, in order, and records it.
void renderFrames(const RenderArgs& a, const mpi::Group& world, const mpi::SubGroups& groups,
                  const Scene& scene, const CameraSpec& base, int width, int height,
                  Renderer& renderer, const Judge& judge, Report& report, bool talk) {
  const mpi::FrameDriver driver(groups.group(), scene,
                                mpi::parseCompositeStrategy(a.composite, "--composite"));
  const auto cameraOf = [&](int f) {
    const CameraSpec spec = withClipPlanes(pathCamera(scene, base, f, a.frames), scene.bounds());
    return Camera(spec, width, height, "camera (frame " + std::to_string(f) + ")");
  };
  Progress progress("rendering " + std::to_string(a.frames) + " frames", uint64_t(a.frames),
                    talk && a.frames > 1);
  for (int first = 0; first < a.frames; first += groups.count()) {
    const int f = first + groups.index();
    FrameResult mine;
    if (f < a.frames) mine = renderFrame(a, driver, cameraOf(f), renderer, judge, f);
    for (int k = 0; k < groups.count() && first + k < a.frames; ++k) {
      const int from = groups.rootOf(k);
      if (world.root()) {
        FrameResult r = from == 0 ? std::move(mine) : receiveFrame(world, from);
        const Camera camera = cameraOf(first + k);
        const FrameOrigin origin{camera, scene.expandedTriangles()};
        writeFrame(r.image, a.out, first + k, a.subsamples ? &r.own : nullptr, &origin);
        if (groups.count() > 1) r.entry["frame_group"] = k;
        report.addFrame(first + k, camera, std::move(r.entry), r.image);
        progress.add();
      } else if (world.rank == from) {
        sendFrame(world, 0, mine);
      }
    }
  }
  progress.done();
}

}  // namespace

int runRender(const RenderArgs& a, const mpi::Group& g, const std::string& commandLine) {
  Stopwatch total;
  const bool talk = g.root() && !a.quiet;
  // Everything one rank can get wrong alone (options, files, memory) is agreed on before any
  // rank writes anything or meets the others in a frame (mpi/failure.hpp).
  Scene scene;
  RenderOptions options;
  int width = 0, height = 0;
  CameraSpec base;
  std::unique_ptr<Renderer> renderer, reference;
  Judge judge;
  double loadSeconds = 0.0, setupSeconds = 0.0;
  mpi::agree(g, [&] {
    validate(a);
    require(a.frameGroups >= 1 && a.frameGroups <= g.size, "--frame-groups",
            "must be in [1, " + std::to_string(g.size) + "] (the number of ranks)");
    if (g.root()) checkOutput(a.out);
  });
  const mpi::SubGroups groups(g, a.frameGroups);
  mpi::agree(g, [&] {
    Stopwatch loadClock;
    scene = loadScene(a.scene, !talk);
    require(scene.expandedTriangles() > 0, a.scene, "the scene has no triangles");
    loadSeconds = loadClock.seconds();

    options.method = a.method;
    options.threads = a.threads > 0 ? a.threads : coresOwned();
    options.seed = a.seed;
    options.quiet = !talk;
    useThreads(options.threads);

    width = a.width ? a.width : scene.width.value_or(640);
    height = a.height ? a.height : scene.height.value_or(480);
    base = scene.camera ? *scene.camera : frameBounds(scene.bounds());
    if (a.fov > 0.0) base.fovyDegrees = a.fov;
    if (a.nearPlane > 0.0) base.nearPlane = a.nearPlane;
    if (a.farPlane > 0.0) base.farPlane = a.farPlane;
    // Validate the first camera and the sub-sample size before any rendering work starts.
    Camera(withClipPlanes(base, scene.bounds()), width, height, "camera");
    checkSubsampleSizes(a, width, height);
    checkFrameMemory(a, width, height);

    Stopwatch setupClock;
    renderer = methodNamed(a.method, "--method").create(scene, options);
    if (!a.reference.empty()) {
      reference = methodNamed(a.reference, "--reference").create(scene, options);
      judge.reference = reference.get();
      // Built once here (set-up time), unless the raycast reference lends its Embree scene.
      if (groups.group().root())
        judge.witness = std::make_unique<WitnessScene>(scene, reference.get(), options.threads);
    }
    setupSeconds = setupClock.seconds();
  });
  const nlohmann::json methodSetup = mpi::gatherStats(g, renderer->setupStats());
  mpi::agree(g, [&] {
    if (g.root()) createOutput(a.out);
  });

  Report report(a, options, g, scene, commandLine);
  report.setMethod(*renderer, reference.get());
  report.setSetup(loadSeconds, setupSeconds, methodSetup);
  if (judge.witness) report.setWitness(*judge.witness);
  try {
    Stopwatch frames;
    renderFrames(a, g, groups, scene, base, width, height, *renderer, judge, report, talk);
    if (g.root()) {
      report.setThroughput(frames.seconds());
      report.setTotal(total.seconds());
      report.write(fs::path(a.out) / "report.json");
      report.printSummary(stdout);
    }
  } catch (const std::exception& e) {
    // Ranks meet in collectives at every step of a frame: an error on one rank (say, a full disk
    // at the root) would leave the others waiting, so a multi-rank run ends them all now.
    if (g.size == 1) throw;
    mpi::abortJob(g, e);
  }
  return 0;
}

}  // namespace lzb
