#pragma once
// sqrt(5) adaptive sampling of one placement of a procedural object (section 3.1): each root of
// the initial grid grows a tree of samples, refined where the undersampling factor F > 1.
//
// The factor: a sample of level i stands for the lattice cell spanned by u_i and v_i around it.
// Their images on the surface, a = p(uv + u_i) - p(uv) and b = p(uv + v_i) - p(uv) (finite
// differences at the lattice's own scale, so steep displacement counts as the paper's 1 / cos(alpha)
// does), are projected to the image at the sample's depth; F = max(|a'|, |b'|)^2 / A'min. The
// paper's eq. (5), F = A'_d / A'min with A'_d = A cos(beta) / (cos(alpha) d^2) (times the focal
// length in pixels squared), is the area |a' x b'| of the same projected cell, never more than
// this F; the longer side is used because at grazing angles the area shrinks with cos(beta) while
// the spacing along the other direction does not, which leaves holes between the samples.
//
// Refinement stops at level `levels` (F is then reported as unmet), and is skipped for samples
// whose descendants (within 1.5 max(|a|, |b|) of them) lie outside the view frustum.
#include <cstdint>
#include <algorithm>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "src/core/camera.hpp"
#include "src/core/procedural.hpp"
#include "src/sqrt5/lattice.hpp"
#include "src/sqrt5/sector.hpp"

namespace lzb::sqrt5 {

// One placement of a procedural object as one camera sees it. The lattice's unit square is the
// object's own (u, v) square, or a terrain's sector (sector.hpp).
struct ProceduralView {
  const ProceduralSurface* surface = nullptr;
  const Sector* sector = nullptr;
  glm::dmat4 toCamera{1.0};  // node frame -> camera space (x right, y up, looking down -z)
  uint64_t idBase = 0;
  double pixelScale = 1.0, cx = 0.0, cy = 0.0, width = 0.0, height = 0.0;
  double nearPlane = 0.1, farPlane = 1e30;
  double amin = 0.5;
  int levels = 12;

  static ProceduralView make(const ProceduralSurface& surface, const Sector* sector,
                             const glm::dmat4& world, uint64_t idBase, const Camera& camera,
                             double amin, int levels);
  // The object's own (u, v) of a lattice point.
  glm::dvec2 surfaceUv(const glm::dvec2& uv) const {
    return sector ? sector->terrainUv(sector->base(uv)) : uv;
  }
  // Whether the lattice point is on the object (a sector reaches beyond the terrain's extent).
  bool onSurface(const glm::dvec2& uv) const { return !sector || Sqrt5Lattice::inside(surfaceUv(uv)); }
  // The surface point at lattice point uv (node frame); beyond a terrain's extent, its smooth
  // continuation.
  glm::dvec3 nodePoint(const glm::dvec2& uv) const {
    const glm::dvec2 s = surfaceUv(uv);
    return surface->spec.position(s.x, s.y);
  }
  // The same in camera space, with z the view depth (the splatting convention).
  glm::dvec3 point(const glm::dvec2& uv) const { return toView(nodePoint(uv)); }
  // A node-frame point in camera space.
  glm::dvec3 toView(const glm::dvec3& node) const {
    const glm::dvec4 c = toCamera * glm::dvec4(node, 1.0);
    return {c.x, c.y, -c.z};
  }
  uint64_t id(const glm::dvec2& uv) const {
    const glm::dvec2 s = surfaceUv(uv);
    return idBase + surface->triangleAt(s.x, s.y);
  }
  // Whether the sample at uv (point c) of `level` must be refined.
  bool undersampled(const glm::dvec2& uv, const glm::dvec3& c, const Sqrt5Lattice& lattice,
                    int level) const {
    if (sector && !mayReachSurface(uv, lattice, level)) return false;
    return undersampledBy(c, point(uv + lattice.u(level)) - c, point(uv + lattice.v(level)) - c);
  }
  // Whether a sector sample's descendants (within 1.5 spawning vectors) can reach the terrain's
  // extent: samples beyond it are not drawn, and refining them far from it only costs.
  bool mayReachSurface(const glm::dvec2& uv, const Sqrt5Lattice& lattice, int level) const {
    const glm::dvec2 s = surfaceUv(uv);
    const double r = 1.5 * std::max(glm::length(surfaceUv(uv + lattice.u(level)) - s),
                                    glm::length(surfaceUv(uv + lattice.v(level)) - s));
    return s.x >= -r && s.x <= 1.0 + r && s.y >= -r && s.y <= 1.0 + r;
  }
  // The same from the images a, b of the spawning vectors (camera space).
  bool undersampledBy(const glm::dvec3& c, const glm::dvec3& a, const glm::dvec3& b) const;
  // The projected length (pixels) of vector e at camera-space point c.
  double projectedLength(const glm::dvec3& c, const glm::dvec3& e) const;
};

struct RefineCounts {
  uint64_t roots = 0, generated = 0, refined = 0, drawn = 0, atLevelBound = 0;
  int deepest = 0;
  void merge(const RefineCounts& o);
};

// Grows the tree of `root` (a level-0 point) and calls sink(point, id, level) for every sample
// it leaves on the surface (the samples not refined further, each once).
template <class Sink>
void refineTree(const ProceduralView& view, const Sqrt5Lattice& lattice, const glm::dvec2& root,
                std::vector<std::pair<glm::dvec2, int>>& stack, std::vector<glm::dvec2>& kids,
                RefineCounts& counts, Sink&& sink) {
  ++counts.roots;
  stack.clear();
  stack.emplace_back(root, 0);
  while (!stack.empty()) {
    auto [uv, level] = stack.back();
    stack.pop_back();
    const glm::dvec3 c = view.point(uv);
    ++counts.generated;
    // Refined: the four children (and boundary children) go on, the self copy stays here.
    while (view.undersampled(uv, c, lattice, level)) {
      if (level >= view.levels) {
        ++counts.atLevelBound;
        break;
      }
      kids.clear();
      lattice.children(uv, level, kids);
      ++counts.refined;
      ++level;
      for (const glm::dvec2& k : kids) stack.emplace_back(k, level);
    }
    counts.deepest = std::max(counts.deepest, level);
    if (!view.onSurface(uv)) continue;
    ++counts.drawn;
    sink(c, view.id(uv), level);
  }
}

// The initial grid's side n (step 1 / n) of a placement by eq. (3): n_s = A / (A'min d~^2) samples
// for the object's area A (world units, times the focal length in pixels squared), all assumed at
// distance d~ (the eye's distance to the bounds' centre, at least the near plane), n = sqrt(n_s)
// rounded up to the ladder 2^(k/4) (so that a moving camera keeps its grid, and its cached forests,
// until d~ changes by 19 %), within [1, kMaxInitialSide].
constexpr int kMaxInitialSide = 1024;
int initialSide(double worldArea, double distance, double pixelScale, double amin);

}  // namespace lzb::sqrt5
