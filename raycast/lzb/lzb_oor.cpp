#include "raycast/lzb/lzb_oor.hpp"

#include <algorithm>
#include <cmath>

namespace lzb::localz {

namespace {

constexpr double kEdgeTolerance = 1e-3;  // pixels, outwards
constexpr float kObjectPixels = 32.0f;   // OOR objects are refined until they fit this size

// Node frame -> homogeneous pixel coordinates (X, Y, W): pixel = (X / W, Y / W), W = view depth.
struct Projector {
  glm::dvec3 gx, gy, gw;
  double ox, oy, ow;
  Projector(const Camera& cam, const glm::dmat4& world) {
    const double s = cam.pixelsPerUnitAt(1.0);
    const glm::dvec3 rowX = 0.5 * cam.width() * cam.forward() + s * cam.right();
    const glm::dvec3 rowY = 0.5 * cam.height() * cam.forward() - s * cam.up();
    const glm::dvec3 rowW = cam.forward();
    const glm::dmat3 lt = glm::transpose(glm::dmat3(world));
    const glm::dvec3 rel = glm::dvec3(world[3]) - cam.position();
    gx = lt * rowX, gy = lt * rowY, gw = lt * rowW;
    ox = glm::dot(rowX, rel), oy = glm::dot(rowY, rel), ow = glm::dot(rowW, rel);
  }
};

double cross(const glm::dvec2& o, const glm::dvec2& a, const glm::dvec2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

ScreenPolygon wholeScreen(const Camera& cam) {
  ScreenPolygon p;
  p.x0 = 0.0f, p.y0 = 0.0f, p.x1 = float(cam.width()), p.y1 = float(cam.height());
  p.count = 0;
  return p;
}

ScreenPolygon project(const Projector& pr, const Bounds& box, const Camera& cam, double clip) {
  // The paper's base point and offset vectors: corner c = base + sum of the edges in c's bits.
  const glm::dvec3 base{glm::dot(pr.gx, box.lo) + pr.ox, glm::dot(pr.gy, box.lo) + pr.oy,
                        glm::dot(pr.gw, box.lo) + pr.ow};
  const glm::dvec3 e = box.extent();
  const glm::dvec3 edge[3] = {{pr.gx.x * e.x, pr.gy.x * e.x, pr.gw.x * e.x},
                              {pr.gx.y * e.y, pr.gy.y * e.y, pr.gw.y * e.y},
                              {pr.gx.z * e.z, pr.gy.z * e.z, pr.gw.z * e.z}};
  glm::dvec3 h[8];
  for (int c = 0; c < 8; ++c) {
    h[c] = base;
    for (int k = 0; k < 3; ++k)
      if (c & (1 << k)) h[c] += edge[k];
  }
  // The part of the box behind the clip plane (depth >= clip > 0): its corners there and the
  // points where its edges cross the plane.
  glm::dvec2 pts[20];
  int count = 0;
  for (int c = 0; c < 8; ++c)
    if (h[c].z >= clip) pts[count++] = {h[c].x / h[c].z, h[c].y / h[c].z};
  if (count == 0) return ScreenPolygon{};  // nothing behind the plane
  if (count < 8)
    for (int a = 0; a < 8; ++a)
      for (int k = 0; k < 3; ++k) {
        const int b = a | (1 << k);
        if (b == a || (h[a].z >= clip) == (h[b].z >= clip)) continue;
        const double s = (clip - h[a].z) / (h[b].z - h[a].z);
        const glm::dvec3 q = h[a] + s * (h[b] - h[a]);
        pts[count++] = {q.x / clip, q.y / clip};
      }
  for (int i = 0; i < count; ++i)
    if (!std::isfinite(pts[i].x) || !std::isfinite(pts[i].y)) return wholeScreen(cam);
  ScreenPolygon poly;
  double x0 = pts[0].x, x1 = x0, y0 = pts[0].y, y1 = y0;
  for (int i = 1; i < count; ++i) {
    x0 = std::min(x0, pts[i].x), x1 = std::max(x1, pts[i].x);
    y0 = std::min(y0, pts[i].y), y1 = std::max(y1, pts[i].y);
  }
  // Conservative float bounds (outwards by the tolerance).
  poly.x0 = float(x0 - kEdgeTolerance), poly.x1 = float(x1 + kEdgeTolerance);
  poly.y0 = float(y0 - kEdgeTolerance), poly.y1 = float(y1 + kEdgeTolerance);
  // Andrew's monotone chain: the convex hull.
  std::sort(pts, pts + count, [](const glm::dvec2& a, const glm::dvec2& b) {
    return a.x < b.x || (a.x == b.x && a.y < b.y);
  });
  glm::dvec2 hull[42];
  int n = 0;
  for (int i = 0; i < count; ++i) {
    while (n >= 2 && cross(hull[n - 2], hull[n - 1], pts[i]) <= 0.0) --n;
    hull[n++] = pts[i];
  }
  for (int i = count - 2, lower = n + 1; i >= 0; --i) {
    while (n >= lower && cross(hull[n - 2], hull[n - 1], pts[i]) <= 0.0) --n;
    hull[n++] = pts[i];
  }
  n -= 1;  // the last point repeats the first
  if (n < 3) {
    // Degenerate (a flat box seen edge-on): the bounding box alone decides.
    poly.count = 4;
    poly.v[0] = {x0, y0}, poly.v[1] = {x1, y0}, poly.v[2] = {x1, y1}, poly.v[3] = {x0, y1};
    return poly;
  }
  poly.count = uint8_t(std::min(n, int(ScreenPolygon::kMaxVertices)));
  for (int i = 0; i < poly.count; ++i) poly.v[i] = hull[i];
  return poly;
}

}  // namespace

bool ScreenPolygon::contains(double x, double y) const {
  if (x < x0 || x > x1 || y < y0 || y > y1) return false;
  if (count == 0) return true;
  const glm::dvec2 p{x, y};
  for (int i = 0; i < count; ++i) {
    const glm::dvec2& a = v[i];
    const glm::dvec2& b = v[i + 1 == count ? 0 : i + 1];
    const glm::dvec2 e = b - a;
    // Signed distance of p from the edge line, positive inside (hull turns have cross > 0).
    const double c = e.x * (p.y - a.y) - e.y * (p.x - a.x);
    if (c < -kEdgeTolerance * std::sqrt(e.x * e.x + e.y * e.y)) return false;
  }
  return true;
}

bool ScreenPolygon::rowSpan(int y, int xa, int xb, int& first, int& last) const {
  const double py = y + 0.5;
  if (xa > xb || py < y0 || py > y1) return false;
  // Each edge bounds the centres' x on one side: contains() accepts e.y px <= bound.
  double lo = x0, hi = x1;
  for (int i = 0; i < count; ++i) {
    const glm::dvec2& a = v[i];
    const glm::dvec2 e = v[i + 1 == count ? 0 : i + 1] - a;
    const double bound =
        e.x * (py - a.y) + e.y * a.x + kEdgeTolerance * std::sqrt(e.x * e.x + e.y * e.y);
    if (e.y > 0.0) {
      hi = std::min(hi, bound / e.y);
    } else if (e.y < 0.0) {
      lo = std::max(lo, bound / e.y);
    } else if (bound < 0.0) {
      return false;
    }
  }
  const double f = std::ceil(lo - 0.5), l = std::floor(hi - 0.5);
  first = f < xa ? xa : (f > xb ? xb + 1 : int(f));
  last = l > xb ? xb : (l < xa ? xa - 1 : int(l));
  // The divisions round: settle both ends with contains() itself, so the span is exactly its set.
  while (first <= last && !contains(first + 0.5, py)) ++first;
  while (first > xa && first <= last + 1 && contains(first - 0.5, py)) --first;
  while (last >= first && !contains(last + 0.5, py)) --last;
  while (last < xb && last + 1 >= first && contains(last + 1.5, py)) ++last;
  return first <= last;
}

ScreenPolygon projectLeaf(const LzbAccel& accel, const CullPath& path, uint32_t leaf,
                          const Camera& camera, double clipDepth) {
  return project(Projector(camera, path.world), accel.node(path.node).contentBox(leaf), camera,
                 clipDepth);
}

void OorObjects::build(const LzbAccel& accel, const CulledScene& culled, const Camera& camera,
                       double clipDepth, const ScreenTiles& tiles, int threads) {
  const Frustum world = camera.frustum();
  const long paths = long(culled.paths.size());
  std::vector<std::vector<ScreenPolygon>>& perPath = perPath_;
  if (perPath.size() < culled.paths.size()) perPath.resize(culled.paths.size());
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (paths >= 32)
  for (long p = 0; p < paths; ++p) {
    const CullPath& path = culled.paths[size_t(p)];
    const NodeAccel& a = accel.node(path.node);
    const Octree& tree = a.octree();
    const Projector pr(camera, path.world);
    const Frustum local = frustumToNodeSpace(world, path.world);
    std::vector<ScreenPolygon>& out = perPath[size_t(p)];
    out.clear();
    // Coarsest first: a node whose far content projects within kObjectPixels (or a leaf) is one
    // object; larger ones are refined into their children.
    std::vector<uint32_t> stack{0};
    while (!stack.empty()) {
      const uint32_t n = stack.back();
      stack.pop_back();
      const Bounds& c = a.contentBox(n);
      if (c.empty()) continue;
      const double depthMax = glm::dot(path.depthGrad, c.center()) + path.depthOffset +
                              glm::dot(glm::abs(path.depthGrad), 0.5 * c.extent());
      if (depthMax < clipDepth || local.classify(c) == Cull::kOutside) continue;
      ScreenPolygon poly = project(pr, c, camera, clipDepth);
      if (poly.x0 > poly.x1) continue;  // nothing behind the plane
      poly.depthMax = depthMax;
      const Octree::Node& node = tree.node(n);
      if (node.leaf() ||
          (poly.x1 - poly.x0 <= kObjectPixels && poly.y1 - poly.y0 <= kObjectPixels)) {
        out.push_back(poly);
        continue;
      }
      for (uint32_t k = 8; k-- > 0;) stack.push_back(node.firstChild + k);
    }
  }
  polygons_.clear();
  for (long p = 0; p < paths; ++p)
    polygons_.insert(polygons_.end(), perPath[size_t(p)].begin(), perPath[size_t(p)].end());
  // Bin by bounding box: counts, prefix sums, fill (object order within each tile).
  const int side = ScreenTiles::kDefaultSide, cols = tiles.columns(), rows = tiles.rows();
  struct Span {
    int tx0, tx1, ty0, ty1;
  };
  std::vector<Span> spans(polygons_.size());
  binBegin_.assign(size_t(tiles.count()) + 1, 0);
  for (size_t i = 0; i < polygons_.size(); ++i) {
    const ScreenPolygon& p = polygons_[i];
    // Pixel centres inside [x0, x1]: columns ceil(x0 - 0.5) .. floor(x1 - 0.5).
    const double px0 = std::ceil(double(p.x0) - 0.5), px1 = std::floor(double(p.x1) - 0.5);
    const double py0 = std::ceil(double(p.y0) - 0.5), py1 = std::floor(double(p.y1) - 0.5);
    Span s{0, -1, 0, -1};
    if (px1 >= 0.0 && py1 >= 0.0 && px0 < camera.width() && py0 < camera.height() && px0 <= px1 &&
        py0 <= py1) {
      s.tx0 = int(std::max(px0, 0.0)) / side;
      s.tx1 = std::min(int(std::min(px1, double(camera.width() - 1))) / side, cols - 1);
      s.ty0 = int(std::max(py0, 0.0)) / side;
      s.ty1 = std::min(int(std::min(py1, double(camera.height() - 1))) / side, rows - 1);
    }
    spans[i] = s;
    for (int ty = s.ty0; ty <= s.ty1; ++ty)
      for (int tx = s.tx0; tx <= s.tx1; ++tx) ++binBegin_[size_t(ty * cols + tx) + 1];
  }
  for (size_t t = 0; t < size_t(tiles.count()); ++t) binBegin_[t + 1] += binBegin_[t];
  binned_.resize(binBegin_.back());
  std::vector<uint32_t> fill(binBegin_.begin(), binBegin_.end() - 1);
  for (size_t i = 0; i < polygons_.size(); ++i) {
    const Span& s = spans[i];
    for (int ty = s.ty0; ty <= s.ty1; ++ty)
      for (int tx = s.tx0; tx <= s.tx1; ++tx) binned_[fill[size_t(ty * cols + tx)]++] = uint32_t(i);
  }
}

}  // namespace lzb::localz
