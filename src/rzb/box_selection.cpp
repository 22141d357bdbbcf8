#include "src/rzb/box_selection.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace lzb::rzb {

namespace {

// One instance level of the traversal: where a tree's frame lies.
struct InstanceLevel {
  const DistributionTree* tree;
  Affine toWorld, toCamera;
  std::array<Plane, 6> planes;  // the view frustum in the tree's frame (normals not unit)
  glm::dvec3 eyeLocal;
  double areaScale, stretch;
  uint64_t idBase;
};

class Selector {
 public:
  Selector(const SampleScene& scene, const Camera& camera, const SelectParams& params,
           const SampleStream& rounding, Selection& out)
      : scene_(scene), camera_(camera), params_(params), rounding_(rounding), out_(out),
        frustum_(camera.frustum()),
        worldToCam_(worldToCamera(camera.position(), camera.right(), camera.up(), camera.forward())),
        near_(camera.nearPlane()), pixelScale_(camera.pixelsPerUnitAt(1.0)) {}

  void run() {
    InstanceLevel root = level(scene_.root(), Affine{}, 1.0, 1.0, 0);
    visitTree(root);
  }

 private:
  InstanceLevel level(const DistributionTree& tree, const Affine& toWorld, double areaScale, double stretch,
              uint64_t idBase) const {
    InstanceLevel l{&tree, toWorld, worldToCam_ * toWorld, {}, {}, areaScale, stretch, idBase};
    const glm::dmat3 at = glm::transpose(toWorld.a);
    for (size_t k = 0; k < 6; ++k) {
      const Plane& p = frustum_.planes[k];
      l.planes[k] = Plane{at * p.n, glm::dot(p.n, toWorld.t) + p.d};
    }
    l.eyeLocal = glm::inverse(toWorld.a) * (camera_.position() - toWorld.t);
    return l;
  }

  // 0: outside; else the mask of planes the box still crosses (bit k: plane k).
  static unsigned cull(const InstanceLevel& l, const Bounds& b, unsigned mask, bool& outside) {
    unsigned next = 0;
    outside = false;
    for (unsigned k = 0; k < 6; ++k) {
      if (!(mask & (1u << k))) continue;
      const Plane& p = l.planes[k];
      const glm::dvec3 pv{p.n.x >= 0 ? b.hi.x : b.lo.x, p.n.y >= 0 ? b.hi.y : b.lo.y,
                          p.n.z >= 0 ? b.hi.z : b.lo.z};
      const glm::dvec3 nv{p.n.x >= 0 ? b.lo.x : b.hi.x, p.n.y >= 0 ? b.lo.y : b.hi.y,
                          p.n.z >= 0 ? b.lo.z : b.hi.z};
      if (p.distance(pv) < 0.0) {
        outside = true;
        return 0;
      }
      if (p.distance(nv) < 0.0) next |= 1u << k;
    }
    return next;
  }

  // View depth range of a node-frame box: depth is affine in the position.
  static void depthRange(const InstanceLevel& l, const Bounds& b, double& zmin, double& zmax) {
    const glm::dvec3 f{l.toCamera.a[0][2], l.toCamera.a[1][2], l.toCamera.a[2][2]};
    const glm::dvec3 c = b.center(), h = 0.5 * b.extent();
    const double zc = glm::dot(f, c) + l.toCamera.t.z;
    const double zr = std::abs(f.x) * h.x + std::abs(f.y) * h.y + std::abs(f.z) * h.z;
    zmin = zc - zr;
    zmax = zc + zr;
  }

  void visitTree(const InstanceLevel& l) {
    for (const DistributionTree::ClassRoot& c : l.tree->classes()) visitNode(l, c.root, 0x3f);
  }

