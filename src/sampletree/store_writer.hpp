#pragma once
// Writes a tree store (tree_store.hpp describes the layout) section by section, so a builder can
// stream a store larger than memory: the header first (rewritten with the checksums at the end),
// then the payload through 64 KiB blocks whose CRC-32C is kept, then the block table.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <vector>

#include "src/sampletree/sample_tree.hpp"
#include "src/sampletree/store_format.hpp"

namespace lzb::sampletree {

// What the header records besides the checksums.
struct StoreMeta {
  TreeParams params;
  glm::dvec3 origin{0.0};
  double size = 1.0;
  uint64_t sceneTriangles = 0, nodes = 0, triangles = 0;
  uint64_t outlineBytes = 0;
};
StoreMeta metaOf(const SampleTree& tree);

class StoreWriter {
 public:
  // Throws InputError naming path when it cannot be created.
  StoreWriter(const std::filesystem::path& path, const StoreMeta& meta);
  // Payload bytes in order: nodes, positions, IDs, colours, the outline.
  void append(const void* data, size_t n);
  // Writes the last block, the block table and the header; throws when the payload appended is
  // not the size the counts give, or the write failed.
  void finish();

 private:
  void flush();
  std::filesystem::path path_;
  std::ofstream out_;
  format::Header header_;
  std::vector<char> block_;
  std::vector<uint32_t> crcs_;
  uint64_t appended_ = 0;
};

}  // namespace lzb::sampletree
