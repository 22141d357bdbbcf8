#include "src/surfels/collector.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <tuple>

namespace lzb::surfels {

CollectorLayout CollectorLayout::of(CollectorQuality q) {
  if (q == CollectorQuality::kLow) return {8, 4, 3, 12, 4};
  return {10, 6, 6, 15, 6};
}

uint32_t encodeColour(double r, double g, double b, int bits) {
  const double top = double((1 << bits) - 1);
  const double rgb[3] = {r, g, b};
  uint32_t code = 0;
  for (int k = 0; k < 3; ++k)
    code |= uint32_t(std::lround(std::clamp(rgb[k], 0.0, 255.0) / 255.0 * top)) << (bits * k);
  return code;
}

void decodeColour(uint32_t code, int bits, uint8_t rgb[3]) {
  const uint32_t top = (1u << bits) - 1;
  for (int k = 0; k < 3; ++k)
    rgb[k] = uint8_t(std::lround(double(code >> (bits * k) & top) * 255.0 / double(top)));
}

uint32_t shuffleKey(uint32_t lx, uint32_t ly, uint32_t lz) {
  uint32_t key = 0;
  for (int j = 0; j < 4; ++j) {
    key |= (lx >> j & 1) << (11 - 3 * j);
    key |= (ly >> j & 1) << (10 - 3 * j);
    key |= (lz >> j & 1) << (9 - 3 * j);
  }
  return key;
}

void unshuffleKey(uint32_t key12, uint32_t& lx, uint32_t& ly, uint32_t& lz) {
  lx = ly = lz = 0;
  for (int j = 0; j < 4; ++j) {
    lx |= (key12 >> (11 - 3 * j) & 1) << j;
    ly |= (key12 >> (10 - 3 * j) & 1) << j;
    lz |= (key12 >> (9 - 3 * j) & 1) << j;
  }
}

namespace {

// A coordinate's bits outside the key's 4 (b - 4 bits), and back.
uint32_t restBits(uint32_t c, int shift) {
  return (c & ((1u << shift) - 1)) | (c >> (shift + 4)) << shift;
}
uint32_t keyBits4(uint32_t c, int shift) {
  return c >> shift & 15u;
}
uint32_t join(uint32_t rest, uint32_t key4, int shift) {
  return (rest & ((1u << shift) - 1)) | key4 << shift | (rest >> shift) << (shift + 4);
}

}  // namespace

void SurfelCollector::pack(const CollectorLayout& l, int shift, const Surfel& s, uint32_t& key,
                           uint64_t& data) {
  const int rb = l.positionBits - 4;
  const uint32_t pos = shuffleKey(keyBits4(s.x, shift), keyBits4(s.y, shift), keyBits4(s.z, shift));
  const bool high = l.keyBits == 15;
  const uint32_t octant = s.normal >> (2 * l.normalLevels);
  key = high ? pos << 3 | octant : pos;
  const uint64_t normal = high ? s.normal & ((1u << 2 * l.normalLevels) - 1) : s.normal;
  const int normalBits = high ? 2 * l.normalLevels : l.normalBits();
  data = uint64_t(restBits(s.x, shift)) | uint64_t(restBits(s.y, shift)) << rb |
         uint64_t(restBits(s.z, shift)) << 2 * rb | normal << 3 * rb |
         uint64_t(s.colour) << (3 * rb + normalBits);
}

Surfel SurfelCollector::unpack(const CollectorLayout& l, int shift, uint32_t key, uint64_t data) {
  const int rb = l.positionBits - 4;
  const bool high = l.keyBits == 15;
  const int normalBits = high ? 2 * l.normalLevels : l.normalBits();
  const uint64_t rmask = (uint64_t(1) << rb) - 1;
  uint32_t kx, ky, kz;
  unshuffleKey(high ? key >> 3 : key, kx, ky, kz);
  Surfel s;
  s.x = join(uint32_t(data & rmask), kx, shift);
  s.y = join(uint32_t(data >> rb & rmask), ky, shift);
  s.z = join(uint32_t(data >> 2 * rb & rmask), kz, shift);
  s.normal = uint32_t(data >> 3 * rb & ((uint64_t(1) << normalBits) - 1));
  if (high) s.normal |= (key & 7u) << (2 * l.normalLevels);
  s.colour = uint32_t(data >> (3 * rb + normalBits) & ((uint64_t(1) << 3 * l.colourBits) - 1));
  return s;
}

SurfelCollector::SurfelCollector(CollectorQuality quality, int shift, std::span<const Surfel> surfels,
                                 std::span<const uint32_t> triangles)
    : quality_(quality),
      layout_(CollectorLayout::of(quality)),
      shift_(shift),
      size_(surfels.size()) {
  if (shift < 0 || shift > layout_.positionBits - 4)
    throw std::invalid_argument("SurfelCollector: shift out of range");
  if (triangles.size() != surfels.size())
    throw std::invalid_argument("SurfelCollector: one triangle per surfel");
  if (size_ >= (uint64_t(1) << 32))
    throw std::invalid_argument("SurfelCollector: too many surfels");
  std::vector<std::tuple<uint32_t, uint64_t, uint32_t>> packed(size_);
  for (size_t i = 0; i < size_; ++i) {
    uint32_t key;
    uint64_t data;
    pack(layout_, shift, surfels[i], key, data);
    packed[i] = {key, data, triangles[i]};
  }
  std::sort(packed.begin(), packed.end());  // by key, data, triangle: the table's one order
  starts_.assign(keys() + 1, 0);
  for (const auto& p : packed) ++starts_[std::get<0>(p) + 1];
  std::partial_sum(starts_.begin(), starts_.end(), starts_.begin());
  const uint32_t maxTriangle =
      triangles.empty() ? 0 : *std::max_element(triangles.begin(), triangles.end());
  triangleBytes_ = maxTriangle < 256 ? 1 : maxTriangle < 65536 ? 2 : 4;
  triangles_.resize(size_ * uint64_t(triangleBytes_));
  if (quality == CollectorQuality::kLow)
    words32_.resize(size_);
  else
    words48_.resize(size_);
  for (size_t i = 0; i < size_; ++i) {
    const auto& [key, data, tri] = packed[i];
    if (quality == CollectorQuality::kLow)
      words32_[i] = uint32_t(data);
    else
      words48_[i] = {uint16_t(data), uint16_t(data >> 16), uint16_t(data >> 32)};
    for (int b = 0; b < triangleBytes_; ++b)
      triangles_[i * size_t(triangleBytes_) + size_t(b)] = uint8_t(tri >> 8 * b);
  }
}

uint64_t SurfelCollector::data(uint64_t i) const {
  if (quality_ == CollectorQuality::kLow) return words32_[i];
  const auto& w = words48_[i];
  return uint64_t(w[0]) | uint64_t(w[1]) << 16 | uint64_t(w[2]) << 32;
}

Surfel SurfelCollector::surfel(uint32_t key, uint64_t i) const {
  return unpack(layout_, shift_, key, data(i));
}

uint32_t SurfelCollector::triangle(uint64_t i) const {
  uint32_t t = 0;
  for (int b = 0; b < triangleBytes_; ++b)
    t |= uint32_t(triangles_[i * uint64_t(triangleBytes_) + uint64_t(b)]) << 8 * b;
  return t;
}

void SurfelCollector::keyPosition(uint32_t key, uint32_t& x, uint32_t& y, uint32_t& z) const {
  unshuffleKey(quality_ == CollectorQuality::kHigh ? key >> 3 : key, x, y, z);
  x <<= shift_;
  y <<= shift_;
  z <<= shift_;
}

}  // namespace lzb::surfels
