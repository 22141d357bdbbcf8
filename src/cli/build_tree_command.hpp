#pragma once
// `lzb build-tree SCENE --out PATH [--mem-mb M]`: builds the randomized sample tree of a scene, in
// memory or (with --mem-mb) out of core within M MiB, streaming the scene (src/sampletree/
// external_build.hpp), and writes it as a tree store (src/sampletree/tree_store.hpp) for
// `lzb render --method sampletree --tree PATH`. Bad input (scene, options, too many triangles)
// writes nothing.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

#include "mpi/group.hpp"
#include "src/sampletree/sample_tree.hpp"

namespace lzb {

struct BuildTreeArgs {
  std::string scene, out;
  double c = 13.8;
  uint64_t seed = 1;
  uint32_t leafTriangles = sampletree::kDefaultLeafTriangles;
  int threads = 0;
  double memMb = 0.0;  // > 0: out of core within this budget
  bool quiet = false;
};

void addBuildTreeOptions(CLI::App& command, BuildTreeArgs& args);
int runBuildTree(const BuildTreeArgs& args, const mpi::Group& g);

}  // namespace lzb
