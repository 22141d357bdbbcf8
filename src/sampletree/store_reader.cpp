#include "src/sampletree/store_reader.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "src/core/error.hpp"
#include "src/sampletree/crc32c.hpp"
#include "src/sampletree/tree_store.hpp"

namespace lzb::sampletree {

StoreReader::StoreReader(const std::string& path, Contents contents)
    : where_(path + " (sample tree store)") {
  std::error_code ec;
  fileBytes_ = std::filesystem::file_size(path, ec);
  require(!ec, where_, "cannot be read: " + ec.message());
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  require(fd_ >= 0, where_, std::string("cannot be opened: ") + std::strerror(errno));
  require(fileBytes_ >= kStoreHeaderBytes, where_,
          "truncated: " + std::to_string(fileBytes_) + " bytes, less than the 128-byte header");
  readFile(0, sizeof(header_), &header_, "the header");
  format::checkHeader(header_, fileBytes_, where_);
  sections_ = format::sections(header_.nodes, header_.triangles);
  crcs_.resize(size_t(format::blockCount(header_.payloadBytes)));
  readFile(kStoreHeaderBytes + header_.payloadBytes, crcs_.size() * 4, crcs_.data(), "the block table");
  require(crc32c(crcs_.data(), crcs_.size() * 4) == header_.tableCrc, where_,
          "the block table is corrupted: checksum mismatch");
  table_.outline.resize(size_t(header_.outlineBytes));
  readPayload(sections_.outline, header_.outlineBytes, table_.outline.data());
  if (contents == Contents::kOutline) return;
  table_.params = {header_.c, header_.seed, header_.leafTriangles};
  table_.origin = {header_.origin[0], header_.origin[1], header_.origin[2]};
  table_.size = header_.size;
  table_.sceneTriangles = header_.sceneTriangles;
  table_.nodes.resize(size_t(header_.nodes));
  readPayload(sections_.nodes, header_.nodes * sizeof(TreeNode), table_.nodes.data());
  format::checkNodes(table_.nodes, header_.triangles, where_);
}

std::string readStoreOutline(const std::string& path) {
  return StoreReader(path, StoreReader::Contents::kOutline).table().outline;
}

StoreReader::~StoreReader() {
  if (fd_ >= 0) ::close(fd_);
}

NodePayload StoreReader::read(uint32_t index) {
  const TreeNode& n = table_.nodes.at(index);
  NodePayload p;
  p.positions.resize(3 * size_t(n.triangleCount));
  p.ids.resize(n.triangleCount);
  p.colours.resize(n.triangleCount);
  readPayload(sections_.positions + n.firstTriangle * format::kPositionBytes,
              n.triangleCount * format::kPositionBytes, p.positions.data());
  readPayload(sections_.ids + n.firstTriangle * format::kIdBytes, n.triangleCount * format::kIdBytes,
              p.ids.data());
  readPayload(sections_.colours + n.firstTriangle * format::kColourBytes,
              n.triangleCount * format::kColourBytes, p.colours.data());
  return p;
}

std::vector<NodePayload> StoreReader::readNodes(std::span<const uint32_t> nodes) {
  std::vector<NodePayload> out;
  out.reserve(nodes.size());
  for (uint32_t n : nodes) out.push_back(read(n));
  return out;
}

void StoreReader::readPayload(uint64_t offset, uint64_t n, void* out) {
  auto* dst = static_cast<char*>(out);
  while (n > 0) {
    const uint64_t index = offset / kStoreBlock, within = offset % kStoreBlock;
    const std::vector<char>& b = block(index);
    const uint64_t k = std::min<uint64_t>(n, b.size() - within);
    std::memcpy(dst, b.data() + within, size_t(k));
    dst += k, offset += k, n -= k;
  }
}

// Block `index`, read and checked, or from the memo.
const std::vector<char>& StoreReader::block(uint64_t index) {
  Memo* slot = &memo_[0];
  for (Memo& m : memo_) {
    if (m.index == index) {
      m.used = ++memoClock_;
      return m.bytes;
    }
    if (m.used < slot->used) slot = &m;
  }
  const uint64_t begin = index * kStoreBlock;
  const size_t size = size_t(std::min<uint64_t>(kStoreBlock, header_.payloadBytes - begin));
  slot->index = UINT64_MAX;  // invalid until checked
  slot->bytes.resize(size);
  readFile(kStoreHeaderBytes + begin, size, slot->bytes.data(), "block " + std::to_string(index));
  fileBytesRead_ += size;
  require(crc32c(slot->bytes.data(), size) == crcs_.at(size_t(index)), where_,
          "block " + std::to_string(index) + " (payload bytes " + std::to_string(begin) + ".." +
              std::to_string(begin + size) + ") is corrupted: checksum mismatch");
  slot->index = index;
  slot->used = ++memoClock_;
  return slot->bytes;
}

void StoreReader::readFile(uint64_t offset, size_t n, void* out, const std::string& what) {
  auto* dst = static_cast<char*>(out);
  while (n > 0) {
    const ssize_t got = ::pread(fd_, dst, n, off_t(offset));
    if (got < 0 && errno == EINTR) continue;
    require(got > 0, where_, what + " could not be read" +
                                 (got < 0 ? std::string(": ") + std::strerror(errno) : " (truncated)"));
    dst += got, offset += uint64_t(got), n -= size_t(got);
  }
}

}  // namespace lzb::sampletree
