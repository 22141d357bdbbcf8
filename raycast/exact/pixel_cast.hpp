#pragma once
// The exact ray caster's frame: one primary ray per pixel centre from the camera position,
// t in [near, far] (t is the view depth), the nearest hit's depth and expanded ID, for this
// rank's screen tiles (tile index mod ranks == rank) under the projection of what the Embree
// scene holds. --method raycast renders every frame so; the hybrid renders so a frame whose
// probe finds casting every pixel the cheapest way (src/hybrid/README.md).
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "mpi/decomposition.hpp"
#include "raycast/exact/embree_scene.hpp"
#include "src/core/camera.hpp"
#include "src/core/framebuffer.hpp"
#include "src/core/renderer.hpp"

namespace lzb {

// The pixels castEveryPixel casts on one rank: those of the tiles under the projection of what
// the Embree scene holds.
uint64_t castablePixels(const EmbreeScene& embree, const Camera& camera);

// A placement of boxes (a scene node's frame) seen by the camera: node frame -> camera space
// (x right, y up, z the view depth), worked out once for the many boxes of a node.
struct CameraPlacement {
  glm::dmat3 a{1.0};
  glm::dvec3 t{0.0};
  CameraPlacement(const Camera& camera, const glm::dmat4& toWorld);
};

// The pixels whose centre rays (t in [near, far], the view depth) can meet `box` placed by p:
// the rectangle of its corners' projections, a pixel wider on each side for rounding; the whole
// frame when a corner is not in front of the camera; none (x0 == x1 or y0 == y1) when the box
// is empty, beside the frame or wholly before the near plane or beyond the far one.
TileRect pixelsUnder(const Bounds& box, const CameraPlacement& p, const Camera& camera);

// The 4 x 4 pixel blocks where a frame's rays may meet something, known from more than the
// scene's box (the hybrid's cover of its octrees, src/hybrid/screen_cover.hpp): castEveryPixel
// casts no ray in another block, which would miss, so the image is the same.
class BlockCover {
 public:
  static constexpr int kSide = 4;  // a packet's block (traceTile)
  BlockCover(int width, int height);
  void add(const TileRect& pixels);  // every block meeting the rectangle
  bool covers(int x, int y) const {  // the block of pixel (x, y)
    return under_[size_t(y / kSide) * size_t(columns_) + size_t(x / kSide)] != 0;
  }
  bool anyIn(const TileRect& pixels) const;
  bool allIn(const TileRect& pixels) const;  // every block meeting the rectangle covered
  uint64_t blocks() const;                   // blocks covered

 private:
  // row(first, count) for the blocks of each row of r (not empty) until it returns false;
  // whether none did.
  template <class Row>
  bool eachRow(const TileRect& r, Row&& row) const;

  int columns_;
  std::vector<uint8_t> under_;
};

// Casts the pixels of share's tiles into fb (depth and ID; other pixels untouched) on `threads`
// threads, as 4 x 4 Embree packets when `packets`; returns the rays cast. `touched` gets 1 for
// each tile (ScreenTiles' grid) where a ray hit, 0 elsewhere (FrameStats::touchedTiles). With
// share.drawnDepth, a pixel's ray stops at the depth drawn there: a miss beyond it. With a
// cover, only its blocks are cast.
uint64_t castEveryPixel(const EmbreeScene& embree, const Camera& camera, const WorkShare& share,
                        Framebuffer& fb, std::vector<uint8_t>& touched, int threads,
                        bool packets = true, const BlockCover* cover = nullptr);

}  // namespace lzb
