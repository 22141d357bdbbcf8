#pragma once
// The surfel collector (Tobor et al., section 4.1): a static hash table whose key and data split
// the bits of quantized surfels.
//
// A surfel is a position quantized on a Q^3 lattice over the object's bounding cube, an
// octahedral normal code (normal_quantizer.hpp) and a colour code. Two layouts, as in the paper:
//   low quality,  4 bytes: 24-bit position (Q = 256), 11-bit normal (4 levels), 9-bit colour
//                 (3 bits per channel); key 12 bits (4 bits of each coordinate: a 4096-entry
//                 table), data 32 bits.
//   high quality, 6 bytes: 30-bit position (Q = 1024), 15-bit normal (6 levels), 18-bit colour
//                 (6 bits per channel); key 15 bits (the 12 position bits and the normal's 3 sign
//                 bits: a 32768-entry table whose entries are whole normal octants, so the
//                 renderer skips back-facing octants per entry without reading a surfel), data
//                 48 bits.
// The key's position bits are 4 bits of each coordinate starting at the level's shift
// (log2(Q / grid), the lowest bits of the grid cell): bucket i holds the cells whose low 4 bits
// are a bit-reversed Morton permutation of i, so bucket 0 is one cell in 16 along each axis, the
// first 8 buckets one in 8, the first 64 one in 4: reading the table in order draws the object
// coarse to fine and spread over its whole surface (the paper's shuffling, which the time budget
// uses). "Dynamic sorted linked lists converted to static arrays" become one array sorted by
// (key, data, triangle) with a start index per key.
//
// Beside the table, a side table gives each entry's representative triangle (a node-local index,
// 1, 2 or 4 bytes by the node's triangle count): the triangle ID every pixel must carry.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace lzb::surfels {

enum class CollectorQuality { kLow, kHigh };

struct CollectorLayout {
  int positionBits;  // per axis (Q = 2^positionBits)
  int normalLevels;  // octahedral subdivision levels (normal code: 3 + 2 levels bits)
  int colourBits;    // per channel
  int keyBits;       // hash key bits
  int entryBytes;    // bytes per stored entry
  static CollectorLayout of(CollectorQuality q);
  int normalBits() const { return 3 + 2 * normalLevels; }
  int dataBits() const { return 3 * positionBits + normalBits() + 3 * colourBits - keyBits; }
  uint32_t lattice() const { return uint32_t(1) << positionBits; }
};

// A surfel unpacked.
struct Surfel {
  uint32_t x = 0, y = 0, z = 0;  // lattice position, each < 2^positionBits
  uint32_t normal = 0;           // octahedral code
  uint32_t colour = 0;           // r | g << b | b << 2b, b = colourBits
  friend bool operator==(const Surfel&, const Surfel&) = default;
};

// Colour codes: each channel's byte rounded to `bits` bits, and back (to the nearest byte).
uint32_t encodeColour(double r, double g, double b, int bits);
void decodeColour(uint32_t code, int bits, uint8_t rgb[3]);

// 4 bits of each coordinate <-> the 12 position bits of a key (bit-reversed Morton order).
uint32_t shuffleKey(uint32_t lx, uint32_t ly, uint32_t lz);
void unshuffleKey(uint32_t key12, uint32_t& lx, uint32_t& ly, uint32_t& lz);

class SurfelCollector {
 public:
  SurfelCollector() = default;
  // Packs `surfels` (triangles[i]: surfel i's representative triangle) into the table. shift:
  // the lowest coordinate bit the key takes (at most positionBits - 4).
  SurfelCollector(CollectorQuality quality, int shift, std::span<const Surfel> surfels,
                  std::span<const uint32_t> triangles);

  CollectorQuality quality() const { return quality_; }
  const CollectorLayout& layout() const { return layout_; }
  int shift() const { return shift_; }
  uint64_t size() const { return size_; }
  uint32_t keys() const { return uint32_t(1) << layout_.keyBits; }
  // Entries [start(k), start(k + 1)) have key k.
  uint32_t start(uint32_t key) const { return starts_[key]; }
  // Entry i unpacked (key: its key), and its representative triangle.
  Surfel surfel(uint32_t key, uint64_t i) const;
  uint32_t triangle(uint64_t i) const;
  // The key's contribution to the position (its bits already in place) and, high quality, the
  // normal octant it fixes.
  void keyPosition(uint32_t key, uint32_t& x, uint32_t& y, uint32_t& z) const;
  uint32_t keyOctant(uint32_t key) const { return quality_ == CollectorQuality::kHigh ? key & 7u : 0u; }
  // Raw storage, for the renderer's inner loop.
  uint64_t data(uint64_t i) const;
  const uint32_t* words32() const { return words32_.data(); }
  const std::array<uint16_t, 3>* words48() const { return words48_.data(); }
  const uint32_t* starts() const { return starts_.data(); }
  int triangleBytes() const { return triangleBytes_; }
  const uint8_t* triangleTable() const { return triangles_.data(); }

  // Memory: the table's entries, its key index, and the side table of triangles.
  uint64_t entryBytes() const { return size_ * uint64_t(layout_.entryBytes); }
  uint64_t indexBytes() const { return starts_.size() * sizeof(uint32_t); }
  uint64_t triangleTableBytes() const { return triangles_.size(); }
  uint64_t memoryBytes() const { return entryBytes() + indexBytes() + triangleTableBytes(); }

  // The key and data words of a surfel (static: tests check the split).
  static void pack(const CollectorLayout& layout, int shift, const Surfel& s, uint32_t& key,
                   uint64_t& data);
  static Surfel unpack(const CollectorLayout& layout, int shift, uint32_t key, uint64_t data);

 private:
  CollectorQuality quality_ = CollectorQuality::kLow;
  CollectorLayout layout_ = CollectorLayout::of(CollectorQuality::kLow);
  int shift_ = 0;
  uint64_t size_ = 0;
  std::vector<uint32_t> starts_;                  // keys() + 1
  std::vector<uint32_t> words32_;                 // low quality entries
  std::vector<std::array<uint16_t, 3>> words48_;  // high quality entries (6 bytes each)
  int triangleBytes_ = 4;
  std::vector<uint8_t> triangles_;  // size_ x triangleBytes_, little-endian
};

}  // namespace lzb::surfels
