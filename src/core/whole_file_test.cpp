// A whole file comes back byte for byte; a missing one is an InputError naming it.
#include "src/core/whole_file.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "src/core/error.hpp"

namespace lzb {
namespace {

TEST(WholeFile, ReadsEveryByteAndNamesAMissingFile) {
  const auto path = std::filesystem::temp_directory_path() / "lzb_whole_file_test.bin";
  const std::string bytes("ply\0\n\xff tail", 11);
  std::ofstream(path, std::ios::binary) << bytes;
  EXPECT_EQ(readWholeFile(path), bytes);
  std::filesystem::remove(path);
  try {
    readWholeFile(path, "cannot read the batch file");
    FAIL() << "a missing file was read";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), path.string() + ": cannot read the batch file");
  }
}

}  // namespace
}  // namespace lzb
