// lzb: output-sensitive parallel rendering of highly complex scenes.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>

#include "mpi/failure.hpp"
#include "mpi/group.hpp"
#include "src/cli/batch_command.hpp"
#include "src/cli/build_tree_command.hpp"
#include "src/cli/compare_command.hpp"
#include "src/cli/export_command.hpp"
#include "src/cli/info_command.hpp"
#include "src/cli/limits_command.hpp"
#include "src/cli/omp_wait_policy.hpp"
#include "src/cli/quality.hpp"
#include "src/cli/render_command.hpp"
#include "src/cli/report_command.hpp"
#include "src/cli/sweep_command.hpp"
#include "src/core/error.hpp"
#include "src/core/system.hpp"

namespace {

std::string joinArgs(int argc, char** argv) {
  std::string s;
  for (int i = 0; i < argc; ++i) s += (i ? " " : "") + std::string(argv[i]);
  return s;
}

// Whether the command asks for the sample tree's node server, whose threads call MPI besides the
// main one (MPI_THREAD_MULTIPLE must be asked for at MPI_Init, before the options are parsed).
bool wantsNodeServer(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]).rfind("--node-server", 0) == 0) return true;
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  lzb::preferPassiveOmpWait(argv);
  // Frames reuse their buffers without faulting them in again (2-rank hybrid, city 1080p:
  // composite 1.7-1.9 -> 1.2 ms, runs/composite/heap_ab.csv).
  lzb::keepFreedMemory();
  lzb::oneArenaUnderAddressLimit();
  lzb::mpi::Session session(&argc, &argv, wantsNodeServer(argc, argv));
  const lzb::mpi::Group g = lzb::mpi::Group::world();
  lzb::setProcessesOnMachine(lzb::mpi::ranksOnMachine(g));  // they share its memory
  const std::string commandLine = joinArgs(argc, argv);

  CLI::App app{"lzb: output-sensitive parallel rendering of highly complex scenes"};
  app.require_subcommand(1);
  lzb::RenderArgs render;
  addRenderOptions(*app.add_subcommand("render", "render frames and write images + report.json"),
                   render);
  lzb::SweepArgs sweep;
  addSweepOptions(*app.add_subcommand("sweep", "render every combination of --param values against "
                                               "the exact reference: sweep.csv + sweep.png"),
                  sweep);
  lzb::BatchArgs batch;
  addBatchOptions(*app.add_subcommand("batch", "many renders in one job: each line of FILE holds "
                                               "the arguments of one `lzb render`"),
                  batch);
  lzb::InfoArgs info;
  addInfoOptions(*app.add_subcommand("info", "triangle counts, bounds, octree statistics, memory"),
                 info);
  lzb::LimitsArgs limits;
  addLimitsOptions(*app.add_subcommand("limits", "what this machine can do at most: memory copy, "
                                                 "atomic-min scatter, key writes (JSON)"),
                   limits);
  lzb::ExportArgs exportArgs;
  addExportOptions(*app.add_subcommand("export", "the fully instanced scene as one binary PLY mesh"),
                   exportArgs);
  lzb::BuildTreeArgs buildTree;
  addBuildTreeOptions(*app.add_subcommand("build-tree", "the randomized sample tree of a scene, "
                                                        "written as a tree store for --method sampletree"),
                      buildTree);
  lzb::CompareArgs compare;
  addCompareOptions(*app.add_subcommand("compare", "accuracy of image A against reference B (JSON); "
                                                    "with --scene, witnessed by rays as in the report"),
                    compare);

  lzb::ReportArgs reportArgs;
  addReportOptions(*app.add_subcommand("report",
                                       "rebuild DIR/report.json from the record a render "
                                       "keeps there (job.json, frames.jsonl)"),
                   reportArgs);

  try {
    // Parsing is agreed on like every step that can fail on one rank alone.
    bool helpShown = false;
    lzb::mpi::agree(g, [&] {
      try {
        app.parse(argc, argv);
        if (app.got_subcommand("render")) lzb::applyQuality(*app.get_subcommand("render"), render);
        if (app.got_subcommand("sweep")) lzb::applyQuality(*app.get_subcommand("sweep"), sweep.render);
      } catch (const CLI::Success& e) {
        if (g.root()) app.exit(e);
        helpShown = true;
      } catch (const CLI::ParseError& e) {
        throw lzb::InputError(std::string(e.what()) + "\nRun 'lzb --help' for the options.");
      }
    });
    if (helpShown) return 0;
    if (app.got_subcommand("render")) return runRender(render, g, commandLine);
    if (app.got_subcommand("sweep")) return runSweep(sweep, g, commandLine);
    if (app.got_subcommand("batch")) return runBatch(batch, g);
    // info, limits, export, build-tree, report and compare: work of each rank alone, written by the
    // root.
    int status = 0;
    lzb::mpi::agree(g, [&] {
      if (app.got_subcommand("info")) status = runInfo(info, g);
      else if (app.got_subcommand("limits")) status = runLimits(limits, g);
      else if (app.got_subcommand("export")) status = runExport(exportArgs, g);
      else if (app.got_subcommand("build-tree")) status = runBuildTree(buildTree, g);
      else if (app.got_subcommand("report"))
        status = runReport(reportArgs, g);
      else status = runCompare(compare, g);
    });
    return status;
  } catch (const lzb::mpi::JobFailed& e) {
    return e.status;  // every rank agreed; the root printed the messages
  } catch (const std::exception& e) {
    // Outside an agreement (between collectives): end every rank now.
    if (g.size > 1) lzb::mpi::abortJob(g, e);
    std::fprintf(stderr, "lzb: %s\n", lzb::mpi::messageOf(e).c_str());
    return lzb::mpi::statusOf(e);
  }
}
