#pragma once
// CRC-32C (Castagnoli), the checksum of the tree store's blocks: detects every burst of up to 32
// flipped bits and any odd number of them.
#include <cstddef>
#include <cstdint>

namespace lzb::sampletree {

// The CRC of bytes [data, data + n) continuing from `crc` (0 to start).
// The CPU's crc32 instruction where it has one (SSE 4.2), else crc32cPortable.
uint32_t crc32c(const void* data, size_t n, uint32_t crc = 0);
// The same CRC from a table, a byte a step.
uint32_t crc32cPortable(const void* data, size_t n, uint32_t crc = 0);

}  // namespace lzb::sampletree
