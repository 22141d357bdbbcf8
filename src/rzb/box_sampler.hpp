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
#include <concepts>
#include <cstdint>
#include <glm/glm.hpp>

#include "src/core/area_sampling.hpp"
#include "src/core/philox_stream.hpp"
#include "src/rzb/box_selection.hpp"
#include "src/rzb/distribution_tree.hpp"

namespace lzb::rzb {

constexpr uint32_t kDrawBatch = 4096;
// How many samples ahead drawBoxSamples fetches the records its walk picked.
constexpr uint64_t kWalkAhead = 32;

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

// A sink that takes camera-space points (the point pass): drawBoxSamples then tests back faces
// and moves points to camera space itself, in the frame of the triangle's own tree, with one
// transform per instance entry a run of samples lands in, instead of composing the box frame's
// position and normal for every sample.
template <class Sink>
concept CameraSink = requires(Sink& s, float x, uint64_t id) {
  { s.dropBackfaces } -> std::convertible_to<bool>;
  s.point(x, x, x, id);  // camera space, expanded ID
  s.backfacing();        // a sample dropped on a back face
};

// A sample at p on a triangle whose normal points along n (both in one frame, with the eye there
// and the map from there to camera space) to a CameraSink.
template <class Sink>
[[gnu::always_inline]] inline void land(Sink& sink, const glm::dvec3& p, const glm::dvec3& n,
                                        const glm::dvec3& eye, const Affine& toCam, uint64_t id) {
  if (sink.dropBackfaces && glm::dot(n, eye - p) < 0.0) return sink.backfacing();
  const glm::dvec3 q = toCam.point(p);
  sink.point(float(q.x), float(q.y), float(q.z), id);
}

// Samples of one box that entered instance entries whose child trees hold triangles only: their
// alias picks wait here in groups, so that the slot and record loads of a group overlap (as in
// descendGroup), and land through their entry's transform straight into camera space.
class LeafGroups {
 public:
  // The instance entry `instance` of tree: what its samples share.
  struct Run {
    const DistributionTree* child = nullptr;
    Affine toCam;    // child frame -> camera space
    glm::dvec3 eye;  // the eye in the child frame
    uint64_t idBase = 0;
  };

  // Run for entry `instance` of `tree` in a box placed by toCam, eye in the box frame; null when
  // the entry's child holds instances (the general descent takes it).
  const Run* enter(const DistributionTree& tree, uint32_t instance, const Affine& toCam,
                   const glm::dvec3& eye, uint64_t idBase) {
    if (instance == instance_) return run_.child ? &run_ : nullptr;
    instance_ = instance;
    const InstanceHot& r = tree.instanceHot(instance);
    run_.child = r.child->instanceCount() == 0 && r.child->aliasSize() ? r.child : nullptr;
    if (!run_.child) return nullptr;
    Affine place{glm::dmat3(1.0), r.t};
    if (r.linear) place.a = tree.instance(r.linear - 1).transform.a;
    run_.toCam = toCam * place;
    // The back-face test keeps its sign in the child frame: the box frame's normal is the
    // child's turned by the linear part's cofactor, times detSign, a factor |det| in all.
    run_.eye = glm::inverse(place.a) * (eye - r.t);
    run_.idBase = idBase + r.idOffset;
    return &run_;
  }

  // A sample with pick number rem (in [0, 1)) and barycentric (a, c) into run.
  template <class Sink>
  void add(const Run& run, double rem, float a, float c, Sink& sink) {
    const size_t size = run.child->aliasSize();
    const double x = rem * double(size);
    const uint32_t pos = uint32_t(std::min(x, double(size - 1)));
    run.child->prefetchAliasSlot(pos);
    if (runs_ == 0 || slots_[runs_ - 1].child != run.child ||
        slots_[runs_ - 1].idBase != run.idBase)
      slots_[runs_++] = run;
    picks_[n_++] = Pick{x - double(pos), pos, a, c, uint8_t(runs_ - 1)};
    if (n_ == kDescentGroup || runs_ == kDescentGroup) flush(sink);
  }

  // Lands every waiting sample: slots read (records prefetched), then records read.
  template <class Sink>
  void flush(Sink& sink) {
    for (uint32_t k = 0; k < n_; ++k) {
      Pick& q = picks_[k];
      const DistributionTree* child = slots_[q.run].child;
      const AliasSlot& slot = child->aliasTable()[q.pos];
      q.pos = q.rem < slot.prob ? q.pos : slot.alias;
      child->prefetchRec(q.pos);
    }
    for (uint32_t k = 0; k < n_; ++k) {
      const Pick& q = picks_[k];
      const Run& run = slots_[q.run];
      const EntryRec& e = run.child->rec(q.pos);
      const glm::vec3 p = e.v0 + q.a * e.e1 + q.c * e.e2;
      land(sink, glm::dvec3(p), glm::dvec3(glm::cross(e.e1, e.e2)), run.eye, run.toCam,
           run.idBase + e.ref);
    }
    n_ = 0;
    runs_ = 0;
    if (run_.child) slots_[runs_++] = run_;  // the current run stays first
  }

