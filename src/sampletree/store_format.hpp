#pragma once
// The tree store's bytes on disk (tree_store.hpp describes the layout), shared by the whole-store
// writer and reader (tree_store.cpp) and the paged reader (store_reader.hpp).
#include <cstdint>
#include <span>
#include <string>

#include "src/sampletree/sample_tree.hpp"

namespace lzb::sampletree::format {

constexpr char kMagic[8] = {'L', 'Z', 'B', 'S', 'T', 'R', 'E', 'E'};

struct Header {
  char magic[8];
  uint32_t version;
  uint32_t blockSize;
  uint64_t nodes, triangles, sceneTriangles;
  double c;
  uint64_t seed;
  uint32_t leafTriangles;
  uint32_t reserved0;
  double origin[3];
  double size;
  uint64_t payloadBytes;
  uint64_t outlineBytes;  // the scene outline's text, the payload's last section
  uint64_t reserved1;
  uint32_t tableCrc;
  uint32_t headerCrc;  // of the bytes before it
};

// Bytes of one triangle in the payload: positions (36), ID (8), colour (4).
constexpr uint64_t kPositionBytes = 3 * sizeof(glm::vec3), kIdBytes = sizeof(uint64_t),
                   kColourBytes = sizeof(Rgba8);

// The scene outline is kept to this size, so a damaged header cannot ask for more.
constexpr uint64_t kMaxOutlineBytes = uint64_t(1) << 26;

uint64_t payloadBytes(uint64_t nodes, uint64_t triangles, uint64_t outlineBytes);
uint64_t blockCount(uint64_t payload);

// Where each array starts in the payload.
struct Sections {
  uint64_t nodes = 0, positions = 0, ids = 0, colours = 0, outline = 0;
};
Sections sections(uint64_t nodes, uint64_t triangles);

// Throws InputError naming `where` unless the header is a sound one of a file of fileBytes.
void checkHeader(const Header& h, uint64_t fileBytes, const std::string& where);
// The nodes fit together: preorder subtrees nest, triangle ranges tile [0, triangles) in order.
void checkNodes(std::span<const TreeNode> nodes, uint64_t triangles, const std::string& where);

}  // namespace lzb::sampletree::format
