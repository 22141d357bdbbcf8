#include "mpi/frame_tiles.hpp"

#include <algorithm>
#include <bit>

namespace lzb {

namespace {

const uint32_t kEmptyBits = std::bit_cast<uint32_t>(kEmptyDepth);

}  // namespace

std::vector<int> markedTiles(const std::vector<uint8_t>& marked) {
  std::vector<int> list;
  for (size_t t = 0; t < marked.size(); ++t)
    if (marked[t]) list.push_back(int(t));
  return list;
}

// Row by row over the whole frame, each tile's span OR-ed without an early exit (it vectorizes; a
// per-pixel test with an exit took milliseconds on a mostly empty 1080p frame), the spans stepped
// by the tile side (a tile(index) call per span, two divisions, took longer than reading the
// pixels).
std::vector<uint8_t> touchedTiles(const Framebuffer& fb, const ScreenTiles& tiles) {
  std::vector<uint8_t> touched(size_t(tiles.count()), 0);
  const int cols = tiles.columns(), side = tiles.side();
  const uint32_t* bits = reinterpret_cast<const uint32_t*>(fb.depth.data());
#pragma omp parallel for schedule(static)
  for (int ty = 0; ty < tiles.rows(); ++ty) {
    uint8_t* band = touched.data() + size_t(ty) * size_t(cols);
    const int y1 = std::min((ty + 1) * side, fb.height);
    for (int y = ty * side; y < y1; ++y) {
      const uint32_t* row = bits + size_t(y) * size_t(fb.width);
      for (int tx = 0; tx < cols; ++tx) {
        const int x0 = tx * side, x1 = std::min(x0 + side, fb.width);
        uint32_t any = 0;
        for (int x = x0; x < x1; ++x) any |= row[x] ^ kEmptyBits;
        band[tx] |= uint8_t(any != 0);
      }
    }
  }
  return touched;
}

std::vector<uint8_t> takeTouchedTiles(const Framebuffer& fb, const ScreenTiles& tiles,
                                      FrameStats& stats) {
  if (stats.touchedTiles.size() == size_t(tiles.count())) return std::move(stats.touchedTiles);
  return touchedTiles(fb, tiles);
}

std::vector<uint32_t> tilePixels(const Framebuffer& fb, const ScreenTiles& tiles,
                                 const std::vector<uint8_t>& marked) {
  const std::vector<int> list = markedTiles(marked);
  std::vector<size_t> at(list.size() + 1, 0);
  for (size_t k = 0; k < list.size(); ++k) at[k + 1] = at[k] + size_t(tiles.tile(list[k]).pixels());
  std::vector<uint32_t> pixels(at.back());
#pragma omp parallel for schedule(static)
  for (size_t k = 0; k < list.size(); ++k) {
    const TileRect r = tiles.tile(list[k]);
    uint32_t* out = pixels.data() + at[k];
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x) *out++ = uint32_t(fb.index(x, y));
  }
  return pixels;
}

void clearTiles(Framebuffer& fb, const ScreenTiles& tiles, const std::vector<uint8_t>& marked) {
  const std::vector<int> list = markedTiles(marked);
#pragma omp parallel for schedule(static)
  for (size_t k = 0; k < list.size(); ++k) {
    const TileRect r = tiles.tile(list[k]);
    for (int y = r.y0; y < r.y1; ++y) {
      const size_t i = fb.index(r.x0, y), n = size_t(r.x1 - r.x0);
      std::fill_n(fb.depth.begin() + ptrdiff_t(i), n, kEmptyDepth);
      std::fill_n(fb.color.begin() + ptrdiff_t(i), n, kBackground);
      std::fill_n(fb.id.begin() + ptrdiff_t(i), n, kNoId);
    }
  }
}

}  // namespace lzb
