// DistributionTree dynamic updates (Wand et al. section 5.4, the distribution-tree variant): insert
// and remove triangles and instance entries along one root-to-node path, keeping the summed areas
// of every node on it right; compact() lays the static distribution list out again.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "src/rzb/distribution_tree.hpp"

namespace lzb::rzb {

namespace {

int octant(const glm::dvec3& center, const glm::dvec3& p) {
  return (p.x >= center.x ? 1 : 0) | (p.y >= center.y ? 2 : 0) | (p.z >= center.z ? 4 : 0);
}

glm::dvec3 childCenter(const glm::dvec3& center, double half, int o) {
  const double q = 0.5 * half;
  return {center.x + (o & 1 ? q : -q), center.y + (o & 2 ? q : -q), center.z + (o & 4 ? q : -q)};
}

}  // namespace

DistributionTree::DynOwn& DistributionTree::dynOwn(uint32_t n) {
  if (nodes_[n].dyn == kNone) {
    DynOwn d;
    const DistributionNode& t = nodes_[n];
    // A node created by an update has an empty static slice; others start from theirs.
    for (uint64_t j = t.ownBegin; j < t.instBegin; ++j) d.tris.push_back(uint32_t(j));
    for (uint64_t j = t.instBegin; j < t.end; ++j) d.insts.push_back(uint32_t(j));
    rebuildSums(d);
    dyn_.push_back(std::move(d));
    nodes_[n].dyn = uint32_t(dyn_.size() - 1);
  }
  return dyn_[nodes_[n].dyn];
}

void DistributionTree::rebuildSums(DynOwn& d) const {
  auto sums = [&](const std::vector<uint32_t>& recs, std::vector<double>& out) {
    out.resize(recs.size());
    double s = 0.0;
    for (size_t k = 0; k < recs.size(); ++k) out[k] = s += recArea(recs[k]);
  };
  sums(d.tris, d.triSum);
  sums(d.insts, d.instSum);
}

void DistributionTree::addOwn(uint32_t n, uint32_t rec, bool instance) {
  DynOwn& d = dynOwn(n);
  (instance ? d.insts : d.tris).push_back(rec);
  rebuildSums(d);
  const uint32_t idx = recs_[rec].index();
  if (instance) {
    instNode_[idx] = n;
    instRec_[idx] = rec;
  } else {
    triNode_[idx] = n;
    triRec_[idx] = rec;
  }
}

void DistributionTree::removeRec(uint32_t n, uint32_t rec, bool instance) {
  DynOwn& d = dynOwn(n);
  std::vector<uint32_t>& list = instance ? d.insts : d.tris;
  const auto it = std::find(list.begin(), list.end(), rec);
  if (it == list.end()) throw std::logic_error("DistributionTree: entry missing from its node");
  list.erase(it);  // keeps the order of the others (determinism)
  rebuildSums(d);
}

// Sums, maxima and (when grow is given) bounds of n from its children and own lists.
void DistributionTree::recomputeNode(uint32_t n) {
  DistributionNode& t = nodes_[n];
  if (t.dyn != kNone) {
    const DynOwn& d = dyn_[t.dyn];
    t.ownTriArea = d.triSum.empty() ? 0.0 : d.triSum.back();
    t.ownInstArea = d.instSum.empty() ? 0.0 : d.instSum.back();
    t.ownMaxTri = 0.0f;
    for (uint32_t r : d.tris) t.ownMaxTri = std::max(t.ownMaxTri, float(recArea(r)));
    t.maxTri = t.ownMaxTri;
    for (uint32_t r : d.insts) t.maxTri = std::max(t.maxTri, instMaxTri_[recs_[r].index()]);
  } else {
    // Own lists untouched: their static maxima still hold; children may have changed.
    t.maxTri = t.ownMaxTri;
    for (uint64_t j = t.instBegin; j < t.end; ++j)
      t.maxTri = std::max(t.maxTri, instMaxTri_[recs_[j].index()]);
  }
  t.area = t.ownTriArea + t.ownInstArea;
  for (uint32_t c : t.child) {
    if (c == kNone) continue;
    t.area += nodes_[c].area;
    t.maxTri = std::max(t.maxTri, nodes_[c].maxTri);
    t.tight.extend(nodes_[c].tight);
  }
}

void DistributionTree::refreshPath(uint32_t n, const Bounds* grow) {
  for (uint32_t m = n; m != kNone; m = nodes_[m].parent) {
    if (grow) nodes_[m].tight.extend(*grow);
    recomputeNode(m);
    nodes_[m].dirty = true;
  }
}

// Descends from the class root to the node that takes the entry (creating nodes on the way where
// a shortcut skips the right level or no child exists), adds it there, returns that node.
uint32_t DistributionTree::placeEntry(const Item& item, uint32_t rec) {
  const bool inst = (item.ref & kInstanceBit) != 0;
  const glm::dvec3 m = item.box.center();
  size_t k = 0;
  while (classes_[k].cls != item.cls) ++k;
  uint32_t x = classes_[k].root;
  for (;;) {
    const DistributionNode& X = nodes_[x];
    if (X.leaf()) {
      const DynOwn* d = X.dyn != kNone ? &dyn_[X.dyn] : nullptr;
      const uint64_t own = d ? d->tris.size() + d->insts.size() : X.end - X.ownBegin;
      addOwn(x, rec, inst);
      if (own + 1 > params_.leafEntries && X.depth < params_.maxDepth) {
        splitLeaf(x);
        return inst ? instNode_[item.ref & ~kInstanceBit] : triNode_[item.ref];
      }
      return x;
    }
    const int o = octant(X.center, m);
    const double ch = 0.5 * X.half;
    const glm::dvec3 cc = childCenter(X.center, X.half, o);
    if (X.depth >= params_.maxDepth || !extContains(cc, ch, item.box)) {
      addOwn(x, rec, inst);
      return x;
    }
    const uint32_t y = X.child[size_t(o)];
    const int xDepth = X.depth;
    if (y == kNone) {
      const uint32_t leaf = newNode(cc, ch, xDepth + 1, x, item.cls);
      nodes_[x].child[size_t(o)] = leaf;
      addOwn(leaf, rec, inst);
      return leaf;
    }
    if (nodes_[y].half == ch) {
      x = y;
      continue;
    }
    // A shortcut skips levels between x and y: follow the virtual cells towards y.
    glm::dvec3 vc = cc;
    double vh = ch;
    int vd = xDepth + 1;
    bool reachedY = false;
    for (;;) {
      const int oy = octant(vc, nodes_[y].center), ob = octant(vc, m);
      const double bh = 0.5 * vh;
      const glm::dvec3 bc = childCenter(vc, vh, ob);
      const bool fits = vd < params_.maxDepth && extContains(bc, bh, item.box);
      if (ob == oy && fits) {
        vc = bc;
        vh = bh;
        ++vd;
        if (nodes_[y].half == vh) {
          reachedY = true;
          break;
        }
        continue;
      }
      // The entry leaves y's path here: materialise this cell as a node.
      const uint32_t v = newNode(vc, vh, vd, x, item.cls);
      nodes_[x].child[size_t(o)] = v;
      nodes_[v].child[size_t(oy)] = y;
      nodes_[y].parent = v;
      nodes_[v].tight = nodes_[y].tight;
      recomputeNode(v);
      if (ob != oy && fits) {
        const uint32_t leaf = newNode(bc, bh, vd + 1, v, item.cls);
        nodes_[v].child[size_t(ob)] = leaf;
        addOwn(leaf, rec, inst);
        return leaf;
      }
      addOwn(v, rec, inst);
      return v;
    }
    if (reachedY) x = y;
  }
}

// A leaf over capacity hands the entries that fit a child's extended box down to new leaves.
void DistributionTree::splitLeaf(uint32_t n) {
  std::vector<uint32_t> tris = dyn_[nodes_[n].dyn].tris, insts = dyn_[nodes_[n].dyn].insts;
  std::vector<uint32_t> keepTris, keepInsts;
  std::array<std::vector<std::pair<uint32_t, bool>>, 8> down;
  auto route = [&](uint32_t r, bool inst) {
    const EntryRec& e = recs_[r];
    const Item it = inst ? instanceItem(e.index()) : triangleItem(e.ref);
    const DistributionNode& t = nodes_[n];
    const int o = octant(t.center, it.box.center());
    if (extContains(childCenter(t.center, t.half, o), 0.5 * t.half, it.box))
      down[size_t(o)].push_back({r, inst});
    else
      (inst ? keepInsts : keepTris).push_back(r);
  };
  for (uint32_t r : tris) route(r, false);
  for (uint32_t r : insts) route(r, true);
  DynOwn& d = dyn_[nodes_[n].dyn];
  d.tris = keepTris;
  d.insts = keepInsts;
  rebuildSums(d);
  for (int o = 0; o < 8; ++o) {
    if (down[size_t(o)].empty()) continue;
    const DistributionNode& t = nodes_[n];
    const uint32_t c =
        newNode(childCenter(t.center, t.half, o), 0.5 * t.half, t.depth + 1, n, t.cls);
    nodes_[n].child[size_t(o)] = c;
    for (const auto& [r, inst] : down[size_t(o)]) {
      addOwn(c, r, inst);
      const EntryRec& e = recs_[r];
      nodes_[c].tight.extend(inst ? instances_[e.index()].bounds : triangleItem(e.ref).box);
    }
    if (down[size_t(o)].size() > params_.leafEntries && nodes_[c].depth < params_.maxDepth)
      splitLeaf(c);
    recomputeNode(c);
    nodes_[c].dirty = true;
  }
  recomputeNode(n);
}

void DistributionTree::insertItem(const Item& item, uint32_t rec) {
  dynamic_ = true;
  size_t k = 0;
  while (k < classes_.size() && classes_[k].cls != item.cls) ++k;
  if (k == classes_.size()) {
    glm::dvec3 center = item.box.center();
    const glm::dvec3 e = item.box.extent();
    const double half = std::max(0.5 * std::max({e.x, e.y, e.z}) * (1.0 + 1e-9),
                                 1e-30 + 1e-12 * glm::length(center));
    const uint32_t root = newNode(center, half, 0, kNone, item.cls);
    classes_.push_back({item.cls, root});
    addOwn(root, rec, (item.ref & kInstanceBit) != 0);
    refreshPath(root, &item.box);
    bounds_.extend(item.box);
    return;
  }
  // Grow the root upwards (doubling, the old root one octant of the new) until it fits.
  for (;;) {
    const uint32_t root = classes_[k].root;
    const DistributionNode& r = nodes_[root];
    if (extContains(r.center, r.half, item.box)) break;
    const glm::dvec3 m = item.box.center();
    const glm::dvec3 c{r.center.x + (m.x >= r.center.x ? r.half : -r.half),
                       r.center.y + (m.y >= r.center.y ? r.half : -r.half),
                       r.center.z + (m.z >= r.center.z ? r.half : -r.half)};
    const uint32_t up = newNode(c, 2.0 * r.half, 0, kNone, item.cls);
    nodes_[up].child[size_t(octant(c, nodes_[root].center))] = root;
    nodes_[root].parent = up;
    nodes_[up].tight = nodes_[root].tight;
    recomputeNode(up);
    nodes_[up].dirty = true;
    classes_[k].root = up;
  }
  const uint32_t n = placeEntry(item, rec);
  refreshPath(n, &item.box);
  bounds_.extend(item.box);
}

void DistributionTree::insertTriangle(uint32_t t) {
  if (t >= mesh_->size())
    throw std::out_of_range("DistributionTree::insertTriangle: not in the mesh");
  if (triNode_.size() < mesh_->size()) {
    triNode_.resize(mesh_->size(), kNone);
    triRec_.resize(mesh_->size(), kNone);
  }
  if (triNode_[t] != kNone)
    throw std::invalid_argument("DistributionTree::insertTriangle: already in");
  const Item item = triangleItem(t);
  if (!(item.area > 0.0)) return;
  const uint32_t rec = uint32_t(recs_.size());
  recs_.push_back(makeRec(item));
  insertItem(item, rec);
}

void DistributionTree::removeTriangle(uint32_t t) {
  if (!containsTriangle(t)) throw std::invalid_argument("DistributionTree::removeTriangle: not in");
  const uint32_t n = triNode_[t];
  dynamic_ = true;
  removeRec(n, triRec_[t], false);
  triNode_[t] = triRec_[t] = kNone;
  refreshPath(n, nullptr);
}

uint32_t DistributionTree::insertInstance(const InstanceRef& ref, double childArea,
                                          float childMaxTri) {
  const uint32_t i = uint32_t(instances_.size());
  instances_.push_back(ref);
  hot_.push_back(makeHot(i));
  instArea_.push_back(ref.areaScale * childArea);
  instMaxTri_.push_back(float(ref.areaScale * childMaxTri));
  instNode_.push_back(kNone);
  instRec_.push_back(kNone);
  if (!(instArea_[i] > 0.0) || ref.bounds.empty()) return i;  // nothing to sample
  const Item item = instanceItem(i);
  const uint32_t rec = uint32_t(recs_.size());
  recs_.push_back(makeRec(item));
  insertItem(item, rec);
  return i;
}

void DistributionTree::removeInstance(uint32_t i) {
  if (i >= instances_.size()) throw std::out_of_range("DistributionTree::removeInstance");
  if (instNode_[i] == kNone) return;
  const uint32_t n = instNode_[i];
  dynamic_ = true;
  removeRec(n, instRec_[i], true);
  instNode_[i] = instRec_[i] = kNone;
  refreshPath(n, nullptr);
}

void DistributionTree::updateInstance(uint32_t i, double childArea, float childMaxTri) {
  if (i >= instances_.size()) throw std::out_of_range("DistributionTree::updateInstance");
  const bool live = instNode_[i] != kNone;
  if (live) {
    const uint32_t n = instNode_[i];
    dynamic_ = true;
    removeRec(n, instRec_[i], true);
    instNode_[i] = instRec_[i] = kNone;
    refreshPath(n, nullptr);
  }
  instArea_[i] = instances_[i].areaScale * childArea;
  instMaxTri_[i] = float(instances_[i].areaScale * childMaxTri);
  if (!(instArea_[i] > 0.0)) return;
  const Item item = instanceItem(i);
  const uint32_t rec = uint32_t(recs_.size());
  recs_.push_back(makeRec(item));
  insertItem(item, rec);
}

void DistributionTree::compact() {
  if (!dynamic_) return;
  // Class roots in class order, each subtree in DFS order: children, own triangles, own instances.
  std::stable_sort(classes_.begin(), classes_.end(),
                   [](const ClassRoot& a, const ClassRoot& b) { return a.cls < b.cls; });
  std::vector<uint32_t> order;  // old record indices in the new list order
  order.reserve(recs_.size());
  std::vector<uint32_t> listNode;
  std::vector<std::array<uint64_t, 4>> slices(nodes_.size());
  auto emit = [&](auto&& self, uint32_t n) -> void {
    slices[n][0] = order.size();
    for (uint32_t c : nodes_[n].child)
      if (c != kNone) self(self, c);
    slices[n][1] = order.size();
    const DistributionNode& t = nodes_[n];
    if (t.dyn != kNone) {
      for (uint32_t r : dyn_[t.dyn].tris) order.push_back(r);
      slices[n][2] = order.size();
      for (uint32_t r : dyn_[t.dyn].insts) order.push_back(r);
    } else {
      for (uint64_t j = t.ownBegin; j < t.instBegin; ++j) order.push_back(uint32_t(j));
      slices[n][2] = order.size();
      for (uint64_t j = t.instBegin; j < t.end; ++j) order.push_back(uint32_t(j));
    }
    slices[n][3] = order.size();
    listNode.resize(order.size(), n);
  };
  for (const ClassRoot& c : classes_) emit(emit, c.root);

  std::vector<EntryRec> recs(order.size());
  std::vector<double> prefix(order.size());
  double sum = 0.0, comp = 0.0, last = 0.0;
  for (size_t j = 0; j < order.size(); ++j) {
    recs[j] = recs_[order[j]];
    const double a = recArea(order[j]), t = sum + a;
    comp += std::abs(sum) >= std::abs(a) ? (sum - t) + a : (a - t) + sum;
    sum = t;
    last = std::max(last, sum + comp);
    prefix[j] = last;
  }
  for (size_t j = 0; j < order.size(); ++j) {
    const EntryRec& e = recs[j];
    if (e.instance()) {
      instRec_[e.index()] = uint32_t(j);
      instNode_[e.index()] = listNode[j];
    } else {
      triRec_[e.ref] = uint32_t(j);
      triNode_[e.ref] = listNode[j];
    }
  }
  recs_ = std::move(recs);
  prefix_ = std::move(prefix);
  dyn_.clear();
  auto P = [&](uint64_t j) { return j ? prefix_[j - 1] : 0.0; };
  for (uint32_t n = 0; n < nodes_.size(); ++n) {
    DistributionNode& t = nodes_[n];
    t.begin = slices[n][0];
    t.ownBegin = slices[n][1];
    t.instBegin = slices[n][2];
    t.end = slices[n][3];
    t.dyn = kNone;
    t.dirty = false;
    t.area = P(t.end) - P(t.begin);
    t.ownTriArea = P(t.instBegin) - P(t.ownBegin);
    t.ownInstArea = P(t.end) - P(t.instBegin);
  }
  dynamic_ = false;
  buildAlias();  // when enabled
}

}  // namespace lzb::rzb
