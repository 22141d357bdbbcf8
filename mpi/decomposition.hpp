#pragma once
// How a frame's work is dealt to ranks: every rule in one place, free of MPI so that it is unit
// tested without ranks. Each rule deals in an order that does not depend on the number of ranks,
// so the composited image never does either; only who does the work changes.
//  - ID ranges (sort-last z-buffer): [0, total) cut into equal contiguous ranges in rank order.
//  - Screen tiles (ray casting): square tiles in row-major order, dealt interleaved
//    (tile % ranks == rank), so neighbouring tiles land on different ranks and cost evens out,
//    or by cost (contiguous runs of about equal estimated cost: the rays each tile will cast,
//    which every rank knows alike).
//  - Items by cost (octree boxes of the point pass): contiguous runs of about equal estimated
//    cost, in the items' own order.
// The scene's regions under --distribute data are cut and dealt in src/regions (region_cut.hpp).
#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "src/core/renderer.hpp"

namespace lzb {

// ---- ID ranges

struct IdRange {
  uint64_t begin = 0, end = 0;  // [begin, end)
  bool overlaps(uint64_t b, uint64_t e) const { return b < end && begin < e; }
  bool contains(uint64_t b, uint64_t e) const { return begin <= b && e <= end; }
};

// Splits [0, total) into share.size ranges whose lengths differ by at most one, in rank order.
IdRange shareRange(uint64_t total, const WorkShare& share);
// The rank of `size` whose shareRange of [0, total) holds `item` (< total).
int shareRankOf(uint64_t item, uint64_t total, int size);

// ---- Screen tiles

struct TileRect {
  int x0, y0, x1, y1;  // pixels [x0, x1) x [y0, y1)
  int pixels() const { return (x1 - x0) * (y1 - y0); }
};

// How screen tiles are dealt to ranks (--tile-deal).
enum class TileDeal { kInterleaved, kCost };
// Throws InputError naming `field` on an unknown name.
TileDeal parseTileDeal(const std::string& text, const std::string& field);
std::string toString(TileDeal deal);
// How the deal reads in a renderer's decomposition() text.
std::string tileDealText(TileDeal deal);

class ScreenTiles {
 public:
  static constexpr int kDefaultSide = 16;

  ScreenTiles(int width, int height, int side = kDefaultSide)
      : width_(width), height_(height), side_(side) {}

  int side() const { return side_; }
  int columns() const { return (width_ + side_ - 1) / side_; }
  int rows() const { return (height_ + side_ - 1) / side_; }
  int count() const { return columns() * rows(); }
  TileRect tile(int index) const {
    const int x0 = index % columns() * side_, y0 = index / columns() * side_;
    return {x0, y0, std::min(x0 + side_, width_), std::min(y0 + side_, height_)};
  }
  // The tiles rank share.rank renders, in increasing order.
  std::vector<int> owned(const WorkShare& share) const;
  // The tiles rank share.rank renders when tile t costs costs[t] (count() entries): a
  // contiguous run of about equal cost (dealByCost below), in increasing order.
  std::vector<int> ownedByCost(std::span<const double> costs, const WorkShare& share) const;

 private:
  int width_, height_, side_;
};

// ---- Items by cost

// Indices of the items rank share.rank takes: item i goes to the rank whose equal share of the
// total cost holds the midpoint of i's cost interval, so every rank gets a contiguous run of
// about equal cost (all items to rank 0 when the total is 0).
std::vector<uint32_t> dealByCost(std::span<const double> costs, const WorkShare& share);

}  // namespace lzb
