// Replays every kept fuzz input (tests/fuzz/corpus/<target>: seeds and what the fuzzers found
// worth keeping; tests/fuzz/regressions/<target>: inputs that crashed or escaped before a fix)
// through the fuzz targets' entry functions, in the normal build: each must load or be refused
// with an InputError (the entry swallows those), never crash or throw anything else.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "tests/fuzz/fuzz_targets.hpp"

namespace lzb::fuzz {

// Test names and failures show the target's name (found by argument-dependent lookup).
void PrintTo(const FuzzTarget& t, std::ostream* os) { *os << t.name; }

namespace {

namespace fs = std::filesystem;

std::vector<fs::path> keptInputs(const std::string& target) {
  std::vector<fs::path> files;
  for (const char* kind : {"corpus", "regressions"}) {
    const fs::path dir = fs::path(LZB_FUZZ_DIR) / kind / target;
    if (!fs::is_directory(dir)) continue;
    for (const auto& entry : fs::directory_iterator(dir))
      if (entry.is_regular_file() && entry.path().filename() != "README.md")
        files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<uint8_t> bytesOf(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class FuzzReplay : public ::testing::TestWithParam<FuzzTarget> {};

TEST_P(FuzzReplay, EveryKeptInputLoadsOrIsRefused) {
  const std::vector<fs::path> files = keptInputs(GetParam().name);
  // Every target has seeds: an empty list means the folder moved, not that all passed.
  ASSERT_FALSE(files.empty()) << "no kept inputs for " << GetParam().name << " in " << LZB_FUZZ_DIR;
  for (const fs::path& file : files) {
    const std::vector<uint8_t> data = bytesOf(file);
    try {
      EXPECT_EQ(GetParam().run(data.data(), data.size()), 0) << file;
    } catch (const std::exception& e) {
      ADD_FAILURE() << file << ": not refused with an InputError: " << e.what();
    }
  }
  RecordProperty("inputs", int(files.size()));
}

INSTANTIATE_TEST_SUITE_P(Targets, FuzzReplay, ::testing::ValuesIn(fuzzTargets()),
                         [](const auto& info) { return info.param.name; });

}  // namespace
}  // namespace lzb::fuzz
