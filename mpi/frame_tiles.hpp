#pragma once
// The tiles a frame touched (ScreenTiles' grid, one byte a tile, 1 where some pixel is covered):
// found from the depths, or recorded by the renderer that wrote them; and what the frame driver
// does with them so that a sparse frame costs what it covers, not its size: shading, sending and
// clearing those tiles alone.
#include <cstdint>
#include <vector>

#include "mpi/decomposition.hpp"
#include "src/core/framebuffer.hpp"
#include "src/core/renderer.hpp"

namespace lzb {

// 1 per tile where fb covers some pixel (a pixel is covered exactly when its depth is not
// kEmptyDepth, framebuffer.hpp).
std::vector<uint8_t> touchedTiles(const Framebuffer& fb, const ScreenTiles& tiles);

// The tiles a renderer covered in fb: its record (stats.touchedTiles, taken) when it kept one,
// else touchedTiles(fb, tiles).
std::vector<uint8_t> takeTouchedTiles(const Framebuffer& fb, const ScreenTiles& tiles,
                                      FrameStats& stats);

// The marked tiles' indices, in order.
std::vector<int> markedTiles(const std::vector<uint8_t>& marked);

// The pixel indices of the marked tiles, tile by tile in tile order, row by row within a tile.
std::vector<uint32_t> tilePixels(const Framebuffer& fb, const ScreenTiles& tiles,
                                 const std::vector<uint8_t>& marked);

// Empties every pixel of the marked tiles (kEmptyDepth, kNoId, kBackground).
void clearTiles(Framebuffer& fb, const ScreenTiles& tiles, const std::vector<uint8_t>& marked);

}  // namespace lzb
