#include "raycast/lzb/lzb_tile_cast.hpp"

#include <algorithm>
#include <cmath>

namespace lzb::localz {

namespace {

// Reach slack: a hit on a content box's deepest corner must not fall beyond the bound by the
// rounding of the depth estimate (relative 1e-16; the boxes are padded by 1e-7 of a diagonal).
constexpr double kReachSlack = 1e-9;

}  // namespace

namespace {

// scratch.mask (tile-local, row order): 1 where tile r casts a ray (an unfinished pixel, with OOR
// only inside a polygon binned to the tile); with `reach`, scratch.reach: the deepest depthMax
// of the polygons whose bounding boxes hold each pixel. False when the tile casts nothing.
bool markTileRays(const TileRect& r, int tileIndex, const TileCastInput& in, bool reach,
                  TileScratch& scratch, TileCastCounts& counts) {
  // A tile no far object projects onto casts nothing (the sky above a street view).
  if (in.oor && in.oor->tile(tileIndex).empty()) return false;
  const int width = in.camera->width();
  const int w = r.x1 - r.x0;
  std::vector<uint8_t>& mask = scratch.mask;
  if (mask.size() < size_t(r.pixels())) mask.resize(size_t(r.pixels()));
  uint64_t open = 0;
  for (int y = r.y0; y < r.y1; ++y) {
    const uint8_t* row = in.unfinished + size_t(y) * size_t(width) + size_t(r.x0);
    std::copy(row, row + w, mask.data() + size_t((y - r.y0) * w));
    uint32_t rowOpen = 0;  // 32-bit lanes: the loop vectorizes
    for (int x = 0; x < w; ++x) rowOpen += row[x];
    open += rowOpen;
  }
  if (open == 0 || !in.oor) return open > 0;
  std::vector<uint8_t>& inside = scratch.inside;
  inside.assign(size_t(r.pixels()), 0);
  if (reach) scratch.reach.assign(size_t(r.pixels()), 0.0);
  // Object by object: every bounding box holding a pixel raises its reach; the pixels inside
  // the polygon are marked (the boolean matrix of the paper), a row span at a time.
  for (uint32_t k : in.oor->tile(tileIndex)) {
    const ScreenPolygon& p = in.oor->polygon(k);
    const int xa = std::max(r.x0, int(std::ceil(double(p.x0) - 0.5)));
    const int xb = std::min(r.x1 - 1, int(std::floor(double(p.x1) - 0.5)));
    const int ya = std::max(r.y0, int(std::ceil(double(p.y0) - 0.5)));
    const int yb = std::min(r.y1 - 1, int(std::floor(double(p.y1) - 0.5)));
    for (int y = ya; y <= yb && xa <= xb; ++y) {
      const size_t row = size_t((y - r.y0) * w - r.x0);
      if (reach) {
        double* rowReach = scratch.reach.data() + row;
        for (int x = xa; x <= xb; ++x) rowReach[x] = std::max(rowReach[x], p.depthMax);
      }
      ++counts.polygonRows;
      int first, last;
      if (p.rowSpan(y, xa, xb, first, last))
        std::fill(inside.data() + row + first, inside.data() + row + last + 1, uint8_t(1));
    }
  }
  for (int i = 0; i < r.pixels(); ++i) mask[size_t(i)] &= inside[size_t(i)];
  return true;
}

}  // namespace

TileRays tileRaysToCast(const TileRect& r, int tileIndex, const TileCastInput& in,
                        TileScratch& scratch, TileCastCounts& counts) {
  TileRays rays;
  if (!markTileRays(r, tileIndex, in, true, scratch, counts)) return rays;
  const int width = in.camera->width(), w = r.x1 - r.x0;
  // Row order (tile-local index order): coherent neighbours for the rays.
  for (int i = 0; i < r.pixels(); ++i)
    if (scratch.mask[size_t(i)]) {
      const int x = r.x0 + i % w, y = r.y0 + i / w;
      rays.pixels.push_back(uint32_t(size_t(y) * size_t(width) + size_t(x)));
      rays.reach.push_back(
          in.oor ? std::min(in.tMax, scratch.reach[size_t(i)] * (1.0 + kReachSlack)) : in.tMax);
    }
  counts.cast += rays.pixels.size();
  return rays;
}

uint64_t countTileRays(const TileRect& r, int tileIndex, const TileCastInput& in,
                       TileScratch& scratch, TileCastCounts& counts) {
  if (!markTileRays(r, tileIndex, in, false, scratch, counts)) return 0;
  uint32_t n = 0;
  for (int i = 0; i < r.pixels(); ++i) n += scratch.mask[size_t(i)];
  return n;
}

void castTilePvl(RayWalker& walker, const TileRect& r, int tileIndex, const TileCastInput& in,
                 TileScratch& scratch, PvlPart& out, TileCastCounts& counts,
                 std::vector<uint32_t>* cast) {
  TileRays rays = tileRaysToCast(r, tileIndex, in, scratch, counts);
  walker.resetCoherence();
  const Camera& cam = *in.camera;
  const int w = cam.width();
  for (size_t k = 0; k < rays.pixels.size(); ++k) {
    const int x = int(rays.pixels[k] % uint32_t(w)), y = int(rays.pixels[k] / uint32_t(w));
    walker.cast(cam.position(), cam.pixelDirection(x + 0.5, y + 0.5), in.tMin, rays.reach[k], out);
  }
  if (cast) *cast = std::move(rays.pixels);
}

namespace {

// Embree's hits of the tile's rays, from the plane to each ray's reach, into scratch.hits.
void traceTileRays(const EmbreeScene& embree, const TileRays& rays, const TileCastInput& in,
                   TileScratch& scratch) {
  const Camera& cam = *in.camera;
  const uint32_t w = uint32_t(cam.width());
  const size_t n = rays.pixels.size();
  scratch.rays.resize(n);
  scratch.hits.resize(n);
  for (size_t k = 0; k < n; ++k) {
    const int x = int(rays.pixels[k] % w), y = int(rays.pixels[k] / w);
    scratch.rays[k] = {cam.position(), cam.pixelDirection(x + 0.5, y + 0.5), in.tMin,
                       rays.reach[k]};
  }
  embree.intersect(scratch.rays, scratch.hits);
}

}  // namespace

void castTileHits(const EmbreeScene& embree, HitLeafRecorder& recorder, const TileRect& r,
                  int tileIndex, const TileCastInput& in, TileScratch& scratch, PvlPart& out,
                  TileCastCounts& counts, std::vector<uint32_t>* cast) {
  TileRays rays = tileRaysToCast(r, tileIndex, in, scratch, counts);
  recorder.beginPart();
  traceTileRays(embree, rays, in, scratch);
  for (size_t k = 0; k < rays.pixels.size(); ++k)
    recorder.record(scratch.rays[k].origin, scratch.rays[k].dir, scratch.hits[k], out);
  if (cast) *cast = std::move(rays.pixels);
}

void castTileEmbree(const EmbreeScene& embree, const TileRect& r, int tileIndex,
                    const TileCastInput& in, TileScratch& scratch, Framebuffer& far,
                    TileCastCounts& counts, std::vector<uint32_t>* cast) {
  TileRays rays = tileRaysToCast(r, tileIndex, in, scratch, counts);
  traceTileRays(embree, rays, in, scratch);
  for (size_t k = 0; k < rays.pixels.size(); ++k) {
    const RayHit& h = scratch.hits[k];
    far.depth[rays.pixels[k]] = h.hit() ? h.t : kEmptyDepth;
    far.id[rays.pixels[k]] = h.id;
  }
  if (cast) *cast = std::move(rays.pixels);
}

}  // namespace lzb::localz
