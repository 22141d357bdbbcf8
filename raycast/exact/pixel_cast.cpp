#include "raycast/exact/pixel_cast.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <span>
#include <vector>

#include "mpi/decomposition.hpp"

namespace lzb {

namespace {

// How far each pixel's ray looks: the far plane, or the depth another share drew there
// (share.drawnDepth; a hit at that depth may still win on its ID, and Embree keeps hits at
// t == tfar). There, a share holding one region among several casts no ray that misses its box
// before that depth (most of them: the regions are disjoint boxes, each under most pixels).
struct PixelReach {
  const std::vector<float>* drawn = nullptr;
  Bounds box;            // what the scene holds, padded for rounding (with drawn only)
  double nearest = 0.0;  // the least view depth in the box
  double far = 0.0;
  double tfar(size_t i) const {
    return drawn && (*drawn)[i] != kEmptyDepth ? std::min(far, double((*drawn)[i])) : far;
  }
  // Whether something is drawn at pixel i in front of the whole box.
  bool hidden(size_t i) const { return drawn && double((*drawn)[i]) < nearest; }
  // Whether the ray from eye along dir can meet what the scene holds before tfar.
  bool reaches(const glm::dvec3& eye, const glm::dvec3& dir, double near, double until) const {
    if (!drawn) return true;
    double t0 = near, t1 = until;
    return RaySlabs(eye, dir).clip(box, t0, t1);
  }
};

// Whether a ray through some pixel of r can meet reach.box before the depth drawn there: the
// box is not wholly outside one side of the tile's pyramid (the planes through the eye and
// its edges), nor behind every pixel's drawn depth. Conservative: the pixels decide the rest.
bool tileReaches(const PixelReach& reach, const Camera& camera, const TileRect& r,
                 const Framebuffer& fb) {
  if (!reach.drawn) return true;
  const glm::dvec3 eye = camera.position();
  const glm::dvec3 d[4] = {camera.pixelDirection(r.x0, r.y0), camera.pixelDirection(r.x1, r.y0),
                           camera.pixelDirection(r.x1, r.y1), camera.pixelDirection(r.x0, r.y1)};
  const glm::dvec3 centre = d[0] + d[1] + d[2] + d[3];
  for (int k = 0; k < 4; ++k) {
    glm::dvec3 n = glm::cross(d[k], d[(k + 1) % 4]);
    if (glm::dot(n, centre) < 0.0) n = -n;  // towards the inside
    double most = -std::numeric_limits<double>::infinity();
    for (int c = 0; c < 8; ++c) most = std::max(most, glm::dot(n, reach.box.corner(c) - eye));
    if (most < 0.0) return false;
  }
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x)
      if (!reach.hidden(fb.index(x, y))) return true;
  return false;
}

// Pixel (x, y)'s centre ray (i: its index), or false when it need not be cast.
bool pixelRay(const Camera& camera, const PixelReach& reach, int x, int y, size_t i, Ray& ray) {
  if (reach.hidden(i)) return false;
  ray = {camera.position(), camera.pixelDirection(x + 0.5, y + 0.5), camera.nearPlane(),
         reach.tfar(i)};
  return reach.reaches(ray.origin, ray.dir, ray.tnear, ray.tfar);
}

struct TileCast {
  uint64_t rays = 0;
  bool hit = false;
};

// Traces the pixel centres of one tile into fb.
TileCast traceTile(const EmbreeScene& embree, const Camera& camera, const TileRect& r, bool packets,
                   const PixelReach& reach, const BlockCover* cover, Framebuffer& fb) {
  TileCast cast;
  if (!tileReaches(reach, camera, r, fb)) return cast;
  if (!packets) {
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x) {
        if (cover && !cover->covers(x, y)) continue;
        const size_t i = fb.index(x, y);
        Ray ray;
        if (!pixelRay(camera, reach, x, y, i, ray)) continue;
        const RayHit h = embree.intersect(ray.origin, ray.dir, ray.tnear, ray.tfar);
        fb.depth[i] = h.hit() ? h.t : kEmptyDepth;
        fb.id[i] = h.id;
        cast.hit |= h.hit();
        ++cast.rays;
      }
    return cast;
  }
  // 4x4 pixel blocks in order, so that each packet of 16 (or 8) rays is coherent.
  constexpr int kMax = ScreenTiles::kDefaultSide * ScreenTiles::kDefaultSide;
  Ray rays[kMax];
  RayHit hits[kMax];
  size_t pixel[kMax];
  size_t n = 0;
  for (int by = r.y0; by < r.y1; by += 4)
    for (int bx = r.x0; bx < r.x1; bx += 4) {
      if (cover && !cover->covers(bx, by)) continue;
      for (int y = by; y < std::min(by + 4, r.y1); ++y)
        for (int x = bx; x < std::min(bx + 4, r.x1); ++x) {
          pixel[n] = fb.index(x, y);
          n += pixelRay(camera, reach, x, y, pixel[n], rays[n]);
        }
    }
  embree.intersect(std::span<const Ray>(rays, n), std::span<RayHit>(hits, n));
  for (size_t k = 0; k < n; ++k) {
    fb.depth[pixel[k]] = hits[k].hit() ? hits[k].t : kEmptyDepth;
    fb.id[pixel[k]] = hits[k].id;
    cast.hit |= hits[k].hit();
  }
  cast.rays = n;
  return cast;
}

