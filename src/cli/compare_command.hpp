#pragma once
// `lzb compare A.exr B.exr`: accuracy of A against the reference B, printed as JSON.
#include <string>

#include <CLI/CLI.hpp>

#include "mpi/group.hpp"

namespace lzb {

struct CompareArgs {
  std::string test, reference;
};

void addCompareOptions(CLI::App& command, CompareArgs& args);
int runCompare(const CompareArgs& args, const mpi::Group& g);

}  // namespace lzb
