// DistributionTree: static build, sampling by the distribution list, and the accessors shared with
// the dynamic updates (distribution_tree_dynamic.cpp).
#include "src/rzb/distribution_tree.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "src/core/error.hpp"

namespace lzb::rzb {

namespace {

constexpr double kBelowOne = 1.0 - 0x1p-53;

int octant(const glm::dvec3& center, const glm::dvec3& p) {
  return (p.x >= center.x ? 1 : 0) | (p.y >= center.y ? 2 : 0) | (p.z >= center.z ? 4 : 0);
}

glm::dvec3 childCenter(const glm::dvec3& center, double half, int o) {
  const double q = 0.5 * half;
  return {center.x + (o & 1 ? q : -q), center.y + (o & 2 ? q : -q), center.z + (o & 4 ? q : -q)};
}

// A cube around b (half side > 0 even for flat content).
void cubeAround(const Bounds& b, glm::dvec3& center, double& half) {
  center = b.center();
  const glm::dvec3 e = b.extent();
  half = 0.5 * std::max({e.x, e.y, e.z});
  half = std::max(half * (1.0 + 1e-9), 1e-30 + 1e-12 * glm::length(center));
}

}  // namespace

double triangleArea(const Mesh& mesh, uint32_t t) {
  const glm::dvec3 a(mesh.vertex(t, 0)), b(mesh.vertex(t, 1)), c(mesh.vertex(t, 2));
  return 0.5 * glm::length(glm::cross(b - a, c - a));
}

DistributionTree::DistributionTree(const Scene& scene, uint32_t node,
                                   std::span<const uint32_t> triangles, bool allTriangles,
                                   std::vector<InstanceRef> instances,
                                   const DistributionParams& params)
    : scene_(&scene),
      mesh_(&scene.nodes[node].mesh),
      sceneNode_(node),
      params_(params),
      logRatio_(std::log(params.areaRatio)),
      instances_(std::move(instances)) {
  require(params.areaRatio >= 2.0 && params.areaRatio <= 64.0, "--area-ratio",
          "must be in [2, 64]");
  const uint32_t meshSize = uint32_t(mesh_->size());
  triNode_.assign(meshSize, kNone);
  triRec_.assign(meshSize, kNone);
  std::vector<Item> items;
  const size_t nTri = allTriangles ? meshSize : triangles.size();
  items.reserve(nTri + instances_.size());
  for (size_t k = 0; k < nTri; ++k) {
    const uint32_t t = allTriangles ? uint32_t(k) : triangles[k];
    if (t >= meshSize) throw std::out_of_range("DistributionTree: triangle index past the mesh");
    Item it = triangleItem(t);
    if (it.area > 0.0 && std::isfinite(it.area)) items.push_back(it);
  }
  instArea_.resize(instances_.size());
  instMaxTri_.resize(instances_.size());
  instNode_.assign(instances_.size(), kNone);
  instRec_.assign(instances_.size(), kNone);
  for (uint32_t i = 0; i < instances_.size(); ++i) hot_.push_back(makeHot(i));
  for (uint32_t i = 0; i < instances_.size(); ++i) {
    const InstanceRef& r = instances_[i];
    instArea_[i] = r.child ? r.areaScale * r.child->totalArea() : 0.0;
    instMaxTri_[i] = r.child ? float(r.areaScale * r.child->maxTriArea()) : 0.0f;
    if (instArea_[i] > 0.0 && std::isfinite(instArea_[i]) && !r.bounds.empty())
      items.push_back(instanceItem(i));
  }
  buildStatic(items);
}

InstanceHot DistributionTree::makeHot(uint32_t i) {
  const InstanceRef& r = instances_[i];
  anyLinear_ = anyLinear_ || !r.translationOnly;
  return InstanceHot{r.child, r.transform.t, r.idOffset, float(r.detSign),
                     r.translationOnly ? 0u : i + 1};
}

DistributionTree::Item DistributionTree::triangleItem(uint32_t t) const {
  Item it;
  for (int k = 0; k < 3; ++k) it.box.extend(glm::dvec3(mesh_->vertex(t, k)));
  it.area = triangleArea(*mesh_, t);
  it.maxTri = float(it.area);
  it.cls = classOf(it.area);
  it.ref = t;
  return it;
}

DistributionTree::Item DistributionTree::instanceItem(uint32_t i) const {
  Item it;
  it.box = instances_[i].bounds;
  it.area = instArea_[i];
  it.maxTri = instMaxTri_[i];
  it.cls = classOf(it.maxTri);
  it.ref = kInstanceBit | i;
  return it;
}

int DistributionTree::classOf(double maxTri) const {
  if (!(maxTri > 0.0)) return std::numeric_limits<int16_t>::min();
  const double c = std::floor(std::log(maxTri) / logRatio_);
  return int(std::clamp(c, -30000.0, 30000.0));
}

EntryRec DistributionTree::makeRec(const Item& item) const {
  EntryRec r{};
  r.ref = item.ref;
  if (!(item.ref & kInstanceBit)) {
    const glm::vec3 &a = mesh_->vertex(item.ref, 0), &b = mesh_->vertex(item.ref, 1),
                    &c = mesh_->vertex(item.ref, 2);
    r.v0 = a;
    r.e1 = b - a;
    r.e2 = c - a;
  }
  return r;
}

double DistributionTree::recArea(uint32_t r) const {
  const EntryRec& e = recs_[r];
  return e.instance() ? instArea_[e.index()] : triangleArea(*mesh_, e.ref);
}

bool DistributionTree::extContains(const glm::dvec3& center, double half, const Bounds& b) const {
  const double h = half * (1.0 + params_.extension);
  return b.lo.x >= center.x - h && b.lo.y >= center.y - h && b.lo.z >= center.z - h &&
         b.hi.x <= center.x + h && b.hi.y <= center.y + h && b.hi.z <= center.z + h;
}

uint32_t DistributionTree::newNode(const glm::dvec3& center, double half, int depth,
                                   uint32_t parent, int cls) {
  DistributionNode t;
  t.center = center;
  t.half = half;
  t.depth = uint8_t(std::min(depth, 255));
  t.parent = parent;
  t.cls = int16_t(cls);
  nodes_.push_back(t);
  return uint32_t(nodes_.size() - 1);
}

// ---------------------------------------------------------------------------------------------
// Static build

void DistributionTree::buildStatic(std::vector<Item>& items) {
  for (const Item& it : items) bounds_.extend(it.box);
  // Class by class in increasing class order (stable: ties keep the input order).
  std::vector<uint32_t> idx(items.size());
  for (uint32_t i = 0; i < idx.size(); ++i) idx[i] = i;
  std::stable_sort(idx.begin(), idx.end(),
                   [&](uint32_t a, uint32_t b) { return items[a].cls < items[b].cls; });
  std::vector<uint32_t> order, scratch(idx.size());
  order.reserve(items.size());
  size_t lo = 0;
  while (lo < idx.size()) {
    size_t hi = lo;
    Bounds b;
    while (hi < idx.size() && items[idx[hi]].cls == items[idx[lo]].cls)
      b.extend(items[idx[hi++]].box);
    glm::dvec3 center;
    double half;
    cubeAround(b, center, half);
    const uint32_t root = buildNode(items, idx, lo, hi, center, half, 0, kNone, order, scratch);
    classes_.push_back({items[idx[lo]].cls, root});
    lo = hi;
  }
  finishStatic(items, order);
}

uint32_t DistributionTree::buildNode(std::vector<Item>& items, std::vector<uint32_t>& idx,
                                     size_t lo, size_t hi, glm::dvec3 center, double half,
                                     int depth, uint32_t parent, std::vector<uint32_t>& order,
                                     std::vector<uint32_t>& scratch) {
  const int cls = items[idx[lo]].cls;
  std::array<size_t, 9> count{};
  auto bucketOf = [&](const Item& it) {
    const int o = octant(center, it.box.center());
    return extContains(childCenter(center, half, o), 0.5 * half, it.box) ? o : 8;
  };
  bool leaf = false;
  // Shortcuts: while everything goes to one child and nothing stays, descend without a node.
  for (;;) {
    const size_t n = hi - lo;
    if (n <= params_.leafEntries || depth >= params_.maxDepth) {
      leaf = true;
      break;
    }
    count.fill(0);
    for (size_t i = lo; i < hi; ++i) ++count[size_t(bucketOf(items[idx[i]]))];
    if (count[8] == n) {
      leaf = true;
      break;
    }
    int only = -1, nonEmpty = 0;
    for (int o = 0; o < 8; ++o)
      if (count[size_t(o)]) ++nonEmpty, only = o;
    if (count[8] == 0 && nonEmpty == 1) {
      center = childCenter(center, half, only);
      half *= 0.5;
      ++depth;
      continue;
    }
    break;
  }
  const uint32_t self = newNode(center, half, depth, parent, cls);
  nodes_[self].begin = order.size();
  size_t ownLo = lo;
  if (!leaf) {
    // Stable counting sort into the 8 children, then the node's own entries.
    std::array<size_t, 10> start{};
    start[0] = lo;
    for (size_t b = 0; b < 9; ++b) start[b + 1] = start[b] + count[b];
    std::array<size_t, 9> fill{};
    for (size_t b = 0; b < 9; ++b) fill[b] = start[b];
    std::copy(idx.begin() + lo, idx.begin() + hi, scratch.begin() + lo);
    for (size_t i = lo; i < hi; ++i) idx[fill[size_t(bucketOf(items[scratch[i]]))]++] = scratch[i];
    for (int o = 0; o < 8; ++o) {
      if (!count[size_t(o)]) continue;
      const uint32_t c = buildNode(items, idx, start[size_t(o)], start[size_t(o) + 1],
                                   childCenter(center, half, o), 0.5 * half, depth + 1, self, order,
                                   scratch);
      nodes_[self].child[size_t(o)] = c;
    }
    ownLo = start[8];
  }
  nodes_[self].ownBegin = order.size();
  for (size_t i = ownLo; i < hi; ++i)
    if (!(items[idx[i]].ref & kInstanceBit)) order.push_back(idx[i]);
  nodes_[self].instBegin = order.size();
  for (size_t i = ownLo; i < hi; ++i)
    if (items[idx[i]].ref & kInstanceBit) order.push_back(idx[i]);
  nodes_[self].end = order.size();
  return self;
}

void DistributionTree::finishStatic(const std::vector<Item>& items,
                                    const std::vector<uint32_t>& order) {
  const size_t n = order.size();
  recs_.resize(n);
  prefix_.resize(n);
  // Compensated (Neumaier) running sum: every prefix is right to about one rounding.
  double sum = 0.0, comp = 0.0, last = 0.0;
  for (size_t j = 0; j < n; ++j) {
    const Item& it = items[order[j]];
    recs_[j] = makeRec(it);
    const double a = it.area, t = sum + a;
    comp += std::abs(sum) >= std::abs(a) ? (sum - t) + a : (a - t) + sum;
    sum = t;
    last = std::max(last, sum + comp);
    prefix_[j] = last;
  }
  auto P = [&](uint64_t j) { return j ? prefix_[j - 1] : 0.0; };  // sum of [0, j)
  for (uint32_t k = 0; k < nodes_.size(); ++k) {
    DistributionNode& t = nodes_[k];
    t.area = P(t.end) - P(t.begin);
    t.ownTriArea = P(t.instBegin) - P(t.ownBegin);
    t.ownInstArea = P(t.end) - P(t.instBegin);
    for (uint64_t j = t.ownBegin; j < t.end; ++j) {
      const Item& it = items[order[j]];
      t.tight.extend(it.box);
      t.maxTri = std::max(t.maxTri, it.maxTri);
      if (!(it.ref & kInstanceBit)) {
        t.ownMaxTri = std::max(t.ownMaxTri, it.maxTri);
        triNode_[it.ref] = k;
        triRec_[it.ref] = uint32_t(j);
      } else {
        instNode_[it.ref & ~kInstanceBit] = k;
        instRec_[it.ref & ~kInstanceBit] = uint32_t(j);
      }
    }
  }
  // Children come after their parents (pre-order), so one backward pass aggregates.
  for (uint32_t k = uint32_t(nodes_.size()); k-- > 0;) {
    const DistributionNode& t = nodes_[k];
    if (t.parent == kNone) continue;
    DistributionNode& p = nodes_[t.parent];
    p.tight.extend(t.tight);
    p.maxTri = std::max(p.maxTri, t.maxTri);
  }
}

void DistributionTree::enableAlias() {
  wantAlias_ = true;
  buildAlias();
}

// Vose's alias method over the list's entry areas (deterministic: work lists in index order).
void DistributionTree::buildAlias() {
  const size_t n = prefix_.size();
  alias_.clear();
  if (n == 0 || !wantAlias_) return;
  alias_.assign(n, AliasSlot{1.0, 1.0, 0.0, 0, 0, 0});
  const double total = prefix_[n - 1];
  std::vector<double> scaled(n);
  std::vector<uint32_t> small, large;
  for (size_t j = 0; j < n; ++j) {
    scaled[j] = (prefix_[j] - (j ? prefix_[j - 1] : 0.0)) / total * double(n);
    (scaled[j] < 1.0 ? small : large).push_back(uint32_t(j));
  }
  while (!small.empty() && !large.empty()) {
    const uint32_t s = small.back(), l = large.back();
    small.pop_back();
    alias_[s] = AliasSlot{scaled[s], 1.0 / scaled[s], 1.0 / (1.0 - scaled[s]), l, 0, 0};
    scaled[l] = (scaled[l] + scaled[s]) - 1.0;
    if (scaled[l] < 1.0) {
      large.pop_back();
      small.push_back(l);
    }
  }
  // Left over (rounding): probability one.
  for (uint32_t j : small) alias_[j] = AliasSlot{1.0, 1.0, 0.0, j, 0, 0};
  for (uint32_t j : large) alias_[j] = AliasSlot{1.0, 1.0, 0.0, j, 0, 0};
  for (size_t j = 0; j < n; ++j) {
    alias_[j].keepRef = recs_[j].ref;
    alias_[j].altRef = recs_[alias_[j].alias].ref;
  }
}

double DistributionTree::totalArea() const {
  double a = 0.0;
  for (const ClassRoot& c : classes_) a += nodes_[c.root].area;
  return a;
}

float DistributionTree::maxTriArea() const {
  float m = 0.0f;
  for (const ClassRoot& c : classes_) m = std::max(m, nodes_[c.root].maxTri);
  return m;
}

TreeStats DistributionTree::stats() const {
  TreeStats s;
  s.nodes = nodes_.size();
  s.classes = classes_.size();
  for (uint32_t t : triNode_) s.triangles += t != kNone;
  for (uint32_t t : instNode_) s.instances += t != kNone;
  for (const DistributionNode& t : nodes_) s.depth = std::max(s.depth, int(t.depth));
  s.memoryBytes = nodes_.capacity() * sizeof(DistributionNode) +
                  prefix_.capacity() * sizeof(double) + recs_.capacity() * sizeof(EntryRec) +
                  instances_.capacity() * sizeof(InstanceRef) +
                  hot_.capacity() * sizeof(InstanceHot) + alias_.capacity() * sizeof(AliasSlot) +
                  (triNode_.capacity() + triRec_.capacity()) * sizeof(uint32_t);
  for (const DynOwn& d : dyn_)
    s.memoryBytes += (d.tris.capacity() + d.insts.capacity()) * 4 +
                     (d.triSum.capacity() + d.instSum.capacity()) * 8;
  return s;
}

// ---------------------------------------------------------------------------------------------
// Sampling

uint32_t DistributionTree::pickSlice(uint64_t b, uint64_t e, double u, double& rem,
                                     double& res) const {
  const double* P = prefix_.data();
  const double base = b ? P[b - 1] : 0.0, span = P[e - 1] - base;
  const double target = base + u * span;
  // Branchless search for the first j in [b, e) with P[j] > target (e - 1 if none).
  uint64_t lo = b, n = e - b;
  while (n > 1) {
    const uint64_t h = n >> 1;
    lo = P[lo + h - 1] <= target ? lo + h : lo;
    n -= h;
  }
  const double before = lo ? P[lo - 1] : 0.0, a = P[lo] - before;
  const double err = res * span + P[e - 1] * 0x1p-52;
  if (a > 0.0) {
    rem = std::clamp((target - before) / a, 0.0, kBelowOne);
    res = err / a;
  } else {
    rem = 0.5;
    res = 1.0;
  }
  return uint32_t(lo);
}

uint32_t DistributionTree::pickSums(const std::vector<uint32_t>& recs,
                                    const std::vector<double>& sums, double v, double& rem,
                                    double& res) {
  const size_t j = std::min(size_t(std::upper_bound(sums.begin(), sums.end(), v) - sums.begin()),
                            sums.size() - 1);
  const double before = j ? sums[j - 1] : 0.0, a = sums[j] - before;
  if (a > 0.0) {
    rem = std::clamp((v - before) / a, 0.0, kBelowOne);
    res = (res + sums.back() * 0x1p-52) / a;
  } else {
    rem = 0.5;
    res = 1.0;
  }
  return recs[j];
}

uint32_t DistributionTree::pick(uint32_t n, Part part, double u, double& rem, double& res) const {
  if (!nodes_[n].dirty) {
    uint64_t b, e;
    slice(n, part, b, e);
    return pickSlice(b, e, u, rem, res);
  }
  const double area = partArea(n, part);
  double err = res * area;
  const uint32_t r = pickDyn(n, part, u * area, rem, err);
  res = err;
  return r;
}

uint32_t DistributionTree::pickWhole(double u, double& rem, double& res) const {
  if (!dynamic_ && !alias_.empty()) {
    const double n = double(alias_.size()), x = u * n;
    const uint32_t i = uint32_t(std::min(x, n - 1.0));
    const double f = std::clamp(x - double(i), 0.0, kBelowOne);
    const AliasSlot& a = alias_[i];
    if (f < a.prob) {
      rem = std::min(f * a.keepScale, kBelowOne);
      res = res * n * a.keepScale;
      return i;
    }
    rem = std::min((f - a.prob) * a.altScale, kBelowOne);
    res = res * n * a.altScale;
    return a.alias;
  }
  if (!dynamic_) return pickSlice(0, prefix_.size(), u, rem, res);
  const double total = totalArea();
  double v = u * total, err = res * total;
  uint32_t last = kNone;
  for (const ClassRoot& c : classes_) {
    const double a = nodes_[c.root].area;
    if (a <= 0.0) continue;
    if (v < a) {
      const uint32_t r = pickDyn(c.root, Part::kSubtree, v, rem, err);
      res = err;
      return r;
    }
    v -= a;
    last = c.root;
  }
  const uint32_t r = pickDyn(last, Part::kSubtree, nodes_[last].area * kBelowOne, rem, err);
  res = err;
  return r;
}

// v: absolute position in [0, partArea(n, part)); res on entry: absolute error of v; on return:
// the relative resolution of rem.
uint32_t DistributionTree::pickDyn(uint32_t n, Part part, double v, double& rem,
                                   double& res) const {
  for (;;) {
    const DistributionNode& t = nodes_[n];
    const double area = partArea(n, part);
    if (!t.dirty) {
      uint64_t b, e;
      slice(n, part, b, e);
      double r = area > 0.0 ? res / area : 1.0;
      const uint32_t out = pickSlice(b, e, std::clamp(v / area, 0.0, kBelowOne), rem, r);
      res = r;
      return out;
    }
    if (part == Part::kSubtree) {
      uint32_t next = kNone, lastChild = kNone;
      for (uint32_t c : t.child) {
        if (c == kNone || nodes_[c].area <= 0.0) continue;
        if (v < nodes_[c].area) {
          next = c;
          break;
        }
        v -= nodes_[c].area;
        lastChild = c;
      }
      if (next != kNone) {
        n = next;
        continue;
      }
      const bool hasTri = t.ownTriArea > 0.0, hasInst = t.ownInstArea > 0.0;
      bool inTri = hasTri && v < t.ownTriArea;
      bool inInst = !inTri && hasInst;
      if (inInst) v = std::min(v - (hasTri ? t.ownTriArea : 0.0), t.ownInstArea * kBelowOne);
      if (!inTri && !inInst) {
        // Rounding ran past the end: take the last non-empty part.
        if (hasTri) {
          inTri = true;
          v = t.ownTriArea * kBelowOne;
        } else if (lastChild != kNone) {
          n = lastChild;
          v = nodes_[lastChild].area * kBelowOne;
          continue;
        } else {
          throw std::logic_error("DistributionTree::pick on an empty box");
        }
      }
      if (inInst) {
        if (t.dyn != kNone) return pickSums(dyn_[t.dyn].insts, dyn_[t.dyn].instSum, v, rem, res);
        double r = res / t.ownInstArea;
        const uint32_t out = pickSlice(t.instBegin, t.end, v / t.ownInstArea, rem, r);
        res = r;
        return out;
      }
    }
    v = std::min(v, t.ownTriArea * kBelowOne);
    if (t.dyn != kNone) return pickSums(dyn_[t.dyn].tris, dyn_[t.dyn].triSum, v, rem, res);
    double r = res / t.ownTriArea;
    const uint32_t out = pickSlice(t.ownBegin, t.instBegin, v / t.ownTriArea, rem, r);
    res = r;
    return out;
  }
}

}  // namespace lzb::rzb
