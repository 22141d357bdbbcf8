#pragma once
// `lzb render SCENE`: render frames with one method (optionally against a reference), write the
// images and report.json at the root rank.
#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "mpi/group.hpp"

namespace lzb {

struct RenderArgs {
  std::string scene;
  std::string method = "hybrid";
  std::string quality;    // empty: the options' own defaults; else fast | balanced | exact
  std::string reference;  // empty: none
  bool subsamples = false;  // store the 4x4 sub-sample IDs and box colour in each EXR
  std::string out = "out";
  std::string composite = "tiles";  // mpi/composite.hpp; the fastest in runs/composite
  int frameGroups = 1;                // frame-parallel batches
  std::string distribute = "replicate";  // src/regions/share.hpp: replicate | data
  std::string bvh = "fast";              // fast | compact: Embree's leaves (raycast, lzb, hybrid)
  uint32_t regions = 0;                  // --distribute data: 0 = from the scene's size
  int threads = 0;  // 0: the cores this rank owns
  uint64_t seed = 1;
  int width = 0, height = 0;  // 0: the scene file's, else 640x480
  int frames = 1;
  std::string frameRange;     // "A:B": frames A..B-1 only (frame_record.hpp); empty: all
  bool resume = false;        // skip the frames --out's record holds complete
  double stallTimeout = 0.0;  // mpi/watchdog.hpp: 0 = automatic
  double fov = 0.0, nearPlane = 0.0, farPlane = 0.0;  // 0: scene's or automatic
  bool quiet = false;
};

void addRenderOptions(CLI::App& command, RenderArgs& args);
// Parses `--NAME=VALUE` texts into `args` with the render command's own options, so method
// options land in the registered methods as for `lzb render`; the other fields keep their values.
// Throws InputError `where: ...` for a text CLI11 refuses.
void parseRenderOverrides(RenderArgs& args, const std::vector<std::string>& options,
                          const std::string& where);
// Returns the process exit status. Throws InputError for bad input (on every rank alike).
int runRender(const RenderArgs& args, const mpi::Group& g, const std::string& commandLine);

}  // namespace lzb
