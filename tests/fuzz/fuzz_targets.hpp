#pragma once
// Fuzz targets of the scene input: the TOML scene reader and the mesh loaders (file checks, then
// assimp, then ours). Plain functions, so the same entry runs under libFuzzer (fuzz_main.cpp,
// built with clang by scripts/fuzz.sh) and in ctest's replay of the kept inputs
// (fuzz_replay_test.cpp, built with the normal build).
//
// Each writes the input to a private folder as `input.<ext>` and loads it as `lzb render` would
// (loadScene). Malformed input must end in a clean refusal, an InputError, which the target
// swallows; a crash, a sanitizer report or any other exception (it escapes) is a finding.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace lzb::fuzz {

int fuzzToml(const uint8_t* data, size_t size);
int fuzzOff(const uint8_t* data, size_t size);
int fuzzPly(const uint8_t* data, size_t size);
int fuzzObj(const uint8_t* data, size_t size);
int fuzzStl(const uint8_t* data, size_t size);
int fuzzGltf(const uint8_t* data, size_t size);
int fuzzGlb(const uint8_t* data, size_t size);

struct FuzzTarget {
  std::string name;  // tests/fuzz/corpus/<name>, tests/fuzz/regressions/<name>, fuzz_<name>
  int (*run)(const uint8_t* data, size_t size);
};
const std::vector<FuzzTarget>& fuzzTargets();

}  // namespace lzb::fuzz
