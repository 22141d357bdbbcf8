#include "src/cli/sweep_command.hpp"

#include <cstdio>
#include <filesystem>
#include <memory>

#include "mpi/composite.hpp"
#include "mpi/failure.hpp"
#include "mpi/frame_driver.hpp"
#include "src/cli/judge.hpp"
#include "src/cli/methods.hpp"
#include "src/cli/render_setup.hpp"
#include "src/cli/sweep_params.hpp"
#include "src/cli/sweep_plot.hpp"
#include "src/cli/sweep_table.hpp"
#include "src/core/error.hpp"
#include "src/core/progress.hpp"
#include "src/core/system.hpp"
#include "src/core/timer.hpp"

namespace lzb {

namespace fs = std::filesystem;

void addSweepOptions(CLI::App& c, SweepArgs& a) {
  a.render.reference = "raycast";
  a.render.out = "sweep";
  addRenderOptions(c, a.render);
  // Every frame is rendered by all ranks and judged, never written: no frame groups, no EXRs.
  c.remove_option(c.get_option("--frame-groups"));
  c.remove_option(c.get_option("--subsamples"));
  c.get_option("--out")->description("output folder for sweep.csv and sweep.png");
  c.get_option("--reference")->capture_default_str();
  c.add_option("--param,-p", a.params,
               "NAME=V1,V2,...: a method option (without its dashes: splat=1,2,4, eps=1.2,1.5) "
               "or threads, seed, composite, and the values to try (';' separates them when a "
               "value holds commas); repeat for more parameters: every combination is rendered "
               "(at most 10000)")
      ->required()
      ->allow_extra_args(false);
  a.command = &c;
}

namespace {

// Everything the sweep can refuse without the scene, before anything is loaded or written.
SweepGrid checkSweep(const SweepArgs& s) {
  const RenderArgs& a = s.render;
  require(!a.reference.empty(), "--reference", "lzb sweep judges against an exact method");
  // A sweep keeps no frame record: its rows are rewritten after each combination instead.
  require(a.frameRange.empty() && !a.resume && a.stallTimeout == 0.0,
          "--frame-range/--resume/--stall-timeout", "are options of lzb render, not of lzb sweep");
  validateRenderArgs(a);
  SweepGrid grid = parseSweepGrid(s.params);
  checkSweepNames(grid, methodNamed(a.method, "--method"), *s.command);
  for (uint64_t k = 0; k < grid.count(); ++k) applyCombination(a, grid, k);
  return grid;
}

// Renders the reference of every frame once, kept at the root for every combination.
std::vector<ExactFrame> renderReferences(const SweepArgs& s, const mpi::Group& g,
                                         const RenderPlan& plan, const Judge& judge,
                                         Progress& progress) {
  const mpi::FrameDriver driver(g, plan.scene,
                                mpi::parseCompositeStrategy(s.render.composite, "--composite"));
  std::vector<ExactFrame> exact;
  for (int f = 0; f < plan.frames; ++f) {
    exact.push_back(renderReference(driver, judge, plan.camera(f), f));
    progress.add();
  }
  return exact;
}

// A combination's renderer, built on every rank with the combination's options applied.
struct Contender {
  RenderArgs args;
  std::unique_ptr<Renderer> renderer;
  double setupSeconds = 0.0;
};

Contender makeContender(const SweepArgs& s, const SweepGrid& grid, uint64_t k,
                        const RenderPlan& plan) {
  Contender c;
  c.args = applyCombination(s.render, grid, k);
  RenderOptions options = plan.options;
  options.threads = c.args.threads > 0 ? c.args.threads : coresOwned();
  options.seed = c.args.seed;
  options.quiet = true;  // one progress line: the sweep's
  useThreads(options.threads);
  Stopwatch clock;
  c.renderer = methodNamed(c.args.method, "--method").create(plan.scene, options);
  c.setupSeconds = clock.seconds();
  return c;
}

// Renders combination k along every frame and judges each frame at the root.
SweepRow sweepOne(const SweepArgs& s, const SweepGrid& grid, uint64_t k, const mpi::Group& g,
                  const RenderPlan& plan, const Judge& judge, const std::vector<ExactFrame>& exact,
                  Progress& progress) {
  Contender c;
  mpi::agree(g, [&] { c = makeContender(s, grid, k, plan); });
  const mpi::FrameDriver driver(g, plan.scene, mpi::parseCompositeStrategy(c.args.composite, "--composite"));
  std::vector<FrameMeasure> frames;
  Framebuffer image;  // one for every frame: a fresh one costs page faults inside the frame time
  for (int f = 0; f < plan.frames; ++f) {
    const Camera camera = plan.camera(f);
    const nlohmann::json entry = driver.render(*c.renderer, camera, f, image);
    if (g.root()) {
      double judging = 0.0;
      frames.push_back({entry.at("seconds").get<double>(), entry.at("counts"),
                        judgeFrame(judge, camera, image, exact[size_t(f)].samples, judging)});
    }
    progress.add();
  }
  return summarize(grid.values(k), c.setupSeconds, frames);
}

std::vector<std::string> names(const SweepGrid& grid) {
  std::vector<std::string> n;
  for (const SweptParam& p : grid.params) n.push_back(p.name);
  return n;
}

std::string plotTitle(const SweepArgs& s, const RenderPlan& plan, const mpi::Group& g) {
  return s.render.scene + "  --method " + s.render.method + ", " + std::to_string(plan.width) + "x" +
         std::to_string(plan.height) + ", " + std::to_string(plan.frames) + " frame(s), " +
         std::to_string(g.size) + " rank(s); against " + s.render.reference;
}

// The root's closing lines: a line per combination, where the CSV went, and the plot or why not.
void finish(const SweepArgs& s, const SweepGrid& grid, const RenderPlan& plan, const mpi::Group& g,
            const std::vector<SweepRow>& rows) {
  const fs::path out = fs::absolute(s.render.out);
  std::printf("lzb sweep: %s, method %s, %llu combination(s) x %d frame(s), against %s\n",
              s.render.scene.c_str(), s.render.method.c_str(), (unsigned long long)grid.count(),
              plan.frames, s.render.reference.c_str());
  for (uint64_t k = 0; k < rows.size(); ++k)
    std::printf("  %s: %.4f s median frame, correct (covered) min %.5f median %.5f\n",
                grid.label(k).c_str(), rows[k].medianFrameSeconds, rows[k].correctMin,
                rows[k].correctMedian);
  std::printf("  csv: %s\n", (out / "sweep.csv").c_str());
  if (!gnuplotAvailable()) {
    std::printf("  plot: skipped, gnuplot is not on PATH (sweep.png not written)\n");
    return;
  }
  std::vector<std::string> labels;
  for (uint64_t k = 0; k < rows.size(); ++k) labels.push_back(grid.label(k));
  plotSweep(out / "sweep.png", plotTitle(s, plan, g), labels, rows);
  std::printf("  plot: %s\n", (out / "sweep.png").c_str());
}

// The combinations in turn; the root rewrites sweep.csv after each, so a long sweep that fails
// keeps what it measured (the folder appears with the first finished combination).
void sweepAll(const SweepArgs& s, const SweepGrid& grid, const std::string& commandLine,
              const mpi::Group& g, const RenderPlan& plan, const Judge& judge, bool talk) {
  Progress progress("sweep: references, then " + std::to_string(grid.count()) + " combination(s) x " +
                        std::to_string(plan.frames) + " frame(s)",
                    uint64_t(plan.frames) * (grid.count() + 1), talk);
  const std::vector<ExactFrame> exact = renderReferences(s, g, plan, judge, progress);
  std::vector<SweepRow> rows;
  for (uint64_t k = 0; k < grid.count(); ++k) {
    rows.push_back(sweepOne(s, grid, k, g, plan, judge, exact, progress));
    if (!g.root()) continue;
    if (k == 0) createOutput(s.render.out);
    writeSweepCsv(fs::path(s.render.out) / "sweep.csv", commandLine, names(grid), rows);
  }
  progress.done();
  if (g.root()) finish(s, grid, plan, g, rows);
}

}  // namespace

int runSweep(const SweepArgs& s, const mpi::Group& g, const std::string& commandLine) {
  const RenderArgs& a = s.render;
  const bool talk = g.root() && !a.quiet;
  // As in `lzb render`: what one rank can get wrong alone is agreed on before anything is
  // written (mpi/failure.hpp); every combination is checked here, so none fails half-way.
  SweepGrid grid;
  mpi::agree(g, [&] {
    grid = checkSweep(s);
    if (g.root()) checkOutput(a.out);
  });
  RenderPlan plan;
  Judge judge;
  mpi::agree(g, [&] {
    loadPlan(a, talk, plan);
    if (g.root())
      requireMemory(uint64_t(plan.frames) * referenceFrameBytes(plan.width, plan.height), "--frames",
                    "keeping the reference of " + std::to_string(plan.frames) + " frames");
    judge = makeJudge(a.reference, plan.scene, plan.options, g.root());
  });
  try {
    sweepAll(s, grid, commandLine, g, plan, judge, talk);
  } catch (const mpi::JobFailed&) {
    throw;  // agreed by every rank: the messages are out
  } catch (const std::exception& e) {
    // Inside the frames the ranks meet in collectives: one failing rank ends them all.
    if (g.size == 1) throw;
    mpi::abortJob(g, e);
  }
  return 0;
}

}  // namespace lzb
