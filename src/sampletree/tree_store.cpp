#include "src/sampletree/tree_store.hpp"

#include <cstddef>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "src/core/atomic_file.hpp"
#include "src/core/error.hpp"
#include "src/sampletree/crc32c.hpp"
#include "src/sampletree/store_format.hpp"
#include "src/sampletree/store_writer.hpp"

namespace lzb::sampletree {

namespace {

using format::blockCount;
using format::Header;
using format::payloadBytes;

// Reads the payload block by block, checking each block's CRC before handing out its bytes.
class BlockReader {
 public:
  BlockReader(std::ifstream& in, const std::vector<uint32_t>& crcs, uint64_t payload,
              const std::string& where)
      : in_(in), crcs_(crcs), payload_(payload), where_(where) {}
  void read(void* data, size_t n) {
    auto* p = static_cast<char*>(data);
    while (n > 0) {
      if (pos_ == block_.size()) load();
      const size_t k = std::min(n, block_.size() - pos_);
      std::memcpy(p, block_.data() + pos_, k);
      p += k, n -= k, pos_ += k;
    }
  }

 private:
  void load() {
    const uint64_t begin = next_ * kStoreBlock;
    const size_t size = size_t(std::min<uint64_t>(kStoreBlock, payload_ - begin));
    block_.resize(size);
    in_.read(block_.data(), std::streamsize(size));
    require(bool(in_), where_, "block " + std::to_string(next_) + " could not be read (truncated)");
    require(crc32c(block_.data(), size) == crcs_[size_t(next_)], where_,
            "block " + std::to_string(next_) + " (payload bytes " + std::to_string(begin) + ".." +
                std::to_string(begin + size) + ") is corrupted: checksum mismatch");
    ++next_;
    pos_ = 0;
  }
  std::ifstream& in_;
  const std::vector<uint32_t>& crcs_;
  uint64_t payload_;
  std::string where_;
  std::vector<char> block_;
  size_t pos_ = 0;
  uint64_t next_ = 0;
};

template <class T>
void appendArray(StoreWriter& w, const std::vector<T>& v) {
  w.append(v.data(), v.size() * sizeof(T));
}

void writeStoreFile(const SampleTree& tree, const std::filesystem::path& path) {
  StoreWriter w(path, metaOf(tree));
  appendArray(w, tree.nodes);
  appendArray(w, tree.positions);
  appendArray(w, tree.ids);
  appendArray(w, tree.colours);
  w.append(tree.outline.data(), tree.outline.size());
  w.finish();
}

Header readHeader(std::ifstream& in, uint64_t fileBytes, const std::string& where) {
  require(fileBytes >= kStoreHeaderBytes, where,
          "truncated: " + std::to_string(fileBytes) + " bytes, less than the 128-byte header");
  Header h;
  in.read(reinterpret_cast<char*>(&h), sizeof(h));
  require(bool(in), where, "the header could not be read");
  format::checkHeader(h, fileBytes, where);
  return h;
}

}  // namespace

uint64_t storeBytes(const SampleTree& tree) {
  const uint64_t payload = payloadBytes(tree.nodes.size(), tree.ids.size(), tree.outline.size());
  return kStoreHeaderBytes + payload + 4 * blockCount(payload);
}

void writeTree(const SampleTree& tree, const std::string& path) {
  writeAtomically(path, [&](const std::filesystem::path& tmp) { writeStoreFile(tree, tmp); });
}

SampleTree readTree(const std::string& path) {
  const std::string where = path + " (sample tree store)";
  std::error_code ec;
  const uint64_t fileBytes = std::filesystem::file_size(path, ec);
  require(!ec, where, "cannot be read: " + ec.message());
  std::ifstream in(path, std::ios::binary);
  require(bool(in), where, "cannot be opened");
  const Header h = readHeader(in, fileBytes, where);
  std::vector<uint32_t> crcs(size_t(blockCount(h.payloadBytes)));
  in.seekg(std::streamoff(kStoreHeaderBytes + h.payloadBytes));
  in.read(reinterpret_cast<char*>(crcs.data()), std::streamsize(crcs.size() * 4));
  require(bool(in), where, "the block table could not be read");
  require(crc32c(crcs.data(), crcs.size() * 4) == h.tableCrc, where,
          "the block table is corrupted: checksum mismatch");
  in.seekg(std::streamoff(kStoreHeaderBytes));
  SampleTree t;
  t.params = {h.c, h.seed, h.leafTriangles};
  t.origin = {h.origin[0], h.origin[1], h.origin[2]};
  t.size = h.size;
  t.sceneTriangles = h.sceneTriangles;
  t.nodes.resize(size_t(h.nodes));
  t.positions.resize(size_t(3 * h.triangles));
  t.ids.resize(size_t(h.triangles));
  t.colours.resize(size_t(h.triangles));
  t.outline.resize(size_t(h.outlineBytes));
  BlockReader r(in, crcs, h.payloadBytes, where);
  r.read(t.nodes.data(), t.nodes.size() * sizeof(TreeNode));
  r.read(t.positions.data(), t.positions.size() * sizeof(glm::vec3));
  r.read(t.ids.data(), t.ids.size() * sizeof(uint64_t));
  r.read(t.colours.data(), t.colours.size() * sizeof(Rgba8));
  r.read(t.outline.data(), t.outline.size());
  format::checkNodes(t.nodes, t.ids.size(), where);
  return t;
}

}  // namespace lzb::sampletree
