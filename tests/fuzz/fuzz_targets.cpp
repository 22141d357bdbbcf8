#include "tests/fuzz/fuzz_targets.hpp"

#include <stdlib.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string_view>

#include "src/core/error.hpp"
#include "src/scene/load.hpp"

namespace lzb::fuzz {

namespace fs = std::filesystem;

namespace {

// A mesh that TOML inputs may name (the seeds do), so the fuzzer reaches instancing.
constexpr const char* kTetOff = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

fs::path makeWorkDir() {
  std::string pattern = (fs::temp_directory_path() / "lzb-fuzz-XXXXXX").string();
  if (!mkdtemp(pattern.data())) throw std::runtime_error("fuzz: cannot create " + pattern);
  std::ofstream(fs::path(pattern) / "tet.off") << kTetOff;
  return pattern;
}

// This process's folder for inputs, removed at exit.
const fs::path& workDir() {
  static const fs::path dir = makeWorkDir();
  static const bool cleanup = std::atexit([] {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }) == 0;
  (void)cleanup;
  return dir;
}

// Writes the input as input.<ext> and loads it as `lzb render` would; refusals are expected.
int loadAs(const char* ext, const uint8_t* data, size_t size) {
  const fs::path file = workDir() / (std::string("input.") + ext);
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  }
  try {
    loadScene(file.string(), true);
  } catch (const InputError&) {
  }
  return 0;
}

// Generators that build up to 5e7 stored triangles from a few bytes (city, chessboard) or 10^6
// instances per level (replicated) are valid scenes that take seconds each: the TOML target
// skips inputs naming them (builtin_test covers their parameters).
bool namesCostlyGenerator(std::string_view text) {
  for (std::string_view name : {"city", "chessboard", "replicated"})
    if (text.find(name) != std::string_view::npos) return true;
  return false;
}

}  // namespace

int fuzzToml(const uint8_t* data, size_t size) {
  if (namesCostlyGenerator({reinterpret_cast<const char*>(data), size})) return 0;
  return loadAs("toml", data, size);
}
int fuzzOff(const uint8_t* data, size_t size) { return loadAs("off", data, size); }
int fuzzPly(const uint8_t* data, size_t size) { return loadAs("ply", data, size); }
int fuzzObj(const uint8_t* data, size_t size) { return loadAs("obj", data, size); }
int fuzzStl(const uint8_t* data, size_t size) { return loadAs("stl", data, size); }
int fuzzGltf(const uint8_t* data, size_t size) { return loadAs("gltf", data, size); }
int fuzzGlb(const uint8_t* data, size_t size) { return loadAs("glb", data, size); }

const std::vector<FuzzTarget>& fuzzTargets() {
  static const std::vector<FuzzTarget> targets = {
      {"toml", fuzzToml}, {"off", fuzzOff},   {"ply", fuzzPly}, {"obj", fuzzObj},
      {"stl", fuzzStl},   {"gltf", fuzzGltf}, {"glb", fuzzGlb}};
  return targets;
}

}  // namespace lzb::fuzz
