#pragma once
// The randomized z-buffer's octree over ONE scene node's content (Wand et al. 2001, sections 5.3,
// 5.4, 7.1, 7.3), in that node's frame.
//
// - Entries are the node's triangles and its instance entries (another node's DistributionTree
// placed by
//   a transform, counted with its whole area). Every entry lives in exactly one octree node: the
//   smallest one whose EXTENDED box (the cell enlarged by DistributionParams::extension on every
//   side) contains it, unless it sits in a leaf (at most leafEntries entries) above that.
// - Shortcuts: chains of inner nodes with one child and no entries are not stored (a child link
//   may skip levels), so storage is linear in the entries.
// - Area classes: entries are split by area (instance entries by their largest triangle) into
//   classes whose bounds grow by areaRatio; each class has its own octree (its own root), so a box
//   of large triangles can be recognised and sent to the z-buffer fallback.
// - One distribution list for the whole tree (Fig. 5): every class tree in DFS order, a node's
//   slice being its children's slices, then its own triangles, then its own instance entries.
//   prefix() holds the inclusive prefix sums of entry areas (double, compensated summation); a node
//   owns the slice [begin, end). Static sampling is one binary search in a slice.
// - Dynamic updates (section 5.4, the distribution-tree variant): every node also keeps the summed
//   area of its subtree. Inserting or removing an entry walks one root-to-node path (creating
//   nodes where needed) and fixes the sums on it, O(tree height). Nodes on modified paths are
//   "dirty": sampling descends through them by their sums until it reaches a clean node, where the
//   static slice is still right. compact() lays the list out again (O(n)).
// Node indices, the list order and all sums are independent of the thread count.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "src/core/bounds.hpp"
#include "src/core/scene.hpp"
#include "src/core/affine.hpp"

namespace lzb::rzb {

constexpr uint32_t kNone = ~uint32_t(0);
constexpr uint32_t kInstanceBit = 0x80000000u;

struct DistributionParams {
  double areaRatio = 4.0;     // area class width (2..64)
  double extension = 0.5;     // extended box = cell enlarged by extension * half side per side
  uint32_t leafEntries = 16;  // a node with at most this many entries is a leaf
  int maxDepth = 40;
  // Instance flattening (sample_scene.hpp): a tree takes its triangle-less children's instances
  // in place of them while it stays under this many entries.
  size_t flattenBudget = 4096;
  bool progress = false;  // SampleScene shows a progress line for large builds
};

// A list entry as the sampler reads it.
struct EntryRec {
  glm::vec3 v0, e1, e2;  // triangles: vertex 0 and the two edges from it (node frame)
  uint32_t ref;          // triangle: mesh index; instance: kInstanceBit | instance entry index
  bool instance() const { return (ref & kInstanceBit) != 0; }
  uint32_t index() const { return ref & ~kInstanceBit; }
};

class DistributionTree;

// What a sample descending through an instance entry reads (a compact copy of InstanceRef).
struct InstanceHot {
  const DistributionTree* child;
  glm::dvec3 t;  // translation
  uint64_t idOffset;
  float detSign;
  uint32_t linear;  // 0: translation only; else 1 + index of the InstanceRef with the linear part
};

// Another node's tree placed in this tree's frame (possibly through flattened instance levels).
struct InstanceRef {
  uint32_t node = 0;                // scene node referenced
  const DistributionTree* child = nullptr;
  Affine transform;                 // child frame -> this frame
  uint64_t idOffset = 0;            // child's expanded ID 0 relative to this node's
  bool translationOnly = false;
  double detSign = 1.0;
  double areaScale = 1.0;           // maxAreaScale(transform)
  double stretch = 1.0;             // maxStretch(transform)
  Bounds bounds;                    // the child's content bounds in this frame
};

enum class Part : uint8_t { kSubtree, kOwnTriangles };

// One slot of a tree's alias table: position i is kept with probability prob, else `alias`.
struct AliasSlot {
  double prob;
  double keepScale, altScale;  // 1 / prob and 1 / (1 - prob): remainders without a division
  uint32_t alias;
  uint32_t keepRef, altRef;    // EntryRec::ref of position i and of alias (saves a load)
};

struct DistributionNode {
  glm::dvec3 center{0.0};
  double half = 0.0;  // the octree cell: center +- half
  Bounds tight;       // bounds of everything in the subtree (node frame; may only grow)
  std::array<uint32_t, 8> child;
  uint32_t parent = kNone;
  uint32_t dyn = kNone;  // index of its own lists once they were modified
  uint64_t begin = 0, ownBegin = 0, instBegin = 0, end = 0;  // static slices (valid if !dirty)
  double area = 0.0, ownTriArea = 0.0, ownInstArea = 0.0;   // subtree, own triangles, own insts
  float maxTri = 0.0f, ownMaxTri = 0.0f;  // largest triangle area (subtree / own triangles)
  int16_t cls = 0;
  uint8_t depth = 0;
  bool dirty = false;
  DistributionNode() { child.fill(kNone); }
  bool leaf() const {
    for (uint32_t c : child)
      if (c != kNone) return false;
    return true;
  }
};

struct TreeStats {
  uint64_t nodes = 0, triangles = 0, instances = 0, classes = 0;
  int depth = 0;
  uint64_t memoryBytes = 0;
};

class DistributionTree {
 public:
  struct ClassRoot {
    int cls;
    uint32_t root;
  };

