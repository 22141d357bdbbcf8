#include "src/rzb/box_sampler.hpp"

#include <algorithm>
#include <vector>

namespace lzb::rzb {

DrawWords batchDraws(const SampleStream& stream, uint64_t boxKey, uint64_t first, uint32_t n) {
  struct Scratch {
    std::vector<uint32_t> w[4];
    Scratch() {
      for (auto& v : w) v.resize(kDrawBatch);
    }
  };
  thread_local Scratch s;
  philoxBatch(stream, boxKey, first, n, s.w[0].data(), s.w[1].data(), s.w[2].data(), s.w[3].data());
  return DrawWords{{s.w[0].data(), s.w[1].data(), s.w[2].data(), s.w[3].data()}};
}

bool descendStep(Descent& d, const SampleStream& stream, uint64_t boxKey, glm::dvec3& p,
                 glm::dvec3& n, const SampleTree*& leaf, uint32_t& meshIndex) {
  const SampleTree* tree = d.tree;
  const InstanceHot& r = tree->instanceHot(d.instance);
  if (d.linear) {
    d.t += d.A * r.t;
  } else {
    d.t += r.t;
  }
  if (r.linear) {
    const glm::dmat3& L = tree->instance(r.linear - 1).transform.a;
    d.A = d.linear ? d.A * L : L;
    d.linear = true;
  }
  d.sign *= r.detSign;
  d.id += r.idOffset;
  tree = r.child;
  d.tree = tree;
  if (d.res > 0x1p-16) {
    // Too few bits of the pick number are left: the sample's spare word, then fresh Philox draws.
    if (d.level == 0) {
      d.rem = (double(d.spare) + 0.5) * 0x1p-32;
      d.res = 0x1p-32;
      d.level = 1;
    } else {
      const auto w = stream.draw(boxKey, d.index, kRefreshDraw + (d.level++ & 0xff));
      d.rem = unit53(w[0], w[1]);
      d.res = 0x1p-53;
    }
  }
  // The whole-list pick: the alias table when the tree has one (O(1), no division).
  uint32_t pos, ref;
  if (const size_t size = tree->aliasSize()) {
    const AliasSlot* table = tree->aliasTable();
    const double x = d.rem * double(size);
    const uint32_t i = uint32_t(std::min(x, double(size - 1)));
    const double f = x - double(i);
    const AliasSlot& slot = table[i];
    const bool keep = f < slot.prob;
    const double scale = keep ? slot.keepScale : slot.altScale;
    d.rem = std::min((keep ? f : f - slot.prob) * scale, 1.0 - 0x1p-53);
    d.res *= double(size) * scale;
    pos = keep ? i : slot.alias;
    ref = keep ? slot.keepRef : slot.altRef;
  } else {
    double next;
    pos = tree->pickWhole(d.rem, next, d.res);
    d.rem = next;
    ref = tree->rec(pos).ref;
  }
  if (ref & kInstanceBit) {
    d.instance = ref & ~kInstanceBit;
    return false;
  }
  const EntryRec& e = tree->rec(pos);
  glm::dvec3 v0(e.v0), e1(e.e1), e2(e.e2);
  if (d.linear) {
    v0 = d.A * v0;
    e1 = d.A * e1;
    e2 = d.A * e2;
  }
  v0 += d.t;
  p = v0 + double(d.a) * e1 + double(d.c) * e2;
  // cross(A e1, A e2) = det(A) A^-T (e1 x e2): the sign of det restores the normal's side.
  n = double(d.sign) * glm::cross(e1, e2);
  d.id += e.ref;
  leaf = tree;
  meshIndex = e.ref;
  return true;
}

void descendInstance(const SampleTree* tree, uint32_t instance, double rem, double res,
                     uint32_t spare, const SampleStream& stream, uint64_t boxKey, uint64_t index,
                     float a, float b, glm::dvec3& p, glm::dvec3& n, uint64_t& id,
                     const SampleTree*& leaf, uint32_t& meshIndex) {
  Descent d{glm::dmat3(1.0), glm::dvec3(0.0), rem, res, id, index, tree, instance, 0, spare, a, b,
            1.0f, false};
  while (!descendStep(d, stream, boxKey, p, n, leaf, meshIndex)) {
  }
  id = d.id;
}

}  // namespace lzb::rzb
