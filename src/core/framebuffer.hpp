#pragma once
// Per-pixel colour, depth (see camera.hpp for the convention) and expanded triangle ID.
// Row 0 is the top row of the image.
#include <cstdint>
#include <limits>
#include <vector>

#include "src/core/color.hpp"
#include "src/core/depth_key.hpp"
#include "src/core/scene.hpp"

namespace lzb {

constexpr float kEmptyDepth = std::numeric_limits<float>::infinity();
constexpr Rgba8 kBackground = packRgba8(0, 0, 0, 0);

// A pixel is empty exactly when its ID is kNoId and its depth kEmptyDepth: writers set the two
// together (compositing finds the touched pixels by depth alone, mpi/composite.cpp).
struct Framebuffer {
  int width = 0, height = 0;
  std::vector<float> depth;
  std::vector<Rgba8> color;
  std::vector<uint64_t> id;
  // Kept by the frame driver alone (mpi/frame_driver.hpp): after its frame, 1 for each tile of
  // ScreenTiles' default grid that may hold a pixel other than the empty one (kEmptyDepth, kNoId,
  // kBackground), so that its next frame clears only those. Empty: not known, every tile may
  // (resize and clear empty it; whoever else writes a frame the driver rendered must too).
  std::vector<uint8_t> tilesInUse;

  Framebuffer() = default;
  Framebuffer(int w, int h) { resize(w, h); }
  void resize(int w, int h);
  // Resizes (and clears) only when the size differs; for a frame whose every depth and ID the
  // caller writes (KeyBuffer::resolve), the colour staying as it was.
  void resizeUnlessSized(int w, int h) {
    if (w != width || h != height) resize(w, h);
  }
  void clear();
  size_t size() const { return size_t(width) * size_t(height); }
  size_t index(int x, int y) const { return size_t(y) * size_t(width) + size_t(x); }
  bool covered(size_t i) const { return id[i] != kNoId; }
  size_t coveredCount() const;
  // Keeps the nearer sample by the compositing key's rule (depth_key.hpp).
  void keepNearer(size_t i, float d, Rgba8 c, uint64_t triangle) {
    if (nearer(d, triangle, depth[i], id[i])) {
      depth[i] = d;
      color[i] = c;
      id[i] = triangle;
    }
  }
};

// Per-pixel minimum of (depth, id) of `other` into `into`: commutative and associative, the one
// compositing rule for threads, passes and ranks.
void compositeNearer(Framebuffer& into, const Framebuffer& other);

}  // namespace lzb
