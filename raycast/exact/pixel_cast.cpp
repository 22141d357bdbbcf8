#include "raycast/exact/pixel_cast.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include "mpi/decomposition.hpp"

namespace lzb {

namespace {

// Traces the pixel centres of one tile into fb; true when some ray hit.
bool traceTile(const EmbreeScene& embree, const Camera& camera, const TileRect& r, bool packets,
               Framebuffer& fb) {
  const glm::dvec3 eye = camera.position();
  bool any = false;
  if (!packets) {
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x) {
        const RayHit h = embree.intersect(eye, camera.pixelDirection(x + 0.5, y + 0.5),
                                          camera.nearPlane(), camera.farPlane());
        fb.depth[fb.index(x, y)] = h.hit() ? h.t : kEmptyDepth;
        fb.id[fb.index(x, y)] = h.id;
        any |= h.hit();
      }
    return any;
  }
  // 4x4 pixel blocks in order, so that each packet of 16 (or 8) rays is coherent.
  constexpr int kMax = ScreenTiles::kDefaultSide * ScreenTiles::kDefaultSide;
  Ray rays[kMax];
  RayHit hits[kMax];
  size_t pixel[kMax];
  size_t n = 0;
  for (int by = r.y0; by < r.y1; by += 4)
    for (int bx = r.x0; bx < r.x1; bx += 4)
      for (int y = by; y < std::min(by + 4, r.y1); ++y)
        for (int x = bx; x < std::min(bx + 4, r.x1); ++x) {
          rays[n] = {eye, camera.pixelDirection(x + 0.5, y + 0.5), camera.nearPlane(),
                     camera.farPlane()};
          pixel[n++] = fb.index(x, y);
        }
  embree.intersect(std::span<const Ray>(rays, n), std::span<RayHit>(hits, n));
  for (size_t k = 0; k < n; ++k) {
    fb.depth[pixel[k]] = hits[k].hit() ? hits[k].t : kEmptyDepth;
    fb.id[pixel[k]] = hits[k].id;
    any |= hits[k].hit();
  }
  return any;
}

// The pixels whose centre rays can meet `box`: the rectangle of its corners' projections, a pixel
// wider on each side for rounding; the whole frame when a corner is not in front of the camera;
// none when the box is empty.
TileRect pixelsUnder(const Bounds& box, const Camera& camera, int width, int height) {
  if (box.empty()) return {0, 0, 0, 0};
  glm::dvec2 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest());
  for (int k = 0; k < 8; ++k) {
    const glm::dvec3 p = camera.project(box.corner(k));
    if (!(p.z > 0.0)) return {0, 0, width, height};
    lo = glm::min(lo, glm::dvec2(p));
    hi = glm::max(hi, glm::dvec2(p));
  }
  const auto x = [&](double v) { return int(std::clamp(v, 0.0, double(width))); };
  const auto y = [&](double v) { return int(std::clamp(v, 0.0, double(height))); };
  return {x(std::floor(lo.x) - 1.0), y(std::floor(lo.y) - 1.0), x(std::ceil(hi.x) + 1.0),
          y(std::ceil(hi.y) + 1.0)};
}

bool overlap(const TileRect& a, const TileRect& b) {
  return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

// share's tiles under the projection of what embree holds.
std::vector<int> tilesToCast(const EmbreeScene& embree, const Camera& camera,
                             const WorkShare& share, const ScreenTiles& tiles) {
  const TileRect under = pixelsUnder(embree.heldBounds(), camera, camera.width(), camera.height());
  std::vector<int> mine;
  for (int t : tiles.owned(share))
    if (overlap(tiles.tile(t), under)) mine.push_back(t);
  return mine;
}

}  // namespace

uint64_t castablePixels(const EmbreeScene& embree, const Camera& camera) {
  const ScreenTiles tiles(camera.width(), camera.height());
  uint64_t pixels = 0;
  for (int t : tilesToCast(embree, camera, WorkShare{}, tiles)) pixels += tiles.tile(t).pixels();
  return pixels;
}

uint64_t castEveryPixel(const EmbreeScene& embree, const Camera& camera, const WorkShare& share,
                        Framebuffer& fb, std::vector<uint8_t>& touched, int threads, bool packets) {
  const ScreenTiles tiles(fb.width, fb.height);
  // Tiles beyond the projection of what the scene holds stay empty without a ray: a scene part
  // (--distribute data) casts only where its regions project.
  const std::vector<int> mine = tilesToCast(embree, camera, share, tiles);
  touched.assign(size_t(tiles.count()), 0);
  const long count = long(mine.size());
  long rays = 0;
#pragma omp parallel for schedule(dynamic, 1) num_threads(std::max(threads, 1)) reduction(+ : rays)
  for (long k = 0; k < count; ++k) {
    const TileRect r = tiles.tile(mine[size_t(k)]);
    touched[size_t(mine[size_t(k)])] = uint8_t(traceTile(embree, camera, r, packets, fb));
    rays += r.pixels();
  }
  return uint64_t(rays);
}

}  // namespace lzb
