#pragma once
// The tests' real meshes: CGAL's scanned meshes in the build's data folder, fetched there by
// scripts/fetch-test-meshes.sh on first use (from ctest or when a test binary is run directly).
#include <filesystem>
#include <string>

namespace lzb::test {

// The build's data folder (build/data).
std::filesystem::path dataDir();

// The path of scanned mesh `name` (e.g. "armadillo.off"), fetched on first use; "" when it cannot
// be had (the caller skips).
std::string scannedMesh(const std::string& name);

}  // namespace lzb::test