  // Builds over `triangles` (indices into scene.nodes[node].mesh) and `instances` (their child
  // trees built). An empty span of triangles with allTriangles = true takes the whole mesh.
  DistributionTree(const Scene& scene, uint32_t node, std::span<const uint32_t> triangles,
                   bool allTriangles, std::vector<InstanceRef> instances,
                   const DistributionParams& params);

  uint32_t sceneNode() const { return sceneNode_; }
  const Mesh& mesh() const { return *mesh_; }
  const DistributionParams& params() const { return params_; }
  double totalArea() const;
  float maxTriArea() const;
  const Bounds& bounds() const { return bounds_; }
  bool dynamic() const { return dynamic_; }
  TreeStats stats() const;

  const std::vector<ClassRoot>& classes() const { return classes_; }
  const DistributionNode& node(uint32_t i) const { return nodes_[i]; }
  uint32_t nodeCount() const { return uint32_t(nodes_.size()); }
  const double* prefix() const { return prefix_.data(); }
  uint64_t listSize() const { return prefix_.size(); }
  const EntryRec& rec(uint32_t r) const { return recs_[r]; }
  const EntryRec* recs() const { return recs_.data(); }
  const InstanceRef& instance(uint32_t i) const { return instances_[i]; }
  uint32_t instanceCount() const { return uint32_t(instances_.size()); }
  double instanceArea(uint32_t i) const { return instArea_[i]; }
  float instanceMaxTri(uint32_t i) const { return instMaxTri_[i]; }
  bool instanceLive(uint32_t i) const { return instNode_[i] != kNone; }
  double recArea(uint32_t r) const;

  // Area and largest triangle of a box (a node's subtree or its own triangles).
  double partArea(uint32_t n, Part part) const {
    return part == Part::kSubtree ? nodes_[n].area : nodes_[n].ownTriArea;
  }
  float partMaxTri(uint32_t n, Part part) const {
    return part == Part::kSubtree ? nodes_[n].maxTri : nodes_[n].ownMaxTri;
  }
  bool clean(uint32_t n) const { return !nodes_[n].dirty; }
  // The static slice of a clean box.
  void slice(uint32_t n, Part part, uint64_t& b, uint64_t& e) const {
    const DistributionNode& t = nodes_[n];
    b = part == Part::kSubtree ? t.begin : t.ownBegin;
    e = part == Part::kSubtree ? t.end : t.instBegin;
  }

