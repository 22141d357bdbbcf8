#pragma once
// Drawing the samples of one selected box (sections 5.2 and 7.3). Sample i of a box's n samples
// takes the Philox numbers of (box key, i): u = (i + r) / n with r from the first word (the
// samples are stratified along the distribution list: each takes one equal-area stratum of the
// box's slice, jittered), words 2 and 3 give uniform barycentric coordinates (the unit square
// folded onto the triangle). Inverting the slice's prefix sums at u picks the entry, so a triangle
// gets its area's share of the samples (the integer part exactly, the rest by the jitter), and
// the points inside a triangle stay independent and uniform: coverage is at least as good as
// with independent picks (the coupon-collector bound still holds), and the picks of consecutive
// samples move forward along the list, so the search is a walk from the previous position.
// An instance entry continues the pick inside the child's whole list with the remainder of u
// (once fewer than 16 bits are left: the sample's spare Philox word, then fresh draws keyed by
// (box key, i, level)), composing transforms.
//
// Philox is computed 4096 samples at a time (vectorized). The result goes to a sink as (position
// in the box's node frame, a normal direction there that transforms like the triangle's normal,
// expanded ID, leaf tree, mesh index). Hot loops are templates over the sink: no allocation,
// virtual call or std::function per sample.
#include <algorithm>
#include <cstdint>
#include <glm/glm.hpp>

#include "src/core/area_sampling.hpp"
#include "src/core/philox_stream.hpp"
#include "src/rzb/box_selection.hpp"
#include "src/rzb/distribution_tree.hpp"

