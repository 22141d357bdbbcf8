#pragma once
// `lzb sweep SCENE --method M --param NAME=V1,V2,...`: renders every combination of the listed
// option values along the frames `lzb render` would render, judges each against the exact
// reference (rendered once per frame, shared by every combination), and writes sweep.csv and,
// with gnuplot, sweep.png (frame time against error) at the root rank.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "mpi/group.hpp"
#include "src/cli/render_command.hpp"

namespace lzb {

struct SweepArgs {
  RenderArgs render;                  // what every combination starts from
  std::vector<std::string> params;    // --param NAME=V1,V2,...
  const CLI::App* command = nullptr;  // the sweep's own options, to see what was given plainly
};

void addSweepOptions(CLI::App& command, SweepArgs& args);
// Returns the process exit status. Throws InputError for bad input (on every rank alike).
int runSweep(const SweepArgs& args, const mpi::Group& g, const std::string& commandLine);

}  // namespace lzb