  // Picks an entry of a box with probability proportional to its area; u in [0, 1). Returns the
  // record index and sets rem to the position inside the picked entry's area, in [0, 1), and
  // res to rem's resolution (grows as a deep pick consumes the 53 bits of u).
  uint32_t pick(uint32_t n, Part part, double u, double& rem, double& res) const;
  // The same over the whole tree (all classes): sampling inside an instance entry. A static tree
  // with an alias table over its list (O(1): Walker/Vose; SampleScene builds one for every tree
  // an instance entry references) answers from it, others by search or descent.
  uint32_t pickWhole(double u, double& rem, double& res) const;
  void enableAlias();
  // The alias table (empty when there is none or the tree is dynamic).
  const AliasSlot* aliasTable() const { return dynamic_ ? nullptr : alias_.data(); }
  size_t aliasSize() const { return dynamic_ ? 0 : alias_.size(); }
  const InstanceHot& instanceHot(uint32_t i) const { return hot_[i]; }
  // Starts loading what a sample entering instance entry i reads (its hot record and, when some
  // entry of this tree has a linear part, that matrix), so a group of descending samples overlaps
  // its cache misses.
  void prefetchInstance(uint32_t i) const {
    prefetchSpan(&hot_[i], sizeof(InstanceHot));
    if (anyLinear_) prefetchSpan(&instances_[i].transform.a, sizeof(glm::dmat3));
  }
  void prefetchAliasSlot(uint32_t i) const { prefetchSpan(&alias_[i], sizeof(AliasSlot)); }
  void prefetchRec(uint32_t r) const { prefetchSpan(&recs_[r], sizeof(EntryRec)); }

  // Calls f(recIndex) for every entry of a box (triangles and instance entries).
  template <class F>
  void forEachEntry(uint32_t n, Part part, F&& f) const;
  // Calls f(instanceIndex) for the instance entries stored in node n itself.
  template <class F>
  void forEachOwnInstance(uint32_t n, F&& f) const;

  // Dynamic updates, O(tree height) each (a leaf over leafEntries is split, O(leafEntries)).
  // The triangle must be in the mesh (append it there first); IDs stay Scene's.
  void insertTriangle(uint32_t meshTriangle);
  void removeTriangle(uint32_t meshTriangle);
  bool containsTriangle(uint32_t meshTriangle) const {
    return meshTriangle < triNode_.size() && triNode_[meshTriangle] != kNone;
  }
  // Whole objects: an instance entry (its own tree), returned index for removal.
  uint32_t insertInstance(const InstanceRef& ref, double childArea, float childMaxTri);
  void removeInstance(uint32_t instance);
  // The child tree's area changed (dynamic edits inside it): refresh the entry's weight.
  void updateInstance(uint32_t instance, double childArea, float childMaxTri);
  // Lays the distribution list out again so sampling is one binary search everywhere.
  void compact();

 private:
  struct Item {  // build input
    Bounds box;
    double area;
    float maxTri;
    int cls;
    uint32_t ref;
  };
  struct DynOwn {
    std::vector<uint32_t> tris, insts;      // record indices
    std::vector<double> triSum, instSum;    // inclusive prefix sums
  };

