#include "raycast/lzb_tile_cast.hpp"

#include <algorithm>
#include <cmath>

namespace lzb {

namespace {

// Reach slack: a hit on a content box's deepest corner must not fall beyond the bound by the
// rounding of the depth estimate (relative 1e-16; the boxes are padded by 1e-7 of a diagonal).
constexpr double kReachSlack = 1e-9;

}  // namespace

TileRays tileRaysToCast(const TileRect& r, int tileIndex, const TileCastInput& in,
                        TileScratch& scratch, TileCastCounts& counts) {
  const int width = in.camera->width();
  const int w = r.x1 - r.x0;
  std::vector<uint8_t>& mask = scratch.mask;
  if (mask.size() < size_t(r.pixels())) mask.resize(size_t(r.pixels()));
  // mask: 0 finished, 1 unfinished and not cast yet, 2 to cast.
  uint64_t open = 0;
  for (int y = r.y0; y < r.y1; ++y) {
    const uint8_t* row = in.unfinished + size_t(y) * size_t(width) + size_t(r.x0);
    std::copy(row, row + w, mask.data() + size_t((y - r.y0) * w));
    uint32_t rowOpen = 0;  // 32-bit lanes: the loop vectorizes
    for (int x = 0; x < w; ++x) rowOpen += row[x];
    open += rowOpen;
  }
  counts.unfinished += open;
  TileRays rays;
  if (open == 0) return rays;
  std::vector<double>& reach = scratch.reach;
  std::vector<uint32_t>& marked = scratch.marked;
  if (in.oor) {
    marked.clear();
    reach.assign(size_t(r.pixels()), 0.0);
    // Object by object: unfinished pixels inside the polygon's bounding box, then inside the
    // polygon, are marked once (the boolean matrix of the paper). Every bounding box holding a
    // pixel raises its reach, marked or not.
    for (uint32_t k : in.oor->tile(tileIndex)) {
      const ScreenPolygon& p = in.oor->polygon(k);
      const int xa = std::max(r.x0, int(std::ceil(double(p.x0) - 0.5)));
      const int xb = std::min(r.x1 - 1, int(std::floor(double(p.x1) - 0.5)));
      const int ya = std::max(r.y0, int(std::ceil(double(p.y0) - 0.5)));
      const int yb = std::min(r.y1 - 1, int(std::floor(double(p.y1) - 0.5)));
      for (int y = ya; y <= yb; ++y)
        for (int x = xa; x <= xb; ++x) {
          const size_t i = size_t((y - r.y0) * w + (x - r.x0));
          uint8_t& m = mask[i];
          if (m == 0) continue;
          reach[i] = std::max(reach[i], p.depthMax);
          if (m != 1) continue;
          ++counts.polygonTests;
          if (p.contains(x + 0.5, y + 0.5)) {
            m = 2;
            marked.push_back(uint32_t(i));
          }
        }
    }
    // Row order (tile-local index order), as without OOR: coherent neighbours for the walk.
    std::sort(marked.begin(), marked.end());
    for (uint32_t i : marked) {
      const int x = r.x0 + int(i % uint32_t(w)), y = r.y0 + int(i / uint32_t(w));
      rays.pixels.push_back(uint32_t(size_t(y) * size_t(width) + size_t(x)));
      rays.reach.push_back(std::min(in.tMax, reach[i] * (1.0 + kReachSlack)));
    }
  } else {
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x)
        if (mask[size_t((y - r.y0) * w + (x - r.x0))] == 1) {
          rays.pixels.push_back(uint32_t(size_t(y) * size_t(width) + size_t(x)));
          rays.reach.push_back(in.tMax);
        }
  }
  counts.cast += rays.pixels.size();
  return rays;
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

void castTileEmbree(const EmbreeScene& embree, const TileRect& r, int tileIndex,
                    const TileCastInput& in, TileScratch& scratch, Framebuffer& far,
                    TileCastCounts& counts, std::vector<uint32_t>* cast) {
  TileRays rays = tileRaysToCast(r, tileIndex, in, scratch, counts);
  const std::vector<uint32_t>& pixels = rays.pixels;
  if (!pixels.empty()) {
    const Camera& cam = *in.camera;
    const int w = cam.width();
    std::vector<Ray> batch(pixels.size());
    std::vector<RayHit> hits(pixels.size());
    for (size_t k = 0; k < pixels.size(); ++k) {
      const int x = int(pixels[k] % uint32_t(w)), y = int(pixels[k] / uint32_t(w));
      batch[k] = {cam.position(), cam.pixelDirection(x + 0.5, y + 0.5), in.tMin, rays.reach[k]};
    }
    embree.intersect(batch, hits);
    for (size_t k = 0; k < pixels.size(); ++k) {
      far.depth[pixels[k]] = hits[k].hit() ? hits[k].t : kEmptyDepth;
      far.id[pixels[k]] = hits[k].id;
    }
  }
  if (cast) *cast = std::move(rays.pixels);
}

}  // namespace lzb