  void visitNode(const InstanceLevel& l, uint32_t n, unsigned mask) {
    if (out_.aborted) return;
    if (++out_.nodesVisited > params_.maxNodes) {
      out_.aborted = true;
      return;
    }
    const DistributionTree& tree = *l.tree;
    const DistributionNode& t = tree.node(n);
    if (!(t.area > 0.0) || t.tight.empty()) return;
    bool outside;
    mask = cull(l, t.tight, mask, outside);
    if (outside) return;
    double zmin, zmax;
    depthRange(l, t.tight, zmin, zmax);
    const double zc = std::max(zmin, near_);
    if (zmax <= zc * std::sqrt(params_.eps)) {
      emit(l, n, Part::kSubtree, zmin, zmax);
      return;
    }
    for (uint32_t c : t.child)
      if (c != kNone) visitNode(l, c, mask);
    if (t.ownTriArea > 0.0) emit(l, n, Part::kOwnTriangles, zmin, zmax);
    tree.forEachOwnInstance(n, [&](uint32_t i) { enterInstance(l, i, mask); });
  }

  void enterInstance(const InstanceLevel& l, uint32_t i, unsigned mask) {
    const DistributionTree& tree = *l.tree;
    if (!tree.instanceLive(i) || !(tree.instanceArea(i) > 0.0)) return;
    const InstanceRef& r = tree.instance(i);
    bool outside;
    cull(l, r.bounds, mask, outside);
    if (outside || !r.child) return;
    visitTree(level(*r.child, l.toWorld * r.transform, l.areaScale * r.areaScale,
                    l.stretch * r.stretch, l.idBase + r.idOffset));
  }

  void emit(const InstanceLevel& l, uint32_t n, Part part, double zmin, double zmax) {
    const DistributionTree& tree = *l.tree;
    SelectedBox b;
    b.tree = &tree;
    b.node = n;
    b.part = part;
    b.idBase = l.idBase;
    b.key = hashCombine(hashCombine(hashCombine(tree.sceneNode(), n), uint64_t(part)), l.idBase);
    b.toWorld = l.toWorld;
    b.toCamera = l.toCamera;
    b.eyeLocal = l.eyeLocal;
    b.zmin = std::max(zmin, near_);
    b.zmax = zmax;
    b.ppu = pixelScale_ / b.zmin;
    b.areaScale = l.areaScale;
    b.stretch = l.stretch;
    b.area = l.areaScale * tree.partArea(n, part);
    const double ppu2 = b.ppu * b.ppu;
    const double maxTriPx = l.areaScale * double(tree.partMaxTri(n, part)) * ppu2;
    if (maxTriPx > params_.fallbackPx) {
      b.fallback = true;
      uint64_t entries = 0;
      std::vector<uint32_t> inner;
      tree.forEachEntry(n, part, [&](uint32_t r) {
        const EntryRec& e = tree.rec(r);
        if (e.instance())
          inner.push_back(e.index());
        else
          ++entries;
      });
      b.entries = entries;
      ++out_.fallbackBoxes;
      out_.fallbackEntries += entries;
      if (entries) out_.boxes.push_back(b);
      for (uint32_t i : inner) enterInstance(l, i, 0x3f);
      return;
    }
    b.expected = b.area * ppu2 * params_.samplesPerPixel;
    if (b.expected > params_.maxBoxSamples) {
      b.expected = params_.maxBoxSamples;
      ++out_.cappedBoxes;
    }
    // Stochastic rounding keyed by the box: unbiased, and the same on every rank.
    const double whole = std::floor(b.expected);
    const auto r = rounding_.draw(b.key, 0, kBoxRounding);
    b.samples = uint64_t(whole) + (unit53(r[0], r[1]) < b.expected - whole ? 1 : 0);
    b.entries = b.samples;
    ++out_.sampleBoxes;
    out_.samples += b.samples;
    out_.projectedArea += b.area * ppu2;
    out_.boxes.push_back(b);
  }

  const SampleScene& scene_;
  const Camera& camera_;
  const SelectParams& params_;
  const SampleStream& rounding_;
  Selection& out_;
  Frustum frustum_;
  Affine worldToCam_;
  double near_, pixelScale_;
};

}  // namespace

Selection selectBoxes(const SampleScene& scene, const Camera& camera, const SelectParams& params,
                      const SampleStream& rounding) {
  Selection out;
  Selector(scene, camera, params, rounding, out).run();
  return out;
}

}  // namespace lzb::rzb
