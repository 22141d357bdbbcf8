#pragma once
// Depth compositing across ranks at the root: the per-pixel minimum of the compositing key of
// src/core/depth_key.hpp, which is commutative and associative, so the result depends neither on
// the number of ranks nor on the order of the reduction.
//
// Ranks send keys only (8 bytes a pixel, 16 above 2^32 expanded triangles): colour is shaded at
// the root from the composited IDs (the frame driver does it), except with `tiles`, where each
// rank shades its touched tiles first and sends them with their colour (compositeWithColour). Every
// strategy sends only the region that carries information, the way IceT skips empty pixels:
//   reduce  MPI_Reduce with the key minimum over the union of the ranks' touched rectangles;
//   bswap   binary swap over that union (halves exchanged pairwise, log2 P rounds; ranks past the
//           largest power of two fold into it first), then the owned stripes gathered;
//   direct  direct send: each rank sends its touched rectangle's part of every stripe of the
//           union to the stripe's owner, which reduces it; then the stripes are gathered;
//   tiles   each rank sends its touched 16 x 16 tiles straight to the root in chunks, which it
//           reduces as they come (cheapest where ranks own disjoint tiles).
// Renderers whose colour is not a function of the IDs (rzb's Gaussian reconstruction, the regions
// of --distribute data) composite whole 16-byte pixels with compositeWithColour, equal (depth, ID)
// keeping the lower rank's: by touched tiles with `tiles`, else by MPI_Reduce of the frame.
#include <cstdint>
#include <string>
#include <vector>

#include "mpi/decomposition.hpp"
#include "mpi/group.hpp"
#include "src/core/framebuffer.hpp"

namespace lzb::mpi {

enum class CompositeStrategy { kReduce, kBinarySwap, kDirect, kTiles };

// "reduce" | "bswap" | "direct" | "tiles"; throws InputError naming `field` otherwise.
CompositeStrategy parseCompositeStrategy(const std::string& text, const std::string& field);
std::string toString(CompositeStrategy s);

struct CompositeStats {
  double seconds = 0.0;
  double bytesSent = 0.0;  // by this rank
};

// After the call, the root's fb holds the composite's depth and ID (colour untouched); other
// ranks' fb is unspecified. wide: 128-bit keys (IDs of 2^32 and above).
CompositeStats compositeAtRoot(const Group& g, Framebuffer& fb, CompositeStrategy strategy,
                               bool wide);

// The same with colour carried along: with kTiles each rank's touched tiles (`touched`,
// ScreenTiles' grid, mpi/frame_tiles.hpp) to the root as 12-byte pixels (16 when wide: IDs of
// 2^32 - 1 and above), merged in rank order, the root adding the tiles it received to its
// `touched`; with the other strategies MPI_Reduce of 16-byte pixels over the whole frame
// (`touched` unused).
CompositeStats compositeWithColour(const Group& g, Framebuffer& fb, CompositeStrategy strategy,
                                   std::vector<uint8_t>& touched, bool wide);

}  // namespace lzb::mpi
