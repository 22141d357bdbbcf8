#include "src/zbuffer/native_raster.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "src/core/prefetch.hpp"
#include "src/core/range_pieces.hpp"
#include "src/zbuffer/soup_prefilter.hpp"

namespace lzb {

namespace {

constexpr int64_t kOne = int64_t(1) << kSubpixelBits;
constexpr int64_t kHalf = kOne / 2;
// Guard band: triangles reaching farther than this many pixels outside the image are clipped
// there, so snapped coordinates stay within ~2^22 subpixels and edge products far inside int64.
constexpr double kGuard = 8192.0;
// Clipping a triangle at 5 planes leaves at most 8 vertices.
constexpr int kMaxClipVertices = 9;

// The clip planes as f(v) >= 0 on view coordinates (x, y, depth): near, then the guard band's
// left, right, top, bottom (pixel x = w/2 + s x / d, pixel y = h/2 - s y / d).
struct ClipPlanes {
  double nearDepth, s, gx, gy;  // gx = w/2 + guard, gy = h/2 + guard
  double eval(int k, const glm::dvec3& v) const {
    switch (k) {
      case 0:
        return v.z - nearDepth;
      case 1:
        return gx * v.z + s * v.x;
      case 2:
        return gx * v.z - s * v.x;
      case 3:
        return gy * v.z - s * v.y;
      default:
        return gy * v.z + s * v.y;
    }
  }
};

// halfWidth, halfHeight: half the image size in pixels (converted once per pass, not per vertex).
ScreenVertex project(const glm::dvec3& v, double s, double halfWidth, double halfHeight) {
  const double f = s / v.z;
  return {halfWidth + f * v.x, halfHeight - f * v.y, v.z};
}

// Round to nearest (ties to even) for |x| < 2^51, without a libm call (rounding mode: nearest).
int64_t roundFast(double x) {
  constexpr double kMagic = 6755399441055744.0;  // 1.5 * 2^52
  return int64_t((x + kMagic) - kMagic);
}
int64_t floorFast(double x) {
  const int64_t t = int64_t(x);
  return t - int64_t(x < double(t));
}
int64_t ceilFast(double x) {
  return -floorFast(-x);
}

// Whether [lo, hi] may hold a pixel centre i + 0.5 with 0 <= i < n once snapped: snapping moves
// a coordinate by at most half a subpixel, so a subpixel of slack keeps this conservative.
[[gnu::always_inline]] inline bool mayCoverCentre(double lo, double hi, int n) {
  constexpr double kSlack = 1.0 / double(kOne);
  const int64_t first = std::max<int64_t>(0, ceilFast(lo - 0.5 - kSlack));
  const int64_t last = std::min<int64_t>(n - 1, floorFast(hi - 0.5 + kSlack));
  return first <= last;
}

// Boxes at most this many pixels wide test each pixel; wider ones compute each row's span.
constexpr int64_t kNarrow = 4;

int64_t floorShift(int64_t a) {
  return a >> kSubpixelBits;
}  // floor(a / kOne)
int64_t ceilShift(int64_t a) {
  return -((-a) >> kSubpixelBits);
}  // ceil(a / kOne)

// Most PVL triangles of a distant scene are smaller than a pixel and miss every pixel centre:
// this rejects them before any snapping or division.
inline bool mayCoverCentre(const ScreenVertex (&v)[3], int width, int height) {
  return mayCoverCentre(std::min({v[0].x, v[1].x, v[2].x}), std::max({v[0].x, v[1].x, v[2].x}),
                        width) &&
         mayCoverCentre(std::min({v[0].y, v[1].y, v[2].y}), std::max({v[0].y, v[1].y, v[2].y}),
                        height);
}

// setupTriangle after mayCoverCentre passed.
bool setupCandidate(const ScreenVertex (&v)[3], uint64_t id, int width, int height,
                    RasterTriangle& t) {
  for (int k = 0; k < 3; ++k) {
    t.x[k] = int32_t(roundFast(v[k].x * double(kOne)));
    t.y[k] = int32_t(roundFast(v[k].y * double(kOne)));
  }
  const int64_t minX = std::min({t.x[0], t.x[1], t.x[2]}),
                maxX = std::max({t.x[0], t.x[1], t.x[2]});
  const int64_t minY = std::min({t.y[0], t.y[1], t.y[2]}),
                maxY = std::max({t.y[0], t.y[1], t.y[2]});
  // Pixel i's centre is i * kOne + kHalf in fixed point.
  t.x0 = int32_t(std::max<int64_t>(0, ceilShift(minX - kHalf)));
  t.x1 = int32_t(std::min<int64_t>(width, floorShift(maxX - kHalf) + 1));
  t.y0 = int32_t(std::max<int64_t>(0, ceilShift(minY - kHalf)));
  t.y1 = int32_t(std::min<int64_t>(height, floorShift(maxY - kHalf) + 1));
  if (t.x0 >= t.x1 || t.y0 >= t.y1) return false;
  const int64_t area = int64_t(t.x[1] - t.x[0]) * int64_t(t.y[2] - t.y[0]) -
                       int64_t(t.y[1] - t.y[0]) * int64_t(t.x[2] - t.x[0]);
  if (area == 0) return false;
  if (area < 0) {  // no back-face culling: both windings are drawn, set up counter-clockwise
    std::swap(t.x[1], t.x[2]);
    std::swap(t.y[1], t.y[2]);
  }
  // The plane of 1/depth through the unsnapped vertices (relative to vertex 0).
  const double i0 = 1.0 / v[0].depth, i1 = 1.0 / v[1].depth, i2 = 1.0 / v[2].depth;
  const double x1 = v[1].x - v[0].x, y1 = v[1].y - v[0].y;
  const double x2 = v[2].x - v[0].x, y2 = v[2].y - v[0].y;
  const double det = x1 * y2 - x2 * y1;
  if (det != 0.0) {
    t.a = ((i1 - i0) * y2 - (i2 - i0) * y1) / det;
    t.b = ((i2 - i0) * x1 - (i1 - i0) * x2) / det;
  } else {  // degenerate unsnapped, not snapped: a constant depth is as good as any
    t.a = t.b = 0.0;
  }
  t.c = i0 - t.a * v[0].x - t.b * v[0].y;
  t.invDepthMin = std::min({i0, i1, i2});
  t.invDepthMax = std::max({i0, i1, i2});
  t.id = id;
  return true;
}

}  // namespace

bool setupTriangle(const ScreenVertex (&v)[3], uint64_t id, int width, int height,
                   RasterTriangle& t) {
  return mayCoverCentre(v, width, height) && setupCandidate(v, id, width, height, t);
}

uint64_t rasterizeTriangle(const RasterTriangle& t, int rowBegin, int rowEnd, const uint8_t* open,
                           double farDepth, Framebuffer& fb) {
  const int ya = std::max(t.y0, rowBegin), yb = std::min(t.y1, rowEnd);
  if (ya >= yb) return 0;
  // Every fragment's depth is at least 1 / invDepthMax (the plane is clamped, division and the
  // float conversion are monotonic): beyond farDepth, no fragment survives.
  const double nearest = 1.0 / t.invDepthMax;
  if (nearest > farDepth) return 0;
  const float nearestF = float(nearest);
  // Edge k runs from vertex k+1 to k+2 (opposite vertex k): E = dx (py - ay) - dy (px - ax) is
  // positive inside. On an edge (E == 0) the pixel belongs to left edges (dy < 0) and bottom
  // edges of the image (y down: dy == 0, dx < 0) only, as OSMesa does (its top-left rule in
  // GL's y-up window coordinates); an edge shared by two triangles runs opposite ways in them,
  // so exactly one owns it.
  int64_t dx[3], dy[3], row[3], bias[3];
  const int64_t px0 = int64_t(t.x0) * kOne + kHalf, py0 = int64_t(ya) * kOne + kHalf;
  for (int k = 0; k < 3; ++k) {
    const int a = (k + 1) % 3, b = (k + 2) % 3;
    dx[k] = int64_t(t.x[b]) - t.x[a];
    dy[k] = int64_t(t.y[b]) - t.y[a];
    row[k] = dx[k] * (py0 - t.y[a]) - dy[k] * (px0 - t.x[a]);
    bias[k] = dy[k] < 0 || (dy[k] == 0 && dx[k] < 0) ? 0 : 1;
  }
  uint64_t written = 0;
  // One covered pixel centre: the z-buffer test against (depth, id).
  auto fragment = [&](size_t i, int x, double rowInvDepth) {
    if (open && !open[i]) return;
    // No fragment of t is nearer than nearestF: skip the division where the test must fail.
    const float old = fb.depth[i];
    if (!nearer(nearestF, t.id, old, fb.id[i])) return;
    // Clamped to the vertices' range, which holds every point of the triangle: on a sliver a
    // pixel centre just outside the unsnapped triangle would extrapolate a steep plane.
    const double depth =
        1.0 / std::clamp(t.a * (x + 0.5) + rowInvDepth, t.invDepthMin, t.invDepthMax);
    if (!(depth <= farDepth)) return;
    const float d = float(depth);
    if (nearer(d, t.id, old, fb.id[i])) {
      fb.depth[i] = d;
      fb.id[i] = t.id;
      ++written;
    }
  };
  const int64_t width = int64_t(t.x1) - t.x0;
  for (int y = ya; y < yb; ++y) {
    const size_t base = fb.index(0, y);
    const double rowInvDepth = t.b * (y + 0.5) + t.c;
    if (width <= kNarrow) {  // test each pixel of the box: cheaper than the divisions below
      int64_t e0 = row[0], e1 = row[1], e2 = row[2];
      for (int x = t.x0; x < t.x1; ++x, e0 -= dy[0] * kOne, e1 -= dy[1] * kOne, e2 -= dy[2] * kOne)
        if (e0 >= bias[0] && e1 >= bias[1] && e2 >= bias[2])
          fragment(base + size_t(x), x, rowInvDepth);
    } else {
      // The row's span [n0, n1) of pixels (from x0) with E_k - dy_k kOne n >= bias_k for every
      // k: each edge bounds n on one side (exact integer division), the same pixels as above.
      int64_t n0 = 0, n1 = width;
      for (int k = 0; k < 3 && n0 < n1; ++k) {
        const int64_t e = row[k] - bias[k], step = dy[k] * kOne;
        if (step > 0) {  // E falls along the row: n <= e / step
          n1 = e < 0 ? 0 : std::min(n1, e / step + 1);
        } else if (step < 0) {  // E rises along the row: n >= ceil(-e / -step)
          if (e < 0) n0 = std::max(n0, (-e - step - 1) / -step);
        } else if (e < 0) {  // a horizontal edge the whole row lies outside of
          n1 = 0;
        }
      }
      for (int x = t.x0 + int(n0), xe = t.x0 + int(n1); x < xe; ++x)
        fragment(base + size_t(x), x, rowInvDepth);
    }
    for (int k = 0; k < 3; ++k) row[k] += dx[k] * kOne;
  }
  return written;
}

void clipAndProject(const glm::dvec3 (&view)[3], double nearDepth, double scale, int width,
                    int height, std::vector<std::array<ScreenVertex, 3>>& out) {
  const ClipPlanes planes{nearDepth, scale, 0.5 * width + kGuard, 0.5 * height + kGuard};
  glm::dvec3 poly[kMaxClipVertices], next[kMaxClipVertices];
  int n = 3;
  for (int k = 0; k < 3; ++k) poly[k] = view[k];
  // Sutherland-Hodgman, in view space (where the planes are linear), near plane first so the
  // guard-band planes see positive depths only.
  for (int p = 0; p < 5 && n >= 3; ++p) {
    int m = 0;
    for (int k = 0; k < n; ++k) {
      const glm::dvec3& a = poly[k];
      const glm::dvec3& b = poly[(k + 1) % n];
      const double fa = planes.eval(p, a), fb = planes.eval(p, b);
      if (fa >= 0.0) next[m++] = a;
      if ((fa >= 0.0) != (fb >= 0.0)) {
        glm::dvec3 c = a + (fa / (fa - fb)) * (b - a);
        if (p == 0) c.z = nearDepth;  // exactly on the near plane, never in front of it
        next[m++] = c;
      }
    }
    n = m;
    std::copy(next, next + n, poly);
  }
  if (n < 3) return;
  ScreenVertex s[kMaxClipVertices];
  for (int k = 0; k < n; ++k) s[k] = project(poly[k], scale, 0.5 * width, 0.5 * height);
  // A convex polygon: a fan from its first vertex (the fan's inner edges are shared exactly).
  for (int k = 1; k + 1 < n; ++k) out.push_back({s[0], s[k], s[k + 1]});
}

namespace {

// A pass's fixed geometry: clip depths, the projection and the guard band in pixels.
struct PassGeometry {
  int width, height;
  double nearDepth, farDepth, s, halfWidth, halfHeight, loX, hiX, loY, hiY;
  PassGeometry(const Camera& camera, int w, int h, double farClip)
      : width(w),
        height(h),
        nearDepth(camera.nearPlane()),
        farDepth(farClip > 0.0 ? std::min(farClip, camera.farPlane()) : camera.farPlane()),
        s(camera.pixelsPerUnitAt(1.0)),
        halfWidth(0.5 * w),
        halfHeight(0.5 * h),
        loX(-kGuard),
        hiX(w + kGuard),
        loY(-kGuard),
        hiY(h + kGuard) {}
};

// Set-up of one view-space triangle into one thread's band bins: clip, snap, bin.
struct Binner {
  const PassGeometry& g;
  std::vector<std::vector<RasterTriangle>>& bins;
  std::vector<std::array<ScreenVertex, 3>> pieces;
  uint64_t setUp = 0, clipped = 0;

