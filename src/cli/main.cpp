// lzb: output-sensitive parallel rendering of highly complex scenes.
#include <cstdio>
#include <string>

#include <CLI/CLI.hpp>

#include "mpi/group.hpp"
#include "src/cli/compare_command.hpp"
#include "src/cli/info_command.hpp"
#include "src/cli/omp_wait_policy.hpp"
#include "src/cli/render_command.hpp"
#include "src/core/error.hpp"

namespace {

std::string joinArgs(int argc, char** argv) {
  std::string s;
  for (int i = 0; i < argc; ++i) s += (i ? " " : "") + std::string(argv[i]);
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  lzb::preferPassiveOmpWait(argv);
  lzb::mpi::Session session(&argc, &argv);
  const lzb::mpi::Group g = lzb::mpi::Group::world();
  const std::string commandLine = joinArgs(argc, argv);

  CLI::App app{"lzb: output-sensitive parallel rendering of highly complex scenes"};
  app.require_subcommand(1);
  lzb::RenderArgs render;
  addRenderOptions(*app.add_subcommand("render", "render frames and write images + report.json"),
                   render);
  lzb::InfoArgs info;
  addInfoOptions(*app.add_subcommand("info", "triangle counts, bounds, octree statistics, memory"),
                 info);
  lzb::CompareArgs compare;
  addCompareOptions(*app.add_subcommand("compare", "accuracy of image A against reference B (JSON)"),
                    compare);

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    if (g.root()) app.exit(e);
    return 0;
  } catch (const CLI::ParseError& e) {
    if (g.root()) std::fprintf(stderr, "lzb: error: %s\nRun 'lzb --help' for the options.\n", e.what());
    return 2;
  }

  try {
    if (app.got_subcommand("render")) return runRender(render, g, commandLine);
    if (app.got_subcommand("info")) return runInfo(info, g);
    return runCompare(compare, g);
  } catch (const lzb::InputError& e) {
    if (g.root()) std::fprintf(stderr, "lzb: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lzb: internal error on rank %d: %s\n", g.rank, e.what());
    if (g.size > 1) MPI_Abort(g.comm, 1);
    return 1;
  }
}