  Item triangleItem(uint32_t t) const;
  Item instanceItem(uint32_t i) const;
  int classOf(double maxTri) const;
  EntryRec makeRec(const Item& item) const;
  void buildStatic(std::vector<Item>& items);
  uint32_t buildNode(std::vector<Item>& items, std::vector<uint32_t>& idx, size_t lo, size_t hi,
                     glm::dvec3 center, double half, int depth, uint32_t parent,
                     std::vector<uint32_t>& order, std::vector<uint32_t>& scratch);
  void finishStatic(const std::vector<Item>& items, const std::vector<uint32_t>& order);
  void buildAlias();
  InstanceHot makeHot(uint32_t i);  // also notes a linear part in anyLinear_
  uint32_t newNode(const glm::dvec3& center, double half, int depth, uint32_t parent, int cls);
  bool extContains(const glm::dvec3& center, double half, const Bounds& b) const;
  DynOwn& dynOwn(uint32_t n);
  void rebuildSums(DynOwn& d) const;
  void addOwn(uint32_t n, uint32_t rec, bool instance);
  uint32_t placeEntry(const Item& item, uint32_t rec);
  void splitLeaf(uint32_t n);
  void refreshPath(uint32_t n, const Bounds* grow);
  void recomputeNode(uint32_t n);
  void insertItem(const Item& item, uint32_t rec);
  void removeRec(uint32_t n, uint32_t rec, bool instance);
  uint32_t pickDyn(uint32_t n, Part part, double v, double& rem, double& res) const;
  uint32_t pickSlice(uint64_t b, uint64_t e, double u, double& rem, double& res) const;
  static uint32_t pickSums(const std::vector<uint32_t>& recs, const std::vector<double>& sums,
                           double v, double& rem, double& res);

  // Every cache line of [p, p + bytes).
  static void prefetchSpan(const void* p, size_t bytes) {
    const char* c = static_cast<const char*>(p);
    __builtin_prefetch(c);
    if ((reinterpret_cast<uintptr_t>(c) & 63) + bytes > 64) __builtin_prefetch(c + bytes - 1);
    if (bytes > 64 && (reinterpret_cast<uintptr_t>(c) & 63) + bytes > 128)
      __builtin_prefetch(c + 64);
  }

  const Scene* scene_;
  const Mesh* mesh_;
  uint32_t sceneNode_;
  DistributionParams params_;
  double logRatio_;
  Bounds bounds_;
  bool dynamic_ = false;
  bool wantAlias_ = false;
  bool anyLinear_ = false;  // some instance entry has a linear part (not translation only)
  std::vector<ClassRoot> classes_;
  std::vector<DistributionNode> nodes_;
  std::vector<double> prefix_;    // the distribution list (static part)
  std::vector<EntryRec> recs_;    // [0, listSize) in list order, then inserted records
  std::vector<AliasSlot> alias_;  // over the static list
  std::vector<InstanceRef> instances_;
  std::vector<InstanceHot> hot_;
  std::vector<double> instArea_;  // areaScale * child area
  std::vector<float> instMaxTri_;
  std::vector<uint32_t> instNode_, instRec_;  // per instance entry: its node and record
  std::vector<uint32_t> triNode_, triRec_;    // per mesh triangle: its node and record (or kNone)
  std::vector<DynOwn> dyn_;
};

// Area of triangle t of a mesh, in double (the one area every sum uses).
double triangleArea(const Mesh& mesh, uint32_t t);

template <class F>
void DistributionTree::forEachEntry(uint32_t n, Part part, F&& f) const {
  const DistributionNode& t = nodes_[n];
  if (!t.dirty) {
    uint64_t b, e;
    slice(n, part, b, e);
    for (uint64_t j = b; j < e; ++j) f(uint32_t(j));
    return;
  }
  if (part == Part::kSubtree)
    for (uint32_t c : t.child)
      if (c != kNone) forEachEntry(c, Part::kSubtree, f);
  if (t.dyn != kNone) {
    for (uint32_t r : dyn_[t.dyn].tris) f(r);
    if (part == Part::kSubtree)
      for (uint32_t r : dyn_[t.dyn].insts) f(r);
  } else {
    const uint64_t e = part == Part::kSubtree ? t.end : t.instBegin;
    for (uint64_t j = t.ownBegin; j < e; ++j) f(uint32_t(j));
  }
}

template <class F>
void DistributionTree::forEachOwnInstance(uint32_t n, F&& f) const {
  const DistributionNode& t = nodes_[n];
  if (t.dyn != kNone) {
    for (uint32_t r : dyn_[t.dyn].insts) f(recs_[r].index());
  } else {
    for (uint64_t j = t.instBegin; j < t.end; ++j) f(recs_[j].index());
  }
}

}  // namespace lzb::rzb