  void bin(const ScreenVertex (&v)[3], uint64_t id) {
    // The cheap reject inline, before the call (it drops ~85 % of a PVL's triangles).
    if (!mayCoverCentre(v, g.width, g.height)) return;
    RasterTriangle t;
    if (!setupCandidate(v, id, g.width, g.height, t)) return;
    ++setUp;
    for (int b = t.y0 / NativeRasterizer::kBandRows; b <= (t.y1 - 1) / NativeRasterizer::kBandRows; ++b)
      bins[size_t(b)].push_back(t);
  }
  [[gnu::always_inline]] inline void add(const glm::dvec3 (&view)[3], uint64_t id) {
    int behind = 0, beyond = 0;
    for (int k = 0; k < 3; ++k) {
      behind += view[k].z < g.nearDepth;
      beyond += view[k].z > g.farDepth;
    }
    if (behind == 3 || beyond == 3) return;
    // The common case, wholly in front: project the three vertices without branches between.
    if (behind == 0) {
      ScreenVertex sv[3];
      bool inside = true;
      for (int k = 0; k < 3; ++k) {
        sv[k] = project(view[k], g.s, g.halfWidth, g.halfHeight);
        inside &= sv[k].x >= g.loX && sv[k].x <= g.hiX && sv[k].y >= g.loY && sv[k].y <= g.hiY;
      }
      if (inside) {
        bin(sv, id);
        return;
      }
    }
    ++clipped;
    pieces.clear();
    clipAndProject(view, g.nearDepth, g.s, g.width, g.height, pieces);
    for (const auto& p : pieces) {
      const ScreenVertex v[3] = {p[0], p[1], p[2]};
      bin(v, id);
    }
  }
};

// Bins triangles [lo, hi) of the `first.back()` triangles numbered through ranges (range r holds
// [first[r], first[r+1])), in chunks the threads share dynamically, each thread into its own
// bins: body(binner, r, from, to) sets up triangles [from, to) of range r, range-local. Fills
// the set-up counts.
template <class Body>
void binChunks(const std::vector<uint64_t>& first, uint64_t lo, uint64_t hi,
               const PassGeometry& geometry, int threads,
               std::vector<std::vector<std::vector<RasterTriangle>>>& bins,
               NativeRasterCounts& counts, Body body) {
  hi = std::min(hi, first.back());
  lo = std::min(lo, hi);
  const uint64_t total = hi - lo;
  // At least ~8 chunks per thread, so that a short list (the near pass) is shared evenly.
  const uint64_t chunk = std::clamp<uint64_t>(total / (8 * uint64_t(threads)), 256, 2048);
  const long chunks = long((total + chunk - 1) / chunk);
  uint64_t setUp = 0, clipped = 0;
#pragma omp parallel num_threads(threads) reduction(+ : setUp, clipped)
  {
    Binner binner{geometry, bins[size_t(omp_get_thread_num())], {}};
#pragma omp for schedule(dynamic, 1)
    for (long c = 0; c < chunks; ++c) {
      const uint64_t begin = lo + uint64_t(c) * chunk, end = std::min(hi, begin + chunk);
      forRangePieces(first, begin, end,
                     [&](size_t r, size_t from, size_t to) { body(binner, r, from, to); });
    }
    setUp += binner.setUp;
    clipped += binner.clipped;
  }
  counts.triangles = total;
  counts.setUp = setUp;
  counts.clipped = clipped;
}

}  // namespace

void NativeRasterizer::clearBins(int threads, int height) {
  const int bands = (height + kBandRows - 1) / kBandRows;
  if (bins_.size() < size_t(threads)) bins_.resize(size_t(threads));
  for (auto& perThread : bins_) {
    perThread.resize(size_t(bands));
    for (auto& b : perThread) b.clear();
  }
}

void NativeRasterizer::draw(const Scene& scene, const Camera& camera, const DrawLists& lists,
                            std::span<const uint8_t> open, int threads, Framebuffer& fb,
                            double farClip, IdRange part) {
  if (!open.empty() && open.size() != fb.size())
    throw std::invalid_argument("NativeRasterizer: open mask and framebuffer sizes differ");
  threads = std::max(threads, 1);
  counts_ = {};
  clearBins(threads, fb.height);
  // Per list: node frame -> camera-relative view coordinates (x right, y up, depth), in double.
  struct ViewTransform {
    glm::dmat3 a;  // columns: images of the node frame's axes
    glm::dvec3 b;
  };
  std::vector<ViewTransform> transforms(lists.lists.size());
  std::vector<uint64_t> first(lists.lists.size() + 1, 0);
  const glm::dmat3 toView =
      glm::transpose(glm::dmat3(camera.right(), camera.up(), camera.forward()));
  for (size_t l = 0; l < lists.lists.size(); ++l) {
    const glm::dmat4& m = lists.lists[l].world;
    transforms[l].a = toView * glm::dmat3(m);
    transforms[l].b = toView * (glm::dvec3(m[3]) - camera.position());
    first[l + 1] = first[l] + lists.lists[l].triangles.size();
  }
  const PassGeometry geometry(camera, fb.width, fb.height, farClip);
  constexpr size_t kPrefetch = 8;  // triangles ahead (their corners; their indices twice as far)
  // Set-up: transform, clip, snap, bin to bands (per thread, so no locks).
  binChunks(first, part.begin, part.end, geometry, threads, bins_, counts_,
            [&](Binner& binner, size_t l, size_t from, size_t to) {
              // The chunk's part of list l, with its per-list data hoisted out of the loop.
              const DrawList& list = lists.lists[l];
              const uint32_t* tris = list.triangles.data();
              const size_t n = list.triangles.size();
              const Mesh& mesh = scene.nodes[list.node].mesh;
              const glm::vec3* pos = mesh.positions.data();
              const uint32_t* corners = mesh.indices.data();
              const ViewTransform& xf = transforms[l];
              for (size_t i = from; i < to; ++i) {
                // Triangles are scattered over the mesh: fetch a later one's indices ahead, and
                // the corners of a nearer one (its indices fetched by then).
                if (i + 2 * kPrefetch < n)
                  prefetchRead(corners + 3 * size_t(tris[i + 2 * kPrefetch]));
                if (i + kPrefetch < n) {
                  const uint32_t* ahead = corners + 3 * size_t(tris[i + kPrefetch]);
                  for (int k = 0; k < 3; ++k) prefetchRead(pos + ahead[k]);
                }
                const uint32_t tri = tris[i];
                const uint32_t* c = corners + 3 * size_t(tri);
                glm::dvec3 view[3];
                for (int k = 0; k < 3; ++k) view[k] = xf.a * glm::dvec3(pos[c[k]]) + xf.b;
                binner.add(view, list.idBase + tri);
              }
            });
  counts_.fragments = rasterizeBins(threads, open.empty() ? nullptr : open.data(),
                                    geometry.farDepth, fb);
}

void NativeRasterizer::drawSoup(const Camera& camera, const TriangleSoup& soup, int threads,
                                Framebuffer& fb) {
  threads = std::max(threads, 1);
  counts_ = {};
  clearBins(threads, fb.height);
  const std::vector<uint64_t> first = rangeStarts(soup.ranges);
  const PassGeometry geometry(camera, fb.width, fb.height, 0.0);
  const glm::dmat3 toView =
      glm::transpose(glm::dmat3(camera.right(), camera.up(), camera.forward()));
  const glm::dvec3 eye = camera.position();
  const SoupPrefilter prefilter(eye, toView, geometry.s, fb.width, fb.height, geometry.nearDepth,
                                kGuard);
  binChunks(first, 0, first.back(), geometry, threads, bins_, counts_,
            [&](Binner& binner, size_t r, size_t from, size_t to) {
              const auto setUp = [&](uint64_t tri) {
                glm::dvec3 view[3];
                for (int k = 0; k < 3; ++k)
                  view[k] = toView * (glm::dvec3(soup.positions[3 * tri + size_t(k)]) - eye);
                binner.add(view, soup.ids[tri]);
              };
              const uint64_t begin = soup.ranges[r].begin;
              size_t i = from;
              // Eight at a time through the float pre-pass; only what it passes is set up exactly.
              for (; i + 8 <= to; i += 8)
                for (unsigned keep = prefilter.mayCover8(&soup.positions[3 * (begin + i)]); keep;
                     keep &= keep - 1)
                  setUp(begin + i + size_t(__builtin_ctz(keep)));
              for (; i < to; ++i) setUp(begin + i);
            });
  counts_.fragments = rasterizeBins(threads, nullptr, geometry.farDepth, fb);
}

uint64_t NativeRasterizer::rasterizeBins(int threads, const uint8_t* mask, double farDepth,
                                         Framebuffer& fb) {
  // Bands of rows, each written by one thread only.
  const int height = fb.height;
  const int bands = (height + kBandRows - 1) / kBandRows;
  uint64_t fragments = 0;
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1) reduction(+ : fragments)
  for (int b = 0; b < bands; ++b) {
    const int rowBegin = b * kBandRows, rowEnd = std::min(height, rowBegin + kBandRows);
    for (int t = 0; t < threads; ++t)
      for (const RasterTriangle& tri : bins_[size_t(t)][size_t(b)])
        fragments += rasterizeTriangle(tri, rowBegin, rowEnd, mask, farDepth, fb);
  }
  return fragments;
}

}  // namespace lzb
