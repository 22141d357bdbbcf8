#pragma once
// `lzb limits`: what this machine can do at most, for benchmarks to measure methods against in
// the same run: a large memory copy (bytes/s), random 64-bit atomic minima into a frame (the
// splatting core's scatter limit, /s) and streaming writes of compositing keys (pixels/s).
#include <CLI/CLI.hpp>

#include "mpi/group.hpp"

namespace lzb {

struct LimitsArgs {
  int width = 640, height = 480;
  int threads = 0;  // 0: the cores this rank owns
  double seconds = 1.0;
};

void addLimitsOptions(CLI::App& command, LimitsArgs& args);
int runLimits(const LimitsArgs& args, const mpi::Group& g);

}  // namespace lzb
