#pragma once
// The paper's "rendering bit": one bit per triangle of a node mesh, set when the triangle is
// recorded, so a triangle listed by many octree leaves (or reached by many rays) is drawn once.
// One set serves one (node, instance path) at a time; take() lists the triangles in ascending
// order (the z-buffer's tie rule wants ascending IDs) and clears only the words it used.
#include <bit>
#include <cstdint>
#include <vector>

namespace lzb::localz {

class TriangleSet {
 public:
  // Starts a set over triangles [0, n); the previous set must have been taken.
  void reset(size_t n) {
    if (bits_.size() < (n + 63) / 64) bits_.resize((n + 63) / 64, 0);
    lo_ = bits_.size();
    hi_ = 0;
    count_ = 0;
  }
  // Sets the bit; returns true when it was not set (a first recording).
  bool add(uint32_t t) {
    const size_t w = t >> 6;
    const uint64_t mask = uint64_t(1) << (t & 63);
    if (bits_[w] & mask) return false;
    bits_[w] |= mask;
    if (w < lo_) lo_ = w;
    if (w + 1 > hi_) hi_ = w + 1;
    ++count_;
    return true;
  }
  size_t count() const { return count_; }
  // Appends the set triangles in ascending order to out and clears the set.
  void take(std::vector<uint32_t>& out) {
    for (size_t w = lo_; w < hi_; ++w) {
      uint64_t word = bits_[w];
      bits_[w] = 0;
      while (word) {
        out.push_back(uint32_t(w * 64 + size_t(std::countr_zero(word))));
        word &= word - 1;
      }
    }
    clear();
  }
  // Clears without listing.
  void clear() {
    for (size_t w = lo_; w < hi_; ++w) bits_[w] = 0;
    lo_ = bits_.size();
    hi_ = 0;
    count_ = 0;
  }

 private:
  std::vector<uint64_t> bits_;
  size_t lo_ = 0, hi_ = 0, count_ = 0;
};

}  // namespace lzb::localz
