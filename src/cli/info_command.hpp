#pragma once
// `lzb info SCENE`: unique and expanded triangle counts, bounds, octree statistics, memory, and
// the estimated peak per rank of rendering it (--method, --ranks, --distribute, --regions).
#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

#include "mpi/group.hpp"

namespace lzb {

struct InfoArgs {
  std::string scene;
  int maxDepth = 16;
  int leafSize = 150;
  std::string method = "hybrid";
  int ranks = 1;
  std::string distribute = "replicate";
  uint32_t regions = 0;
  std::string bvh = "fast";  // the render option the estimate assumes
  bool json = false;
  bool quiet = false;
};

void addInfoOptions(CLI::App& command, InfoArgs& args);
int runInfo(const InfoArgs& args, const mpi::Group& g);

}  // namespace lzb
