#include "src/sampletree/store_writer.hpp"

#include <cstddef>
#include <cstring>
#include <string>

#include "src/core/error.hpp"
#include "src/sampletree/crc32c.hpp"
#include "src/sampletree/tree_store.hpp"

namespace lzb::sampletree {

namespace {

format::Header makeHeader(const StoreMeta& m) {
  format::Header h{};
  std::memcpy(h.magic, format::kMagic, sizeof(format::kMagic));
  h.version = kStoreVersion;
  h.blockSize = kStoreBlock;
  h.nodes = m.nodes;
  h.triangles = m.triangles;
  h.sceneTriangles = m.sceneTriangles;
  h.c = m.params.c;
  h.seed = m.params.seed;
  h.leafTriangles = m.params.leafTriangles;
  for (int k = 0; k < 3; ++k) h.origin[k] = m.origin[k];
  h.size = m.size;
  h.outlineBytes = m.outlineBytes;
  h.payloadBytes = format::payloadBytes(h.nodes, h.triangles, h.outlineBytes);
  return h;
}

}  // namespace

StoreMeta metaOf(const SampleTree& tree) {
  return {tree.params, tree.origin, tree.size, tree.sceneTriangles, tree.nodes.size(),
          tree.ids.size(), tree.outline.size()};
}

StoreWriter::StoreWriter(const std::filesystem::path& path, const StoreMeta& meta)
    : path_(path), out_(path, std::ios::binary), header_(makeHeader(meta)) {
  require(bool(out_), path.string(), "cannot be created");
  out_.write(reinterpret_cast<const char*>(&header_), sizeof(header_));  // rewritten in finish()
  block_.reserve(kStoreBlock);
}

void StoreWriter::append(const void* data, size_t n) {
  const auto* p = static_cast<const char*>(data);
  appended_ += n;
  while (n > 0) {
    const size_t k = std::min(n, size_t(kStoreBlock) - block_.size());
    block_.insert(block_.end(), p, p + k);
    p += k, n -= k;
    if (block_.size() == kStoreBlock) flush();
  }
}

void StoreWriter::flush() {
  crcs_.push_back(crc32c(block_.data(), block_.size()));
  out_.write(block_.data(), std::streamsize(block_.size()));
  block_.clear();
}

void StoreWriter::finish() {
  require(appended_ == header_.payloadBytes, path_.string(),
          "internal: " + std::to_string(appended_) + " payload bytes written, the header counts " +
              std::to_string(header_.payloadBytes));
  if (!block_.empty()) flush();
  out_.write(reinterpret_cast<const char*>(crcs_.data()), std::streamsize(crcs_.size() * 4));
  header_.tableCrc = crc32c(crcs_.data(), crcs_.size() * 4);
  header_.headerCrc = crc32c(&header_, offsetof(format::Header, headerCrc));
  out_.seekp(0);
  out_.write(reinterpret_cast<const char*>(&header_), sizeof(header_));
  out_.close();
  require(bool(out_), path_.string(), "write failed");
}

}  // namespace lzb::sampletree
