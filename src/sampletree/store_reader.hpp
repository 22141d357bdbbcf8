#pragma once
// The paged reader of a tree store (section 6): opens the store, checks its header and block table
// and reads the node table, which stays resident; a node's triangles are read when asked for,
// checking the CRC of every 64 KiB block they touch. Any fault is an InputError naming the store.
#include <atomic>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "src/sampletree/node_source.hpp"
#include "src/sampletree/sample_tree.hpp"
#include "src/sampletree/store_format.hpp"

namespace lzb::sampletree {

// The scene outline's text (src/core/scene_outline.hpp) of the store at `path`, checked like
// everything the reader reads; InputError naming the store for any fault.
std::string readStoreOutline(const std::string& path);

class StoreReader : public NodeSource {
 public:
  // kOutline: the header, block table and scene outline only (no node table).
  enum class Contents { kTable, kOutline };
  explicit StoreReader(const std::string& path, Contents contents = Contents::kTable);
  ~StoreReader() override;
  StoreReader(const StoreReader&) = delete;
  StoreReader& operator=(const StoreReader&) = delete;

  // The tree without triangles: parameters, root cube, every node and the scene outline.
  const SampleTree& table() const override { return table_; }
  uint64_t triangles() const { return header_.triangles; }
  uint64_t fileBytes() const { return fileBytes_; }
  const std::string& where() const { return where_; }

  // Node `index`'s positions, IDs and colours. Not thread-safe: one loader calls it.
  NodePayload read(uint32_t index);
  std::vector<NodePayload> readNodes(std::span<const uint32_t> nodes) override;
  // Bytes read from the file so far (whole blocks, each once per miss of the block memo).
  uint64_t fileBytesRead() const override { return fileBytesRead_.load(); }

 private:
  void readPayload(uint64_t offset, uint64_t n, void* out);
  const std::vector<char>& block(uint64_t index);
  void readFile(uint64_t offset, size_t n, void* out, const std::string& what);

  std::string where_;
  int fd_ = -1;
  uint64_t fileBytes_ = 0;
  format::Header header_{};
  format::Sections sections_;
  std::vector<uint32_t> crcs_;
  SampleTree table_;
  // The last few verified blocks: neighbouring nodes share blocks (preorder, Morton order).
  static constexpr size_t kMemoBlocks = 4;
  struct Memo {
    uint64_t index = UINT64_MAX;
    uint64_t used = 0;
    std::vector<char> bytes;
  };
  Memo memo_[kMemoBlocks];
  uint64_t memoClock_ = 0;
  std::atomic<uint64_t> fileBytesRead_{0};
};

}  // namespace lzb::sampletree