namespace lzb::rzb {

constexpr uint32_t kDrawBatch = 4096;

// Philox words of samples [first, first + n) of a box (n <= kDrawBatch): w[k][i] is word k of
// sample first + i. A per-thread buffer valid until the next call on this thread.
struct DrawWords {
  const uint32_t* w[4];
};
DrawWords batchDraws(const SampleStream& stream, uint64_t boxKey, uint64_t first, uint32_t n);

// A sample on its way down through instance entries: the transform composed so far (child frame
// -> box frame), the remainder of its pick number and that number's resolution.
struct Descent {
  glm::dmat3 A;
  glm::dvec3 t;
  double rem, res;
  uint64_t id, index;
  const DistributionTree* tree;
  uint32_t instance;  // the entry of `tree` to enter next
  uint32_t pos, ref;  // the record picked in the child (pos: its list position)
  uint32_t level;
  uint32_t spare;  // a fresh 32-bit word for the first refresh (the sample's Philox word 1)
  float a, c, sign;
  bool linear;
};

// Samples descend in groups (descendGroup), level by level. One sample's steps form a long
// dependent chain (conversions, the slot load, selects) whose loads mostly miss the cache (random
// entries of the child trees); members of a group are independent, so the core overlaps their
// chains and misses. (Caching a composed transform per level would not help: a box's consecutive
// samples share their first instance entry, but the next level's picks already differ.)
constexpr uint32_t kDescentGroup = 64;
static_assert(kDescentGroup <= 256, "group indices are bytes");

// Where a finished descent landed: p, n in the box frame, the complete expanded ID, the leaf tree
// and the triangle's mesh index there.
struct DescentHit {
  glm::dvec3 p, n;
  uint64_t id;
  const DistributionTree* leaf;
  uint32_t meshIndex;
};

// A descent into instance entry `instance` of `tree`.
inline void startDescent(Descent& d, const DistributionTree* tree, uint32_t instance, double rem,
                         double res, uint32_t spare, uint64_t id, uint64_t index, float a,
                         float c) {
  d.A = glm::dmat3(1.0);
  d.t = glm::dvec3(0.0);
  d.rem = rem;
  d.res = res;
  d.id = id;
  d.index = index;
  d.tree = tree;
  d.instance = instance;
  d.level = 0;
  d.spare = spare;
  d.a = a;
  d.c = c;
  d.sign = 1.0f;
  d.linear = false;
}

// Enters d's instance entry (composing its transform) and starts the pick in the child's whole
// list: with an alias table, d.pos = the slot (its line prefetched) and d.rem = the position
// inside it, finished by pickSlot; without one, the pick is complete.
void enterEntry(Descent& d, const SampleStream& stream, uint64_t boxKey);
// Reads d's alias slot: sets d.pos, d.ref and the remainder.
inline void pickSlot(Descent& d) {
  const size_t size = d.tree->aliasSize();
  const AliasSlot& slot = d.tree->aliasTable()[d.pos];
  const double f = d.rem;
  const bool keep = f < slot.prob;
  const double scale = keep ? slot.keepScale : slot.altScale;
  d.rem = std::min((keep ? f : f - slot.prob) * scale, 1.0 - 0x1p-53);
  d.res *= double(size) * scale;
  d.ref = keep ? slot.keepRef : slot.altRef;
  d.pos = keep ? d.pos : slot.alias;
}
// d picked a triangle: where the sample lands.
void finishDescent(const Descent& d, DescentHit& hit);

// Runs group[0, n) down to their triangles; emit(const DescentHit&) for each, in an order that
// depends only on the group. Each level is three passes over the members still descending (enter
// and prefetch the slot; read the slot and prefetch what comes next; finish those on a triangle),
// so the loads of one pass were started a whole pass earlier.
template <class Emit>
void descendGroup(Descent* group, uint32_t n, const SampleStream& stream, uint64_t boxKey,
                  Emit&& emit) {
  uint8_t active[kDescentGroup], leaves[kDescentGroup];
  for (uint32_t k = 0; k < n; ++k) active[k] = uint8_t(k);
  DescentHit hit;
  while (n) {
    for (uint32_t k = 0; k < n; ++k) enterEntry(group[active[k]], stream, boxKey);
    uint32_t still = 0, done = 0;
    for (uint32_t k = 0; k < n; ++k) {
      Descent& d = group[active[k]];
      if (d.tree->aliasSize()) pickSlot(d);
      if (d.ref & kInstanceBit) {
        d.instance = d.ref & ~kInstanceBit;
        d.tree->prefetchInstance(d.instance);
        active[still++] = active[k];
      } else {
        d.tree->prefetchRec(d.pos);
        leaves[done++] = active[k];
      }
    }
    for (uint32_t k = 0; k < done; ++k) {
      finishDescent(group[leaves[k]], hit);
      emit(hit);
    }
    n = still;
  }
}

// Samples [first, first + count) of the `total` samples of box. Sink: void(const dvec3& p,
// const dvec3& n, uint64_t id, const DistributionTree* leaf, uint32_t meshIndex), and optionally
// flush(), called after every batch of kDrawBatch samples.
template <class Sink>
void drawBoxSamples(const SelectedBox& box, const SampleStream& stream, uint64_t first,
                    uint64_t count, uint64_t total, Sink& sink) {
  if (!count) return;
  const DistributionTree& tree = *box.tree;
  const EntryRec* recs = tree.recs();
  const bool clean = tree.clean(box.node);
  uint64_t b = 0, e = 0;
  double base = 0.0, span = 0.0, top = 0.0;
  const double* P = tree.prefix();
  if (clean) {
    tree.slice(box.node, box.part, b, e);
    base = b ? P[b - 1] : 0.0;
    top = P[e - 1];
    span = top - base;
  }
  const double inv = 1.0 / double(total);
  uint64_t j = b;
  Descent group[kDescentGroup];
  uint32_t grouped = 0;
  const auto descend = [&] {
    descendGroup(group, grouped, stream, box.key,
                 [&](const DescentHit& h) { sink(h.p, h.n, h.id, h.leaf, h.meshIndex); });
    grouped = 0;
  };
  for (uint64_t s0 = first; s0 < first + count; s0 += kDrawBatch) {
    const uint32_t n = uint32_t(std::min<uint64_t>(kDrawBatch, first + count - s0));
    const DrawWords d = batchDraws(stream, box.key, s0, n);
    for (uint32_t k = 0; k < n; ++k) {
      const uint64_t i = s0 + k;
      // 32 bits of jitter are ample inside a stratum; word 1 stays spare for a deep descent.
      const double jitter = (double(d.w[0][k]) + 0.5) * 0x1p-32;
      const double u = std::min((double(i) + jitter) * inv, 1.0 - 0x1p-53);
      float a = unit24(d.w[2][k]), c = unit24(d.w[3][k]);
      foldUnitSquare(a, c);
      double rem = 0.0, res = 0x1p-32 * inv;
      if (clean) {
        const double target = base + u * span;
        j = searchForward(P, e, j, target);
        if (recs[j].instance()) {
          const double before = j ? P[j - 1] : 0.0, area = P[j] - before;
          const double ia = area > 0.0 ? 1.0 / area : 0.0;
          rem = area > 0.0 ? glm::clamp((target - before) * ia, 0.0, 1.0 - 0x1p-53) : 0.5;
          res = area > 0.0 ? (span * res + top * 0x1p-52) * ia : 1.0;
        }
      } else {
        j = tree.pick(box.node, box.part, u, rem, res);
      }
      const EntryRec& r = recs[j];
      if (!r.instance()) {
        // In float, as exact as the vertices themselves; the transform to camera space is double.
        const glm::vec3 p = r.v0 + a * r.e1 + c * r.e2;
        sink(glm::dvec3(p), glm::dvec3(glm::cross(r.e1, r.e2)), box.idBase + r.ref, &tree, r.ref);
        continue;
      }
      startDescent(group[grouped++], &tree, r.index(), rem, res, d.w[1][k], box.idBase, i, a, c);
      if (grouped == kDescentGroup) descend();
    }
    descend();
    // A sink may buffer a batch (e.g. to splat it after the tree lookups, so the two working sets
    // do not evict each other from the cache).
    if constexpr (requires { sink.flush(); }) sink.flush();
  }
}

}  // namespace lzb::rzb
