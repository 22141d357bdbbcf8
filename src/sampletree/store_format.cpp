#include "src/sampletree/store_format.hpp"

#include <cstddef>
#include <cstring>

#include "src/core/error.hpp"
#include "src/sampletree/crc32c.hpp"
#include "src/sampletree/tree_store.hpp"

namespace lzb::sampletree::format {

static_assert(sizeof(Header) == kStoreHeaderBytes, "the header is 128 bytes");

uint64_t payloadBytes(uint64_t nodes, uint64_t triangles, uint64_t outlineBytes) {
  return nodes * sizeof(TreeNode) + triangles * (kPositionBytes + kIdBytes + kColourBytes) +
         outlineBytes;
}

uint64_t blockCount(uint64_t payload) { return (payload + kStoreBlock - 1) / kStoreBlock; }

Sections sections(uint64_t nodes, uint64_t triangles) {
  Sections s;
  s.positions = nodes * sizeof(TreeNode);
  s.ids = s.positions + triangles * kPositionBytes;
  s.colours = s.ids + triangles * kIdBytes;
  s.outline = s.colours + triangles * kColourBytes;
  return s;
}

void checkHeader(const Header& h, uint64_t fileBytes, const std::string& where) {
  require(std::memcmp(h.magic, kMagic, sizeof(kMagic)) == 0, where,
          "not a sample tree store (no LZBSTREE magic)");
  require(h.version == kStoreVersion, where,
          "store format version " + std::to_string(h.version) + ", this lzb reads version " +
              std::to_string(kStoreVersion) + " (rebuild it with lzb build-tree)");
  require(crc32c(&h, offsetof(Header, headerCrc)) == h.headerCrc, where,
          "the header is corrupted: checksum mismatch");
  require(h.blockSize == kStoreBlock, where, "block size " + std::to_string(h.blockSize) +
                                                 ", expected " + std::to_string(kStoreBlock));
  // Counts beyond the file's bytes would overflow the sizes below: refuse them first.
  require(h.nodes <= fileBytes && h.triangles <= fileBytes && h.outlineBytes <= kMaxOutlineBytes,
          where, "the header's counts are absurd");
  require(h.payloadBytes == payloadBytes(h.nodes, h.triangles, h.outlineBytes), where,
          "the header's sizes do not agree");
  const uint64_t expected = kStoreHeaderBytes + h.payloadBytes + 4 * blockCount(h.payloadBytes);
  require(fileBytes == expected, where,
          (fileBytes < expected ? "truncated: " : "wrong size: ") + std::to_string(fileBytes) +
              " bytes, the header says " + std::to_string(expected));
}

void checkNodes(std::span<const TreeNode> nodes, uint64_t triangles, const std::string& where) {
  uint64_t next = 0;
  for (size_t i = 0; i < nodes.size(); ++i) {
    const TreeNode& n = nodes[i];
    const auto bad = [i](const char* what) {
      return [i, what] { return "node " + std::to_string(i) + ": " + what; };
    };
    require(n.subtreeEnd > i && n.subtreeEnd <= nodes.size(), where, bad("bad subtree end"));
    require(n.firstTriangle == next && n.triangleCount <= triangles - next, where,
            bad("bad triangle range"));
    require(n.level <= 20, where, bad("bad level"));
    next += n.triangleCount;
  }
  require(next == triangles, where, "the nodes do not hold every triangle");
}

}  // namespace lzb::sampletree::format