 private:
  struct Pick {
    double rem;
    uint32_t pos;
    float a, c;
    uint8_t run;
  };
  Run run_;
  uint32_t instance_ = ~0u;
  Run slots_[kDescentGroup];
  Pick picks_[kDescentGroup];
  uint32_t n_ = 0, runs_ = 0;
};

// Samples [first, first + count) of the `total` samples of box. Sink: void(const dvec3& p,
// const dvec3& n, uint64_t id, const DistributionTree* leaf, uint32_t meshIndex), and optionally
// flush(), called after every batch of kDrawBatch samples; or a CameraSink.
template <class Sink>
void drawBoxSamples(const SelectedBox& box, const SampleStream& stream, uint64_t first,
                    uint64_t count, uint64_t total, Sink& sink) {
  if (!count) return;
  constexpr bool kCamera = CameraSink<Sink>;
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
  LeafGroups leaves;
  const auto descend = [&] {
    descendGroup(group, grouped, stream, box.key, [&](const DescentHit& h) {
      if constexpr (kCamera) {
        land(sink, h.p, h.n, box.eyeLocal, box.toCamera, h.id);
      } else {
        sink(h.p, h.n, h.id, h.leaf, h.meshIndex);
      }
    });
    grouped = 0;
  };
  // The entry whose area split was computed last (one division per entry, not per sample).
  uint64_t splitEntry = ~uint64_t(0);
  double before = 0.0, ia = 0.0;
  // Per batch, first every sample's entry (a walk over the prefix sums alone), then the entries'
  // records, fetched a few samples ahead: the walk skips a few entries a sample, too far apart in
  // the records for the hardware's prefetch.
  uint64_t picked[kDrawBatch];
  double targets[kDrawBatch];  // clean: the target in the list; else the pick's remainder
  double dirtyRes[kDrawBatch];
  for (uint64_t s0 = first; s0 < first + count; s0 += kDrawBatch) {
    const uint32_t n = uint32_t(std::min<uint64_t>(kDrawBatch, first + count - s0));
    const DrawWords d = batchDraws(stream, box.key, s0, n);
    for (uint32_t k = 0; k < n; ++k) {
      // 32 bits of jitter are ample inside a stratum; word 1 stays spare for a deep descent.
      const double jitter = (double(d.w[0][k]) + 0.5) * 0x1p-32;
      const double u = std::min((double(s0 + k) + jitter) * inv, 1.0 - 0x1p-53);
      if (clean) {
        targets[k] = base + u * span;
        j = searchForward(P, e, j, targets[k]);
      } else {
        // The pick reads the resolution so far (that of u) and leaves the remainder's.
        targets[k] = 0.0;
        dirtyRes[k] = 0x1p-32 * inv;
        j = tree.pick(box.node, box.part, u, targets[k], dirtyRes[k]);
      }
      picked[k] = j;
    }
    for (uint32_t k = 0; k < n; ++k) {
      const uint64_t i = s0 + k;
      if (k + kWalkAhead < n) tree.prefetchRec(uint32_t(picked[k + kWalkAhead]));
      j = picked[k];
      float a = unit24(d.w[2][k]), c = unit24(d.w[3][k]);
      foldUnitSquare(a, c);
      double rem = 0.0, res = 0x1p-32 * inv;
      if (clean) {
        if (recs[j].instance()) {
          const double target = targets[k];
          if (j != splitEntry) {
            splitEntry = j;
            before = j ? P[j - 1] : 0.0;
            const double area = P[j] - before;
            ia = area > 0.0 ? 1.0 / area : 0.0;
          }
          rem = ia > 0.0 ? glm::clamp((target - before) * ia, 0.0, 1.0 - 0x1p-53) : 0.5;
          res = ia > 0.0 ? (span * res + top * 0x1p-52) * ia : 1.0;
        }
      } else {
        rem = targets[k];
        res = dirtyRes[k];
      }
      const EntryRec& r = recs[j];
      if (!r.instance()) {
        // In float, as exact as the vertices themselves; the transform to camera space is double.
        const glm::vec3 p = r.v0 + a * r.e1 + c * r.e2;
        if constexpr (kCamera) {
          land(sink, glm::dvec3(p), glm::dvec3(glm::cross(r.e1, r.e2)), box.eyeLocal, box.toCamera,
               box.idBase + r.ref);
        } else {
          sink(glm::dvec3(p), glm::dvec3(glm::cross(r.e1, r.e2)), box.idBase + r.ref, &tree, r.ref);
        }
        continue;
      }
      if constexpr (kCamera) {
        if (const LeafGroups::Run* run =
                leaves.enter(tree, r.index(), box.toCamera, box.eyeLocal, box.idBase)) {
          // As enterEntry refreshes a pick number left with fewer than 16 bits.
          if (res > 0x1p-16) rem = (double(d.w[1][k]) + 0.5) * 0x1p-32;
          leaves.add(*run, rem, a, c, sink);
          continue;
        }
      }
      startDescent(group[grouped++], &tree, r.index(), rem, res, d.w[1][k], box.idBase, i, a, c);
      if (grouped == kDescentGroup) descend();
    }
    descend();
    if constexpr (kCamera) leaves.flush(sink);
    // A sink may buffer a batch (e.g. to splat it after the tree lookups, so the two working sets
    // do not evict each other from the cache).
    if constexpr (requires { sink.flush(); }) sink.flush();
  }
}

}  // namespace lzb::rzb