bool overlap(const TileRect& a, const TileRect& b) {
  return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

// share's tiles under the projection of what embree holds.
std::vector<int> tilesToCast(const EmbreeScene& embree, const Camera& camera,
                             const WorkShare& share, const ScreenTiles& tiles) {
  const TileRect under =
      pixelsUnder(embree.heldBounds(), CameraPlacement(camera, glm::dmat4(1.0)), camera);
  std::vector<int> mine;
  for (int t : tiles.owned(share))
    if (overlap(tiles.tile(t), under)) mine.push_back(t);
  return mine;
}

// The box grown by a margin for the float rounding of hits and of Embree's bounds.
Bounds padded(const Bounds& box) {
  const double pad = 1e-5 * (box.diagonal() + std::max(glm::length(box.lo), glm::length(box.hi)));
  return {box.lo - pad, box.hi + pad};
}

}  // namespace

CameraPlacement::CameraPlacement(const Camera& camera, const glm::dmat4& toWorld) {
  const glm::dmat3 rows = glm::transpose(glm::dmat3(camera.right(), camera.up(), camera.forward()));
  a = rows * glm::dmat3(toWorld);
  t = rows * (glm::dvec3(toWorld[3]) - camera.position());
}

TileRect pixelsUnder(const Bounds& box, const CameraPlacement& p, const Camera& camera) {
  const int width = camera.width(), height = camera.height();
  if (box.empty()) return {0, 0, 0, 0};
  // Corner k = o + the edges whose bit k sets (Bounds::corner's order).
  const glm::dvec3 o = p.a * box.lo + p.t;
  const glm::dvec3 size = box.hi - box.lo;
  const glm::dvec3 e[3] = {p.a[0] * size.x, p.a[1] * size.y, p.a[2] * size.z};
  double near = o.z, far = o.z;
  for (const glm::dvec3& edge : e) (edge.z < 0.0 ? near : far) += edge.z;
  // (A margin of 1e-6 of the depths for the rounding of the corners and of Embree's bounds.)
  const double slack = 1e-6 * std::max(std::abs(near), std::abs(far));
  if (far < camera.nearPlane() - slack || near > camera.farPlane() + slack) return {0, 0, 0, 0};
  if (!(near > 0.0)) return {0, 0, width, height};
  glm::dvec2 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest());
  for (int k = 0; k < 8; ++k) {
    const glm::dvec3 c = o + (k & 1 ? e[0] : glm::dvec3(0.0)) + (k & 2 ? e[1] : glm::dvec3(0.0)) +
                         (k & 4 ? e[2] : glm::dvec3(0.0));
    const glm::dvec2 s(c.x / c.z, c.y / c.z);
    lo = glm::min(lo, s);
    hi = glm::max(hi, s);
  }
  // Camera::project's pixel coordinates (y down) of the extremes.
  const double x0 = (lo.x / camera.tanHalfX() + 1.0) * 0.5 * width;
  const double x1 = (hi.x / camera.tanHalfX() + 1.0) * 0.5 * width;
  const double y0 = (1.0 - hi.y / camera.tanHalfY()) * 0.5 * height;
  const double y1 = (1.0 - lo.y / camera.tanHalfY()) * 0.5 * height;
  const auto x = [&](double v) { return int(std::clamp(v, 0.0, double(width))); };
  const auto y = [&](double v) { return int(std::clamp(v, 0.0, double(height))); };
  return {x(std::floor(x0) - 1.0), y(std::floor(y0) - 1.0), x(std::ceil(x1) + 1.0),
          y(std::ceil(y1) + 1.0)};
}

