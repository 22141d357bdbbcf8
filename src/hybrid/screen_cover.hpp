#pragma once
// The screen cover of a frame cast every pixel: the 4 x 4 pixel blocks under the projection of
// what the octrees hold (their leaves' triangle content boxes, down through the instances),
// so that castEveryPixel (raycast/exact/pixel_cast.hpp) casts no ray that would miss in a block
// where nothing projects. Every triangle point lies in a leaf box of its node's octree, and a
// box projects inside the rectangle of its corners' projections, so the cover is exact: a
// frame cast with it is the image cast without it. The walk stops at boxes of a few pixels.
#include <cstdint>
#include <optional>

#include "raycast/exact/pixel_cast.hpp"
#include "raycast/lzb/lzb_accel.hpp"
#include "src/core/camera.hpp"

namespace lzb::hybrid {

// The cover, or none: when a leaf's triangles may lie under every pixel (nothing for a cover to
// save), or once the walk has visited more than `budget` octree nodes and instances.
std::optional<BlockCover> screenCover(const localz::LzbAccel& accel, const Camera& camera,
                                      uint64_t budget);

}  // namespace lzb::hybrid
