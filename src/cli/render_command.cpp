#include "src/cli/render_command.hpp"

#include <cstdio>
#include <filesystem>
#include <memory>

#include "mpi/composite.hpp"
#include "mpi/failure.hpp"
#include "mpi/frame_driver.hpp"
#include "mpi/watchdog.hpp"
#include "src/cli/frame_record.hpp"
#include "src/cli/frame_transfer.hpp"
#include "src/cli/judge.hpp"
#include "src/cli/methods.hpp"
#include "src/cli/render_job.hpp"
#include "src/cli/render_setup.hpp"
#include "src/cli/report.hpp"
#include "src/core/error.hpp"
#include "src/core/progress.hpp"
#include "src/core/statistics.hpp"
#include "src/core/timer.hpp"
#include "src/image/frame_io.hpp"
#include "src/image/metrics.hpp"
#include "src/regions/part_renderer.hpp"
#include "src/regions/share.hpp"

namespace lzb {

namespace fs = std::filesystem;

void addRenderOptions(CLI::App& c, RenderArgs& a) {
  c.add_option("scene", a.scene,
               "mesh file (OBJ, PLY, OFF, STL, glTF, ...), scene.toml, or builtin:NAME?key=value")
      ->required();
  c.add_option("--method,-m", a.method, "rendering method: " + methodNames())
      ->capture_default_str();
  c.add_option("--quality", a.quality,
               "fast | balanced | exact: the method's preset along its measured speed-accuracy "
               "trade (runs/tradeoff); options given on the command line win; exact is the "
               "method's most accurate setting (exact methods and lzb have no trade to make)");
  c.add_option("--reference", a.reference,
               "also render this exact method, at the pixel centres and at 4x4 sub-samples per "
               "pixel, and report accuracy against it: a pixel is correct when its triangle is "
               "one the reference sees at the pixel's centre or one of its 16 sub-samples, or "
               "when a ray through the pixel sees that triangle first (the ray witness; it "
               "traces the raycast reference's Embree scene, else one built at set-up; "
               "src/image/README.md): " +
                   methodNames(true) + "; width and height at most 4096");
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
  c.add_option(
       "--distribute", a.distribute,
       "replicate: every rank holds the whole scene | data: the scene is cut into "
       "--regions spatial regions balanced by triangle count, each rank (of each frame "
       "group) holds only its regions' triangles and renders the whole frame of them, "
       "and the frames are composited by depth (methods other than zbuffer and raycast "
       "render each region apart: the same --regions give the same image on any number "
       "of ranks) | auto: data when a PLY, OFF or OBJ file or builtin:landscape would not fit "
       "replicated in some rank's memory (estimated), else replicate")
      ->capture_default_str();
  c.add_option("--regions", a.regions,
               "--distribute data: regions the scene is cut into, the same on any number of "
               "ranks (0: from the scene's size, 16 to 4096: one per 65,536 unique triangles for "
               "zbuffer and raycast, one per 1,048,576 for the methods that render each region "
               "apart)")
      ->capture_default_str();
  c.add_option("--bvh", a.bvh,
               "Embree's BVH for raycast, lzb and the hybrid: fast (leaves hold each triangle's "
               "vertices) | compact (leaves index the scene's vertices: about half of raycast's "
               "memory, its rays 1.45-1.6x slower, the same triangle at every pixel; "
               "runs/memory/README.md)")
      ->capture_default_str();
  c.add_option("--threads,-t", a.threads, "threads per rank (0: the cores this rank owns)")
      ->capture_default_str();
  c.add_option("--seed", a.seed, "seed of all randomness (runs repeat exactly)")
      ->capture_default_str();
  c.add_option("--width", a.width, "image width (default: the scene file's, else 640)")
      ->check(CLI::Range(1, 16384));
  c.add_option("--height", a.height, "image height (default: the scene file's, else 480)")
      ->check(CLI::Range(1, 16384));
  c.add_option("--frames", a.frames,
               "frames along the camera path (scene keyframes, else a circle around the centre)")
      ->capture_default_str();
  c.add_option("--frame-range", a.frameRange,
               "A:B renders only frames A..B-1 of the --frames path (A: to its end), so a path "
               "splits across jobs or array tasks whose frames equal one run's, byte for byte");
  c.add_flag("--resume", a.resume,
             "skip the frames of the range that --out's record (frames.jsonl) holds complete, "
             "with their files in place, and render the rest; refused (exit 2) when the record "
             "is of another job: another scene, method, option, size, seed or path");
  c.add_option("--stall-timeout", a.stallTimeout,
               "seconds a rank of a multi-rank job may go without finishing a frame, set-up "
               "included, before it ends itself (exit 1), so no rank waits forever for a lost "
               "peer when the launcher does not end the job (0: from the first frame on, 10 x "
               "the longest frame so far, at least 60 s)")
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

void parseRenderOverrides(RenderArgs& args, const std::vector<std::string>& options,
                          const std::string& where) {
  std::vector<std::string> argv(options.rbegin(), options.rend());  // CLI11 takes them last first
  argv.push_back(args.scene);
  CLI::App command;
  addRenderOptions(command, args);
  try {
    command.parse(argv);
  } catch (const CLI::ParseError& e) {
    throw InputError(where + ": " + e.what());
  }
}

namespace {

// Renders the reference of frame f (centres, then sub-samples) and adds the test image's
// accuracy against it, witnessed by rays, to the frame's entry at the root.
void addAccuracy(const mpi::FrameDriver& driver, const Judge& judge, const Camera& camera, int f,
                 const Framebuffer& image, nlohmann::json& frame) {
  const ExactFrame exact = renderReference(driver, judge, camera, f);
  double seconds = 0.0;
  Accuracy accuracy;
  if (judge.parts) {  // --distribute data: every rank witnesses with what it holds
    std::vector<uint64_t> rays;
    accuracy = judgePartFrame(judge, driver.group(), camera, image, exact.samples, seconds, rays);
    if (driver.group().root()) frame["witness_rays_per_rank"] = rays;
  } else if (driver.group().root()) {
    accuracy = judgeFrame(judge, camera, image, exact.samples, seconds);
  }
  if (!driver.group().root()) return;
  frame["accuracy"] = toJson(accuracy);
  frame["accuracy_seconds"] = seconds;
  frame["reference_seconds"] = exact.centreSeconds;
  frame["reference_subsample_seconds"] = exact.subsampleSeconds;
}

// Renders frame f on the ranks of the driver's group: its root gets the image, the report entry
// and, with --subsamples, the frame's own sub-samples.
// r's image keeps its memory from the previous frame: a fresh 4-16 MB frame buffer a frame cost
// up to 9 ms of page faults here (raycast's `clear` stage on the 512^2 city).
void renderFrame(const RenderArgs& a, const mpi::FrameDriver& driver, const Camera& camera,
                 Renderer& renderer, const Judge& judge, int f, FrameResult& r) {
  r.entry = driver.render(renderer, camera, f, r.image);
  if (a.subsamples) {
    double seconds = 0.0;
    r.own = renderSubsamples(driver, renderer, camera, f, r.image, seconds);
    if (driver.group().root()) r.entry["subsample_seconds"] = seconds;
  }
  if (judge.reference) addAccuracy(driver, judge, camera, f, r.image, r.entry);
}

// "median frame 0.041 s" over the frames rendered so far.
std::string medianNote(const std::vector<double>& seconds) {
  char text[64];
  std::snprintf(text, sizeof(text), "median frame %.3f s", median(seconds));
  return text;
}

// The frame loop: the frames to render are dealt to the frame groups round-robin (the i-th to
// group i mod G), every rank of a group renders its share of the group's frame, and the job's
// root writes every frame, in order, then appends its record.
void renderFrames(const RenderArgs& a, const mpi::Group& world, const mpi::SubGroups& groups,
                  const RenderPlan& plan, Renderer& renderer, const Judge& judge,
                  const std::vector<int>& todo, const Report& report, mpi::StallWatchdog& watchdog,
                  bool talk) {
  const mpi::FrameDriver driver(groups.group(), plan.scene,
                                mpi::parseCompositeStrategy(a.composite, "--composite"));
  Progress progress("rendering " + std::to_string(todo.size()) + " frames", todo.size(),
                    talk && todo.size() > 1);
  std::unique_ptr<FrameRecordWriter> record;
  if (world.root()) record = std::make_unique<FrameRecordWriter>(fs::path(a.out) / kFramesFile);
  std::vector<double> seconds;
  FrameResult mine, received;
  const size_t G = size_t(groups.count());
  for (size_t first = 0; first < todo.size(); first += G) {
    const size_t mineAt = first + size_t(groups.index());
    if (mineAt < todo.size())
      renderFrame(a, driver, plan.camera(todo[mineAt]), renderer, judge, todo[mineAt], mine);
    for (size_t k = 0; k < G && first + k < todo.size(); ++k) {
      const int from = groups.rootOf(int(k)), f = todo[first + k];
      if (world.root()) {
        if (from != 0) received = receiveFrame(world, from);
        FrameResult& r = from == 0 ? mine : received;
        const Camera camera = plan.camera(f);
        const FrameOrigin origin{camera, plan.scene.expandedTriangles()};
        writeFrame(r.image, a.out, f, a.subsamples ? &r.own : nullptr, &origin);
        if (G > 1) r.entry["frame_group"] = k;
        nlohmann::json entry = report.frameEntry(f, camera, std::move(r.entry), r.image);
        entry["files"] = frameFiles(a.out, f);  // the record is appended once they are in place
        record->append(entry);
        seconds.push_back(entry["seconds"].get<double>());
        progress.add(1, [&seconds] { return medianNote(seconds); });
      } else if (world.rank == from) {
        sendFrame(world, 0, mine);
      }
    }
    watchdog.progress();
  }
  progress.done();
}

// A folder this run created, holding only its record of no frame yet.
void removeRecordAndFolder(const std::string& out) {
  std::error_code ec;
  fs::remove(fs::path(out) / kJobFile, ec);
  fs::remove(fs::path(out) / kFramesFile, ec);
  fs::remove(out, ec);  // (only when it is empty now)
}

// The root's frames to render, on every rank.
std::vector<int> shareFrames(const mpi::Group& g, std::vector<int> frames) {
  uint64_t count = frames.size();
  LZB_MPI_CALL(MPI_Bcast(&count, 1, MPI_UINT64_T, 0, g.comm));
  frames.resize(count);
  LZB_MPI_CALL(MPI_Bcast(frames.data(), int(count), MPI_INT, 0, g.comm));
  return frames;
}

// --distribute data: the renderer of this rank's part (loadPlan cut it).
std::unique_ptr<Renderer> createPartRenderer(const RenderArgs& a, const RenderPlan& plan) {
  const regions::HeldShare& held = plan.held;
  std::vector<std::unique_ptr<Renderer>> inner;
  for (const regions::ScenePart& part : held.parts)
    inner.push_back(part.scene.expandedTriangles() > 0
                        ? methodNamed(a.method, "--method").create(part.scene, plan.options)
                        : nullptr);
  return regions::makePartRenderer(held, std::move(inner), a.method);
}

// --distribute auto: data when the whole scene would not fit replicated on some rank (every rank
// takes the same mode).
regions::Distribution resolveDistribution(const RenderArgs& a, const mpi::Group& g) {
  const regions::Distribution asked = regions::parseDistribution(a.distribute, "--distribute");
  if (asked != regions::Distribution::kAuto) return asked;
  int fits = 1;
  mpi::agree(g, [&] { fits = replicaFits(a) ? 1 : 0; });
  LZB_MPI_CALL(MPI_Allreduce(MPI_IN_PLACE, &fits, 1, MPI_INT, MPI_MIN, g.comm));
  return fits ? regions::Distribution::kReplicate : regions::Distribution::kData;
}

}  // namespace

int runRender(const RenderArgs& a, const mpi::Group& g, const std::string& commandLine) {
  Stopwatch total;
  const bool talk = g.root() && !a.quiet;
  mpi::StallWatchdog watchdog(g.rank, a.stallTimeout, g.size > 1);
  // Everything one rank can get wrong alone (options, files, memory) is agreed on before any
  // rank writes anything or meets the others in a frame (mpi/failure.hpp).
  RenderPlan plan;
  std::unique_ptr<Renderer> renderer;
  Judge judge;
  double setupSeconds = 0.0;
  mpi::agree(g, [&] {
    validateRenderArgs(a);
    require(a.frameGroups >= 1 && a.frameGroups <= g.size, "--frame-groups",
            "must be in [1, " + std::to_string(g.size) + "] (the number of ranks)");
    if (g.root()) checkOutput(a.out);
  });
  const mpi::SubGroups groups(g, a.frameGroups);
  const regions::Distribution distribution = resolveDistribution(a, g);
  mpi::agree(g, [&] {
    loadPlan(a, talk, plan, &groups.group(), distribution);
    Stopwatch setupClock;
    if (distribution == regions::Distribution::kData)
      renderer = createPartRenderer(a, plan);
    else
      renderer = methodNamed(a.method, "--method").create(plan.scene, plan.options);
    if (!a.reference.empty())
      judge = distribution == regions::Distribution::kData
                  ? makePartJudge(a.reference, plan.held, plan.options)
                  : makeJudge(a.reference, plan.scene, plan.options, groups.group().root());
    setupSeconds = setupClock.seconds();
  });
  FrameStats setupStats = renderer->setupStats();
  if (distribution != regions::Distribution::kData)  // a part renderer counts what its rank holds
    setupStats.addCount("held_unique_triangles", double(plan.scene.uniqueTriangles()));
  const nlohmann::json methodSetup = mpi::gatherStats(g, setupStats);
  Report report(a, plan.options, g, plan.outline, plan.sceneLoaded, commandLine);
  report.setImageSize(plan.width, plan.height);
  report.setMethod(*renderer, judge.reference.get());
  report.setDistribution(distribution == regions::Distribution::kData ? "data" : "replicate");
  report.setSetup(plan.loadSeconds, setupSeconds, methodSetup);
  if (judge.witness)
    report.setWitness(judge.witness->sharedWithReference(), judge.witness->buildSeconds());
  if (judge.parts)
    report.setWitness(judge.parts->sharedWithReference(), judge.parts->buildSeconds());

  // A --resume of another job is refused here, before anything is written.
  FramesToRender todo;
  mpi::agree(g, [&] {
    if (g.root()) todo = framesToRender(a, report.head());
  });
  todo.frames = shareFrames(g, std::move(todo.frames));
  bool created = false;
  mpi::agree(g, [&] {
    if (!g.root()) return;
    created = createOutput(a.out);
    startRecord(a, report.head(), todo.sameJob);
  });

  try {
    Stopwatch frames;
    renderFrames(a, g, groups, plan, *renderer, judge, todo.frames, report, watchdog, talk);
    if (g.root()) {
      report.setFrames(recordedFrames(a.out));
      report.setThroughput(frames.seconds(), todo.frames.size());
      report.setTotal(total.seconds());
      report.write(fs::path(a.out) / "report.json");
      report.printSummary(stdout);
      if (todo.skipped > 0)
        std::printf("  resumed: %d frame(s) of the range were complete, %zu rendered\n",
                    todo.skipped, todo.frames.size());
    }
  } catch (const std::exception& e) {
    // A run refused at its first frame (lzb on a scene too instanced to cull) leaves no folder.
    if (created && recordedFrames(a.out).empty()) removeRecordAndFolder(a.out);
    // Ranks meet in collectives at every step of a frame: an error on one rank (say, a full disk
    // at the root) would leave the others waiting, so a multi-rank run ends them all now.
    if (g.size == 1) throw;
    mpi::abortJob(g, e);
  }
  return 0;
}

}  // namespace lzb