BlockCover::BlockCover(int width, int height)
    : columns_((width + kSide - 1) / kSide),
      under_(size_t(columns_) * size_t((height + kSide - 1) / kSide), 0) {}

template <class Row>
bool BlockCover::eachRow(const TileRect& r, Row&& row) const {
  const int c0 = r.x0 / kSide, count = (r.x1 - 1) / kSide - c0 + 1;
  for (int y = r.y0 / kSide; y <= (r.y1 - 1) / kSide; ++y)
    if (!row(size_t(y) * size_t(columns_) + size_t(c0), size_t(count))) return false;
  return true;
}

void BlockCover::add(const TileRect& r) {
  if (r.x0 >= r.x1 || r.y0 >= r.y1) return;
  eachRow(r, [&](size_t first, size_t n) {
    std::fill_n(under_.begin() + std::ptrdiff_t(first), n, uint8_t(1));
    return true;
  });
}

bool BlockCover::anyIn(const TileRect& r) const {
  if (r.x0 >= r.x1 || r.y0 >= r.y1) return false;
  return !eachRow(r, [&](size_t first, size_t n) {
    return std::count(under_.begin() + std::ptrdiff_t(first),
                      under_.begin() + std::ptrdiff_t(first + n), uint8_t(0)) == std::ptrdiff_t(n);
  });
}

bool BlockCover::allIn(const TileRect& r) const {
  if (r.x0 >= r.x1 || r.y0 >= r.y1) return true;
  return eachRow(r, [&](size_t first, size_t n) {
    return std::memchr(under_.data() + first, 0, n) == nullptr;
  });
}

uint64_t BlockCover::blocks() const {
  return uint64_t(std::count(under_.begin(), under_.end(), 1));
}

uint64_t castablePixels(const EmbreeScene& embree, const Camera& camera) {
  const ScreenTiles tiles(camera.width(), camera.height());
  uint64_t pixels = 0;
  for (int t : tilesToCast(embree, camera, WorkShare{}, tiles)) pixels += tiles.tile(t).pixels();
  return pixels;
}

uint64_t castEveryPixel(const EmbreeScene& embree, const Camera& camera, const WorkShare& share,
                        Framebuffer& fb, std::vector<uint8_t>& touched, int threads, bool packets,
                        const BlockCover* cover) {
  const ScreenTiles tiles(fb.width, fb.height);
  // Tiles beyond the projection of what the scene holds stay empty without a ray: a scene part
  // (--distribute data) casts only where its regions project.
  std::vector<int> mine = tilesToCast(embree, camera, share, tiles);
  if (cover) std::erase_if(mine, [&](int t) { return !cover->anyIn(tiles.tile(t)); });
  touched.assign(size_t(tiles.count()), 0);
  PixelReach reach{share.drawnDepth, {}, 0.0, camera.farPlane()};
  if (reach.drawn) {
    reach.box = padded(embree.heldBounds());
    reach.nearest = std::numeric_limits<double>::infinity();
    for (int c = 0; c < 8; ++c)
      reach.nearest = std::min(reach.nearest, camera.viewDepth(reach.box.corner(c)));
  }
  const long count = long(mine.size());
  long rays = 0;
#pragma omp parallel for schedule(dynamic, 1) num_threads(std::max(threads, 1)) reduction(+ : rays)
  for (long k = 0; k < count; ++k) {
    const TileCast cast =
        traceTile(embree, camera, tiles.tile(mine[size_t(k)]), packets, reach, cover, fb);
    touched[size_t(mine[size_t(k)])] = uint8_t(cast.hit);
    rays += long(cast.rays);
  }
  return uint64_t(rays);
}

}  // namespace lzb
