// The tree store: round trip, and every kind of damage refused with an error naming the store.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "src/core/error.hpp"
#include "src/sampletree/crc32c.hpp"
#include "tests/support/files.hpp"
#include "tests/support/random_geometry.hpp"
#include "src/sampletree/tree_build.hpp"
#include "src/sampletree/tree_store.hpp"

namespace lzb::sampletree {
namespace {

namespace fs = std::filesystem;

fs::path tempStore(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "lzb_tree_store_test";
  fs::create_directories(dir);
  return dir / (name + ".lzbtree");
}

void writeBytes(const fs::path& p, const std::vector<char>& bytes) {
  std::ofstream(p, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

// The message of readTree's InputError ("" when it read the file).
std::string readError(const fs::path& p) {
  try {
    readTree(p.string());
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

SampleTree sampleTree() {
  // Enough triangles for several 64 KiB blocks.
  return buildTree(test::scatteredTriangles(6000, 0.02f), TreeParams{13.8, 3, 16}, 2);
}

TEST(Crc32c, KnownValue) {
  EXPECT_EQ(crc32c("123456789", 9), 0xE3069283u);  // the standard check value
  EXPECT_EQ(crc32c("6789", 4, crc32c("12345", 5)), 0xE3069283u);
  EXPECT_EQ(crc32cPortable("123456789", 9), 0xE3069283u);
  // The instruction and the table agree at every length and alignment.
  std::vector<uint8_t> bytes(200);
  for (size_t k = 0; k < bytes.size(); ++k) bytes[k] = uint8_t(k * 37 + 11);
  for (size_t at = 0; at < 8; ++at)
    for (size_t n = 0; n + at <= bytes.size(); n += 13)
      ASSERT_EQ(crc32c(bytes.data() + at, n, 7), crc32cPortable(bytes.data() + at, n, 7)) << n;
}

TEST(TreeStore, RoundTrips) {
  const SampleTree tree = sampleTree();
  const fs::path p = tempStore("roundtrip");
  writeTree(tree, p.string());
  EXPECT_EQ(fs::file_size(p), storeBytes(tree));
  const SampleTree back = readTree(p.string());
  EXPECT_EQ(back.params.c, tree.params.c);
  EXPECT_EQ(back.params.seed, tree.params.seed);
  EXPECT_EQ(back.params.leafTriangles, tree.params.leafTriangles);
  EXPECT_EQ(back.origin, tree.origin);
  EXPECT_EQ(back.size, tree.size);
  EXPECT_EQ(back.sceneTriangles, tree.sceneTriangles);
  ASSERT_EQ(back.nodes.size(), tree.nodes.size());
  EXPECT_EQ(std::memcmp(back.nodes.data(), tree.nodes.data(), tree.nodes.size() * sizeof(TreeNode)), 0);
  EXPECT_EQ(back.positions, tree.positions);
  EXPECT_EQ(back.ids, tree.ids);
  EXPECT_EQ(back.colours, tree.colours);
}

TEST(TreeStore, EveryCorruptedBlockIsFound) {
  const fs::path p = tempStore("corrupt");
  writeTree(sampleTree(), p.string());
  const std::vector<char> good = test::fileBytes(p);
  uint64_t payload = 0;
  std::memcpy(&payload, good.data() + 96, 8);  // the header's payload size
  const size_t blocks = size_t((payload + kStoreBlock - 1) / kStoreBlock);
  ASSERT_GE(blocks, 3u);
  ASSERT_EQ(good.size(), kStoreHeaderBytes + payload + 4 * blocks);
  for (size_t b = 0; b < blocks; ++b) {
    std::vector<char> bad = good;
    const size_t length = size_t(std::min<uint64_t>(kStoreBlock, payload - b * kStoreBlock));
    const size_t at = kStoreHeaderBytes + b * kStoreBlock + length / 2;
    bad[at] = char(bad[at] ^ 0x10);
    writeBytes(p, bad);
    const std::string e = readError(p);
    EXPECT_NE(e.find(p.string()), std::string::npos) << "block " << b << ": " << e;
    EXPECT_NE(e.find("corrupted"), std::string::npos) << "block " << b << ": " << e;
  }
}

TEST(TreeStore, CorruptedHeaderOrTableIsFound) {
  const fs::path p = tempStore("header");
  writeTree(sampleTree(), p.string());
  const std::vector<char> good = test::fileBytes(p);
  for (size_t at : {size_t(20), size_t(60), good.size() - 2}) {  // header counts, header c, table
    std::vector<char> bad = good;
    bad[at] = char(bad[at] ^ 0x01);
    writeBytes(p, bad);
    const std::string e = readError(p);
    EXPECT_NE(e.find(p.string()), std::string::npos) << at << ": " << e;
    EXPECT_NE(e.find("corrupted"), std::string::npos) << at << ": " << e;
  }
}

TEST(TreeStore, TruncatedFilesAreFound) {
  const fs::path p = tempStore("truncated");
  writeTree(sampleTree(), p.string());
  const std::vector<char> good = test::fileBytes(p);
  for (size_t keep : {size_t(0), size_t(64), size_t(kStoreHeaderBytes), good.size() / 2, good.size() - 1}) {
    writeBytes(p, std::vector<char>(good.begin(), good.begin() + long(keep)));
    const std::string e = readError(p);
    EXPECT_NE(e.find(p.string()), std::string::npos) << keep << ": " << e;
    EXPECT_NE(e.find("truncated"), std::string::npos) << keep << ": " << e;
  }
}

TEST(TreeStore, WrongVersionAndForeignFilesAreRefused) {
  const fs::path p = tempStore("version");
  writeTree(sampleTree(), p.string());
  std::vector<char> bytes = test::fileBytes(p);
  const uint32_t version = kStoreVersion + 1;
  std::memcpy(bytes.data() + 8, &version, 4);
  writeBytes(p, bytes);
  std::string e = readError(p);
  EXPECT_NE(e.find(p.string()), std::string::npos) << e;
  EXPECT_NE(e.find("version 2"), std::string::npos) << e;
  bytes[0] = 'X';
  writeBytes(p, bytes);
  e = readError(p);
  EXPECT_NE(e.find("not a sample tree store"), std::string::npos) << e;
}

}  // namespace
}  // namespace lzb::sampletree
