#pragma once
// Square screen tiles in row-major order, dealt to ranks interleaved (tile % size == rank): the
// unit of work of every ray-casting pass, so neighbouring tiles land on different ranks and
// cost evens out without a cost model.
#include <algorithm>
#include <vector>

#include "src/core/renderer.hpp"

namespace lzb {

struct TileRect {
  int x0, y0, x1, y1;  // pixels [x0, x1) x [y0, y1)
  int pixels() const { return (x1 - x0) * (y1 - y0); }
};

class ScreenTiles {
 public:
  static constexpr int kDefaultSide = 16;

  ScreenTiles(int width, int height, int side = kDefaultSide)
      : width_(width), height_(height), side_(side) {}

  int columns() const { return (width_ + side_ - 1) / side_; }
  int rows() const { return (height_ + side_ - 1) / side_; }
  int count() const { return columns() * rows(); }
  TileRect tile(int index) const {
    const int x0 = index % columns() * side_, y0 = index / columns() * side_;
    return {x0, y0, std::min(x0 + side_, width_), std::min(y0 + side_, height_)};
  }
  // The tiles rank share.rank renders, in increasing order.
  std::vector<int> owned(const WorkShare& share) const {
    std::vector<int> out;
    for (int t = share.rank; t < count(); t += share.size) out.push_back(t);
    return out;
  }

 private:
  int width_, height_, side_;
};

}  // namespace lzb
