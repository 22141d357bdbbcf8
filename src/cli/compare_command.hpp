#pragma once
// `lzb compare A.exr B.exr [--scene SCENE]`: accuracy of A against the reference B, printed as
// JSON; with --scene, judged with the ray witness exactly as `lzb render --reference` judges.
#include <string>

#include <CLI/CLI.hpp>

#include "mpi/group.hpp"

namespace lzb {

struct CompareArgs {
  std::string test, reference, scene;
  int threads = 0;
};

void addCompareOptions(CLI::App& command, CompareArgs& args);
int runCompare(const CompareArgs& args, const mpi::Group& g);

}  // namespace lzb
