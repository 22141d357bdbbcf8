#include "src/surfels/surfelize.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "src/core/color.hpp"
#include "src/core/framebuffer.hpp"
#include "src/core/timer.hpp"
#include "src/octree/tri_box_overlap.hpp"
#include "src/zbuffer/native_raster.hpp"

namespace lzb::surfels {

Domain Domain::around(const Mesh& mesh) {
  Bounds b;
  for (const glm::vec3& p : mesh.positions) b.extend(glm::dvec3(p));
  const glm::dvec3 e = b.extent();
  // A hair larger than the bounds, so the far faces map inside the last cell.
  const double side = std::max({e.x, e.y, e.z}) * (1.0 + 1e-6) + 1e-30;
  return {b.center() - glm::dvec3(0.5 * side), side};
}

namespace {

using Tri = std::array<glm::dvec3, 3>;

Tri gridTriangle(const Mesh& mesh, uint32_t t, const Domain& d, int grid) {
  Tri g;
  for (int k = 0; k < 3; ++k)
    g[size_t(k)] = (glm::dvec3(mesh.vertex(t, k)) - d.origin) / d.side * double(grid);
  return g;
}

glm::dvec3 closestOnSegment(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec3 ab = b - a;
  const double len2 = glm::dot(ab, ab);
  if (!(len2 > 0.0)) return a;
  return a + std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) * ab;
}

// Ericson, Real-Time Collision Detection 5.1.5: the point of triangle abc nearest p.
glm::dvec3 closestOnTriangle(const glm::dvec3& p, const Tri& t) {
  const glm::dvec3 &a = t[0], &b = t[1], &c = t[2];
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + d1 / (d1 - d3) * ab;
  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// Keeps the part of convex polygon `poly` with coordinate k >= bound (above) or <= bound.
void clipAxis(std::vector<glm::dvec3>& poly, int k, double bound, bool above,
              std::vector<glm::dvec3>& out) {
  out.clear();
  const auto inside = [&](const glm::dvec3& v) { return above ? v[k] >= bound : v[k] <= bound; };
  for (size_t i = 0; i < poly.size(); ++i) {
    const glm::dvec3 &a = poly[i], &b = poly[(i + 1) % poly.size()];
    if (inside(a)) out.push_back(a);
    if (inside(a) != inside(b)) {
      const double s = (bound - a[k]) / (b[k] - a[k]);
      glm::dvec3 v = a + s * (b - a);
      v[k] = bound;
      out.push_back(v);
    }
  }
  poly.swap(out);
}

// The point of the closed triangle inside the unit cell at `lo` nearest the cell's centre; false
// when clipping leaves nothing (the triangle only grazes the cell).
bool sampleInCell(const Tri& t, const glm::dvec3& lo, glm::dvec3& out) {
  const glm::dvec3 hi = lo + 1.0, centre = lo + 0.5;
  const glm::dvec3 p = closestOnTriangle(centre, t);
  if (glm::all(glm::greaterThanEqual(p, lo)) && glm::all(glm::lessThanEqual(p, hi))) {
    out = p;
    return true;
  }
  // The nearest point of the triangle lies outside: clip it to the cell (a convex polygon) and
  // take the polygon's nearest point, on its plane or on an edge.
  thread_local std::vector<glm::dvec3> poly, scratch;
  poly.assign(t.begin(), t.end());
  for (int k = 0; k < 3 && !poly.empty(); ++k) {
    clipAxis(poly, k, lo[k], true, scratch);
    if (!poly.empty()) clipAxis(poly, k, hi[k], false, scratch);
  }
  if (poly.empty()) return false;
  const glm::dvec3 n = glm::cross(t[1] - t[0], t[2] - t[0]);
  const double n2 = glm::dot(n, n);
  if (poly.size() >= 3 && n2 > 0.0) {
    const glm::dvec3 q = centre - n * (glm::dot(n, centre - poly[0]) / n2);
    bool inside = true;
    for (size_t i = 0; i < poly.size() && inside; ++i)
      inside = glm::dot(glm::cross(poly[(i + 1) % poly.size()] - poly[i], q - poly[i]), n) >= 0.0;
    if (inside) {
      out = glm::clamp(q, lo, hi);
      return true;
    }
  }
  double best = INFINITY;
  for (size_t i = 0; i < poly.size(); ++i) {
    const glm::dvec3 c = closestOnSegment(centre, poly[i], poly[(i + 1) % poly.size()]);
    const double d2 = glm::dot(c - centre, c - centre);
    if (d2 < best) {
      best = d2;
      out = c;
    }
  }
  out = glm::clamp(out, lo, hi);
  return true;
}

Candidate makeCandidate(const glm::ivec3& cell, int grid, uint32_t tri, uint32_t weight,
                        const glm::dvec3& sample) {
  const glm::dvec3 d = sample - (glm::dvec3(cell) + 0.5);
  return {
      uint64_t(cell.x) + uint64_t(grid) * (uint64_t(cell.y) + uint64_t(grid) * uint64_t(cell.z)),
      tri, weight, glm::vec3(sample), float(glm::dot(d, d))};
}

// The cells of the bounding box that triangle t overlaps, column by column along its dominant
// axis (only the cells the plane crosses in each column are tested).
void rasterTriangle(const Tri& g, uint32_t tri, int grid, std::vector<Candidate>& out) {
  glm::ivec3 lo, hi;
  for (int k = 0; k < 3; ++k) {
    const double mn = std::min({g[0][k], g[1][k], g[2][k]}),
                 mx = std::max({g[0][k], g[1][k], g[2][k]});
    lo[k] = std::clamp(int(std::floor(mn)), 0, grid - 1);
    hi[k] = std::clamp(int(std::floor(mx)), 0, grid - 1);
  }
  const glm::dvec3 n = glm::cross(g[1] - g[0], g[2] - g[0]);
  const glm::dvec3 an = glm::abs(n);
  const int w = an.x >= an.y && an.x >= an.z ? 0 : an.y >= an.z ? 1 : 2;
  const int a = (w + 1) % 3, b = (w + 2) % 3;
  const double planeD = glm::dot(n, g[0]);
  glm::ivec3 c;
  glm::dvec3 sample;
  for (c[a] = lo[a]; c[a] <= hi[a]; ++c[a])
    for (c[b] = lo[b]; c[b] <= hi[b]; ++c[b]) {
      int k0 = lo[w], k1 = hi[w];
      if (an[w] > 0.0) {  // the plane's w over the column's four corners
        double wmin = INFINITY, wmax = -INFINITY;
        for (int corner = 0; corner < 4; ++corner) {
          const double ua = c[a] + (corner & 1), ub = c[b] + (corner >> 1);
          const double wv = (planeD - n[a] * ua - n[b] * ub) / n[w];
          wmin = std::min(wmin, wv);
          wmax = std::max(wmax, wv);
        }
        k0 = std::max(k0, int(std::floor(std::max(wmin, -1.0))));
        k1 = std::min(k1, int(std::floor(std::min(wmax, double(grid)))));
      }
      for (c[w] = k0; c[w] <= k1; ++c[w]) {
        const glm::dvec3 cl(c);
        if (!triBoxOverlap(Bounds{cl, cl + 1.0}, g[0], g[1], g[2])) continue;
        if (sampleInCell(g, cl, sample)) out.push_back(makeCandidate(c, grid, tri, 1, sample));
      }
    }
}

bool byCellTriangle(const Candidate& x, const Candidate& y) {
  return x.cell < y.cell || (x.cell == y.cell && x.triangle < y.triangle);
}

// Candidates of the same (cell, triangle) as one: weights summed, the sample nearest the centre
// kept (the first of equals: the input order decides, which is fixed).
void mergeSameTriangle(std::vector<Candidate>& c) {
  std::stable_sort(c.begin(), c.end(), byCellTriangle);
  size_t out = 0;
  for (size_t i = 0; i < c.size();) {
    Candidate m = c[i];
    size_t j = i + 1;
    for (; j < c.size() && c[j].cell == m.cell && c[j].triangle == m.triangle; ++j) {
      m.weight += c[j].weight;
      if (c[j].dist2 < m.dist2) {
        m.sample = c[j].sample;
        m.dist2 = c[j].dist2;
      }
    }
    c[out++] = m;
    i = j;
  }
  c.resize(out);
}

// The 26 shot directions: the faces, edges and corners of the cube.
std::vector<glm::dvec3> shotDirections() {
  std::vector<glm::dvec3> dirs;
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if (x || y || z) dirs.push_back(glm::normalize(glm::dvec3(x, y, z)));
  return dirs;
}

// One orthographic shot along `dir` (the view looks along +dir): the native z-buffer's ID buffer
// at two pixels per cell, each covered pixel turned into the exact point of its triangle.
std::vector<Candidate> shoot(const Mesh& mesh, const Domain& d, int grid, const glm::dvec3& dir) {
  constexpr double kPitch = 0.5;  // grid units per pixel
  const glm::dvec3 centre(0.5 * grid);
  const double h = 0.5 * std::sqrt(3.0) * grid;  // the cube's half diagonal
  const int size = int(std::ceil(2.0 * h / kPitch)) + 2;
  const glm::dvec3 helper = std::abs(dir.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 e1 = glm::normalize(glm::cross(dir, helper)), e2 = glm::cross(e1, dir);
  // The rasterizer interpolates 1 / depth across the screen; orthographic depth D is affine, so
  // vertices get depth 1 / (far - D): the nearest fragment keeps the smallest stored value.
  const double far = 4.0 * h + 1.0;
  Framebuffer fb(size, size);
  for (uint32_t t = 0; t < mesh.size(); ++t) {
    const Tri g = gridTriangle(mesh, t, d, grid);
    ScreenVertex v[3];
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 u = g[size_t(k)] - centre;
      v[k] = {0.5 * size + glm::dot(u, e1) / kPitch, 0.5 * size - glm::dot(u, e2) / kPitch,
              1.0 / (far - (glm::dot(u, dir) + h))};
    }
    RasterTriangle rt;
    if (setupTriangle(v, t, size, size, rt)) rasterizeTriangle(rt, 0, size, nullptr, INFINITY, fb);
  }
  std::vector<Candidate> out;
  for (int py = 0; py < size; ++py)
    for (int px = 0; px < size; ++px) {
      const uint64_t id = fb.id[fb.index(px, py)];
      if (id == kNoId) continue;
      const Tri g = gridTriangle(mesh, uint32_t(id), d, grid);
      const glm::dvec3 n = glm::cross(g[1] - g[0], g[2] - g[0]);
      const double nd = glm::dot(n, dir);
      if (nd == 0.0) continue;
      const glm::dvec3 o =
          centre + (px + 0.5 - 0.5 * size) * kPitch * e1 - (py + 0.5 - 0.5 * size) * kPitch * e2;
      const glm::dvec3 p =
          glm::clamp(o + glm::dot(n, g[0] - o) / nd * dir, glm::dvec3(0.0), glm::dvec3(grid));
      const glm::ivec3 cell =
          glm::clamp(glm::ivec3(glm::floor(p)), glm::ivec3(0), glm::ivec3(grid - 1));
      out.push_back(makeCandidate(cell, grid, uint32_t(id), 1, p));
    }
  mergeSameTriangle(out);
  return out;
}

glm::dvec3 rgb(Rgba8 c) {
  return {double(channel(c, 0)), double(channel(c, 1)), double(channel(c, 2))};
}

bool coloursClose(Rgba8 a, Rgba8 b) {
  for (int k = 0; k < 3; ++k)
    if (std::abs(int(channel(a, k)) - int(channel(b, k))) > kSplitColour) return false;
  return true;
}

struct Merged {
  std::vector<Surfel> surfels;
  std::vector<uint32_t> triangles;
  uint64_t cells = 0, splitCells = 0;
};

class CellMerger {
 public:
  CellMerger(const Mesh& mesh, const OctahedralNormals& normals, const CollectorLayout& layout,
             int grid, bool split)
      : mesh_(mesh),
        normals_(normals),
        layout_(layout),
        grid_(grid),
        split_(split),
        cosSplit_(std::cos(kSplitDegrees * 3.14159265358979323846 / 180.0)) {}

  // One cell's candidates [first, last) into one or two surfels.
  void mergeCell(const Candidate* first, const Candidate* last, Merged& out) const {
    const Candidate* rep = nearest(first, last);
    std::vector<const Candidate*> other;
    std::vector<const Candidate*> mine;
    for (const Candidate* c = first; c != last; ++c)
      (!split_ || similar(*c, *rep) ? mine : other).push_back(c);
    emit(*rep, mine, out);
    ++out.cells;
    if (!other.empty()) {
      const Candidate* rep2 = other.front();
      for (const Candidate* c : other)
        if (c->dist2 < rep2->dist2) rep2 = c;
      emit(*rep2, other, out);
      ++out.splitCells;
    }
  }

 private:
  // The candidate nearest the cell's centre (the first of equals: candidates are sorted by
  // triangle, so the smaller triangle).
  static const Candidate* nearest(const Candidate* first, const Candidate* last) {
    const Candidate* best = first;
    for (const Candidate* c = first + 1; c != last; ++c)
      if (c->dist2 < best->dist2) best = c;
    return best;
  }

  bool similar(const Candidate& c, const Candidate& rep) const {
    return glm::dot(mesh_.normal(c.triangle), mesh_.normal(rep.triangle)) >= cosSplit_ &&
           coloursClose(mesh_.color(c.triangle), mesh_.color(rep.triangle));
  }

  // A surfel: the members' weighted mean normal and colour, at the representative's sample.
  void emit(const Candidate& rep, const std::vector<const Candidate*>& members, Merged& out) const {
    glm::dvec3 n(0.0), colour(0.0);
    double w = 0.0;
    for (const Candidate* c : members) {
      n += double(c->weight) * glm::dvec3(mesh_.normal(c->triangle));
      colour += double(c->weight) * rgb(mesh_.color(c->triangle));
      w += double(c->weight);
    }
    // Opposite normals cancel (a sheet seen from both sides, merged by --collisions average):
    // the representative's normal then stands for the cell.
    if (!(glm::length(n) > 1e-6 * w)) n = glm::dvec3(mesh_.normal(rep.triangle));
    Surfel s;
    const uint32_t per = layout_.lattice() / uint32_t(grid_);  // lattice steps per cell
    const uint64_t g = uint64_t(grid_);
    const uint32_t cell[3] = {uint32_t(rep.cell % g), uint32_t(rep.cell / g % g),
                              uint32_t(rep.cell / (g * g))};
    uint32_t* q[3] = {&s.x, &s.y, &s.z};
    for (int k = 0; k < 3; ++k) {
      const double u = std::floor(double(rep.sample[k]) * double(per));
      *q[k] = uint32_t(std::clamp(u, double(cell[k] * per), double(cell[k] * per + per - 1)));
    }
    s.normal = normals_.encode(n);
    const glm::dvec3 mean = colour / w;
    s.colour = encodeColour(mean.r, mean.g, mean.b, layout_.colourBits);
    out.surfels.push_back(s);
    out.triangles.push_back(rep.triangle);
  }

  const Mesh& mesh_;
  const OctahedralNormals& normals_;
  CollectorLayout layout_;
  int grid_;
  bool split_;
  double cosSplit_;
};

Merged mergeCells(const std::vector<Candidate>& c, const Mesh& mesh,
                  const OctahedralNormals& normals, const CollectorLayout& layout, int grid,
                  bool split) {
  const CellMerger merger(mesh, normals, layout, grid, split);
  Merged out;
  for (size_t i = 0; i < c.size();) {
    size_t j = i + 1;
    while (j < c.size() && c[j].cell == c[i].cell) ++j;
    merger.mergeCell(c.data() + i, c.data() + j, out);
    i = j;
  }
  return out;
}

int log2Exact(uint32_t v) {
  int l = 0;
  while ((1u << l) < v) ++l;
  return l;
}

}  // namespace

std::vector<Candidate> rasterCandidates(const Mesh& mesh, const Domain& d, int grid, int threads) {
  std::vector<std::vector<Candidate>> parts(size_t(std::max(threads, 1)));
#pragma omp parallel num_threads(std::max(threads, 1))
  {
    std::vector<Candidate>& mine = parts[size_t(omp_get_thread_num())];
#pragma omp for schedule(dynamic, 64)
    for (int64_t t = 0; t < int64_t(mesh.size()); ++t)
      rasterTriangle(gridTriangle(mesh, uint32_t(t), d, grid), uint32_t(t), grid, mine);
  }
  std::vector<Candidate> all;
  for (auto& p : parts) all.insert(all.end(), p.begin(), p.end());
  // (cell, triangle) pairs are unique here, so the sorted order is the same for any threads.
  std::sort(all.begin(), all.end(), byCellTriangle);
  return all;
}

std::vector<Candidate> shotCandidates(const Mesh& mesh, const Domain& d, int grid, int threads) {
  const std::vector<glm::dvec3> dirs = shotDirections();
  std::vector<std::vector<Candidate>> shots(dirs.size());
#pragma omp parallel for schedule(dynamic, 1) num_threads(std::max(threads, 1))
  for (size_t i = 0; i < dirs.size(); ++i) shots[i] = shoot(mesh, d, grid, dirs[i]);
  std::vector<Candidate> all;
  for (auto& s : shots) {
    all.insert(all.end(), s.begin(), s.end());
    std::vector<Candidate>().swap(s);
  }
  mergeSameTriangle(all);  // stable: shots in direction order decide ties
  return all;
}

SurfelLevel surfelize(const Mesh& mesh, const OctahedralNormals& normals,
                      const SurfelizeParams& p) {
  const CollectorLayout layout = CollectorLayout::of(p.quality);
  if (p.grid < 1 || uint32_t(p.grid) > layout.lattice() || (p.grid & (p.grid - 1)) != 0)
    throw std::invalid_argument("surfelize: grid must be a power of two up to the lattice");
  if (normals.levels() != layout.normalLevels)
    throw std::invalid_argument("surfelize: normal quantizer does not match the collector");
  Stopwatch clock;
  SurfelLevel level;
  level.grid = p.grid;
  level.domain = Domain::around(mesh);
  const std::vector<Candidate> c = p.method == Surfelizer::kRaster
                                       ? rasterCandidates(mesh, level.domain, p.grid, p.threads)
                                       : shotCandidates(mesh, level.domain, p.grid, p.threads);
  const Merged m = mergeCells(c, mesh, normals, layout, p.grid, p.split);
  const int shift =
      std::min(log2Exact(layout.lattice() / uint32_t(p.grid)), layout.positionBits - 4);
  level.collector = SurfelCollector(p.quality, shift, m.surfels, m.triangles);
  level.cells = m.cells;
  level.splitCells = m.splitCells;
  level.seconds = clock.seconds();
  return level;
}

}  // namespace lzb::surfels
