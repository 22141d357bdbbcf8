#pragma once
// `lzb export SCENE OUT.ply`: the fully instanced scene as one binary PLY mesh (three vertices
// per triangle, world coordinates, the triangle's colour on its face), for tools that cannot
// read lzb's scene files or built-in scenes (the peer study renders it with ParaView's pvbatch).
// Refuses scenes above --max-triangles before writing anything.
#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

#include "mpi/group.hpp"

namespace lzb {

struct ExportArgs {
  std::string scene, out;
  uint64_t maxTriangles = 50'000'000;
  bool quiet = false;
};

void addExportOptions(CLI::App& command, ExportArgs& args);
int runExport(const ExportArgs& args, const mpi::Group& g);

}  // namespace lzb
