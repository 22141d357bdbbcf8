#include "raycast/lzb_tile_cast.hpp"

#include <algorithm>
#include <cmath>

namespace lzb {

std::vector<uint32_t> tilePixelsToCast(const TileRect& r, int tileIndex, const TileCastInput& in,
                                       std::vector<uint8_t>& mask, TileCastCounts& counts) {
  const Framebuffer& fb = *in.nearPass;
  const int w = r.x1 - r.x0;
  if (mask.size() < size_t(r.pixels())) mask.resize(size_t(r.pixels()));
  // mask: 0 finished, 1 unfinished and not cast yet, 2 to cast.
  uint64_t open = 0;
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x) {
      const bool unfinished = fb.id[fb.index(x, y)] == kNoId;
      mask[size_t((y - r.y0) * w + (x - r.x0))] = unfinished ? 1 : 0;
      open += unfinished;
    }
  counts.unfinished += open;
  std::vector<uint32_t> pixels;
  if (open == 0) return pixels;
  if (in.oor) {
    // Object by object: unfinished pixels inside the polygon's bounding box, then inside the
    // polygon, are marked once (the boolean matrix of the paper).
    for (uint32_t k : in.oor->tile(tileIndex)) {
      const ScreenPolygon& p = in.oor->polygon(k);
      const int xa = std::max(r.x0, int(std::ceil(double(p.x0) - 0.5)));
      const int xb = std::min(r.x1 - 1, int(std::floor(double(p.x1) - 0.5)));
      const int ya = std::max(r.y0, int(std::ceil(double(p.y0) - 0.5)));
      const int yb = std::min(r.y1 - 1, int(std::floor(double(p.y1) - 0.5)));
      for (int y = ya; y <= yb; ++y)
        for (int x = xa; x <= xb; ++x) {
          uint8_t& m = mask[size_t((y - r.y0) * w + (x - r.x0))];
          if (m != 1) continue;
          ++counts.polygonTests;
          if (p.contains(x + 0.5, y + 0.5)) {
            m = 2;
            --open;
          }
        }
      if (open == 0) break;  // every unfinished pixel of the tile is marked
    }
  }
  const uint8_t want = in.oor ? 2 : 1;
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x)
      if (mask[size_t((y - r.y0) * w + (x - r.x0))] == want)
        pixels.push_back(uint32_t(fb.index(x, y)));
  counts.cast += pixels.size();
  return pixels;
}

void castTilePvl(RayWalker& walker, const TileRect& r, int tileIndex, const TileCastInput& in,
                 std::vector<uint8_t>& mask, PvlPart& out, TileCastCounts& counts,
                 std::vector<uint32_t>* cast) {
  const std::vector<uint32_t> pixels = tilePixelsToCast(r, tileIndex, in, mask, counts);
  walker.resetCoherence();
  const Camera& cam = *in.camera;
  const int w = in.nearPass->width;
  for (uint32_t i : pixels) {
    const int x = int(i % uint32_t(w)), y = int(i / uint32_t(w));
    walker.cast(cam.position(), cam.pixelDirection(x + 0.5, y + 0.5), in.tMin, in.tMax, out);
  }
  if (cast) *cast = pixels;
}

void castTileEmbree(const EmbreeScene& embree, const TileRect& r, int tileIndex,
                    const TileCastInput& in, std::vector<uint8_t>& mask, Framebuffer& far,
                    TileCastCounts& counts, std::vector<uint32_t>* cast) {
  const std::vector<uint32_t> pixels = tilePixelsToCast(r, tileIndex, in, mask, counts);
  if (cast) *cast = pixels;
  if (pixels.empty()) return;
  const Camera& cam = *in.camera;
  const int w = in.nearPass->width;
  std::vector<Ray> rays(pixels.size());
  std::vector<RayHit> hits(pixels.size());
  for (size_t k = 0; k < pixels.size(); ++k) {
    const int x = int(pixels[k] % uint32_t(w)), y = int(pixels[k] / uint32_t(w));
    rays[k] = {cam.position(), cam.pixelDirection(x + 0.5, y + 0.5), in.tMin, in.tMax};
  }
  embree.intersect(rays, hits);
  for (size_t k = 0; k < pixels.size(); ++k) {
    far.depth[pixels[k]] = hits[k].hit() ? hits[k].t : kEmptyDepth;
    far.id[pixels[k]] = hits[k].id;
  }
}

}  // namespace lzb
