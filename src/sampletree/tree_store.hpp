#pragma once
// The tree store: one file holding a sample tree, written atomically (src/core/atomic_file.hpp).
//
//   header     128 bytes: magic "LZBSTREE", format version, block size, counts, construction
//              parameters, the root cube, payload size, the block table's CRC, the header's CRC
//   payload    the nodes in preorder (88 bytes each, so a subtree and neighbouring cells lie
//              together), then the triangles in node order: positions (36 bytes), IDs (8),
//              colours (4), then the scene outline as JSON text (src/core/scene_outline.hpp:
//              what a render needs of the scene, which is then not loaded)
//   block table  CRC-32C of each kStoreBlock bytes of the payload
//
// Little-endian. readTree checks everything before it returns: a truncated file, a wrong magic
// or version, any corrupted block or header, or nodes that do not fit together give an InputError
// naming the store and what is wrong.
#include <cstdint>
#include <string>

#include "src/sampletree/sample_tree.hpp"

namespace lzb::sampletree {

constexpr uint32_t kStoreVersion = 2;
constexpr uint32_t kStoreBlock = 64 * 1024;
constexpr uint64_t kStoreHeaderBytes = 128;

void writeTree(const SampleTree& tree, const std::string& path);
SampleTree readTree(const std::string& path);

// Bytes of the file writeTree makes for `tree`.
uint64_t storeBytes(const SampleTree& tree);

}  // namespace lzb::sampletree
