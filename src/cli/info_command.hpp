#pragma once
// `lzb info SCENE`: unique and expanded triangle counts, bounds, octree statistics, memory.
#include <string>

#include <CLI/CLI.hpp>

#include "mpi/group.hpp"

namespace lzb {

struct InfoArgs {
  std::string scene;
  int maxDepth = 16;
  int leafSize = 150;
  bool json = false;
  bool quiet = false;
};

void addInfoOptions(CLI::App& command, InfoArgs& args);
int runInfo(const InfoArgs& args, const mpi::Group& g);

}  // namespace lzb
