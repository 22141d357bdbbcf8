#pragma once
// The exact ray caster's frame: one primary ray per pixel centre from the camera position,
// t in [near, far] (t is the view depth), the nearest hit's depth and expanded ID, for this
// rank's screen tiles (tile index mod ranks == rank) under the projection of what the Embree
// scene holds. --method raycast renders every frame so; the hybrid renders so a frame whose
// probe finds casting every pixel the cheapest way (src/hybrid/README.md).
#include <cstdint>
#include <vector>

#include "raycast/exact/embree_scene.hpp"
#include "src/core/camera.hpp"
#include "src/core/framebuffer.hpp"
#include "src/core/renderer.hpp"

namespace lzb {

// The pixels castEveryPixel casts on one rank: those of the tiles under the projection of what
// the Embree scene holds.
uint64_t castablePixels(const EmbreeScene& embree, const Camera& camera);

// Casts the pixels of share's tiles into fb (depth and ID; other pixels untouched) on `threads`
// threads, as 4 x 4 Embree packets when `packets`; returns the rays cast. `touched` gets 1 for
// each tile (ScreenTiles' grid) where a ray hit, 0 elsewhere (FrameStats::touchedTiles). With
// share.drawnDepth, a pixel's ray stops at the depth drawn there: a miss beyond it.
uint64_t castEveryPixel(const EmbreeScene& embree, const Camera& camera, const WorkShare& share,
                        Framebuffer& fb, std::vector<uint8_t>& touched, int threads,
                        bool packets = true);

}  // namespace lzb
