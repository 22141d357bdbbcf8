#pragma once
// LZB step 5 for one screen tile, self-contained so tiles can be dealt to threads and ranks:
// input = the tile's unfinished pixels (empty after the near pass) and, with OOR, the polygons
// binned to the tile; output = the tile's PVL part (or, naive, its ray-cast pixels) and counts.
// The result depends only on the tile, never on the thread that ran it or the tiles before.
#include <cstdint>
#include <vector>

#include "raycast/exact/embree_scene.hpp"
#include "raycast/lzb/lzb_hit_leaves.hpp"
#include "raycast/lzb/lzb_oor.hpp"
#include "raycast/lzb/lzb_ray_walk.hpp"
#include "mpi/decomposition.hpp"
#include "src/core/camera.hpp"
#include "src/core/framebuffer.hpp"

namespace lzb::localz {

struct TileCastCounts {
  uint64_t cast = 0;          // rays cast (unfinished pixels, inside some polygon with OOR)
  uint64_t polygonRows = 0;   // OOR: rows of polygons intersected with the tile's pixel rows
  void add(const TileCastCounts& o) {
    cast += o.cast;
    polygonRows += o.polygonRows;
  }
};

struct TileCastInput {
  const Camera* camera;
  const uint8_t* unfinished;  // per pixel (Framebuffer::index order): 1 unfinished, else 0
  double tMin, tMax;          // ray interval (view depth): the partition plane to far
  const OorObjects* oor;      // null: cast every unfinished pixel
};

// What a tile casts: pixels (framebuffer indices, row order) and each ray's far end.
struct TileRays {
  std::vector<uint32_t> pixels;
  // View depth a ray needs to reach: with OOR the deepest depthMax of the polygons whose
  // bounding boxes hold the pixel (slightly widened), else the input's tMax.
  std::vector<double> reach;
};

// Per-thread buffers of tileRaysToCast and the Embree casts, reused from tile to tile.
struct TileScratch {
  std::vector<uint8_t> mask;
  std::vector<double> reach;
  std::vector<uint8_t> inside;   // OOR: 1 where a polygon holds the pixel centre
  std::vector<Ray> rays;
  std::vector<RayHit> hits;
};

// The rays of tile r: its unfinished pixels and, with OOR, only those inside a polygon binned
// to the tile.
TileRays tileRaysToCast(const TileRect& r, int tileIndex, const TileCastInput& in,
                        TileScratch& scratch, TileCastCounts& counts);
// How many rays tileRaysToCast would cast (the cost that --tile-deal cost deals by).
uint64_t countTileRays(const TileRect& r, int tileIndex, const TileCastInput& in,
                       TileScratch& scratch, TileCastCounts& counts);

// PVL finding for one tile with the walker (its coherence state is reset first). The pixels
// cast go to *cast when given.
void castTilePvl(RayWalker& walker, const TileRect& r, int tileIndex, const TileCastInput& in,
                 TileScratch& scratch, PvlPart& out, TileCastCounts& counts,
                 std::vector<uint32_t>* cast = nullptr);

// PVL finding for one tile with Embree: each ray's hit recorded as the leaves around it
// (lzb_hit_leaves.hpp). The pixels cast go to *cast when given.
void castTileHits(const EmbreeScene& embree, HitLeafRecorder& recorder, const TileRect& r,
                  int tileIndex, const TileCastInput& in, TileScratch& scratch, PvlPart& out,
                  TileCastCounts& counts, std::vector<uint32_t>* cast = nullptr);

// Naive LZB: classic ray casting (Embree packets) of the tile's unfinished pixels; hits go to
// far (depth, id) at their pixels.
void castTileEmbree(const EmbreeScene& embree, const TileRect& r, int tileIndex,
                    const TileCastInput& in, TileScratch& scratch, Framebuffer& far,
                    TileCastCounts& counts, std::vector<uint32_t>* cast = nullptr);

}  // namespace lzb::localz
