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

namespace {

// Too few bits of the pick number are left: the sample's spare word, then fresh Philox draws.
__attribute__((noinline)) void refresh(Descent& d, const SampleStream& stream, uint64_t boxKey) {
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

}  // namespace

void enterEntry(Descent& d, const SampleStream& stream, uint64_t boxKey) {
  const DistributionTree* tree = d.tree;
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
  if (d.res > 0x1p-16) refresh(d, stream, boxKey);
  // The whole-list pick: the alias table when the tree has one (O(1), no division).
  if (const size_t size = tree->aliasSize()) {
    const double x = d.rem * double(size);
    d.pos = uint32_t(std::min(x, double(size - 1)));
    d.rem = x - double(d.pos);
    tree->prefetchAliasSlot(d.pos);
    return;
  }
  double next;
  d.pos = tree->pickWhole(d.rem, next, d.res);
  d.rem = next;
  d.ref = tree->rec(d.pos).ref;
}

void finishDescent(const Descent& d, DescentHit& hit) {
  const DistributionTree* tree = d.tree;
  const EntryRec& e = tree->rec(d.pos);
  glm::dvec3 v0(e.v0), e1(e.e1), e2(e.e2);
  if (d.linear) {
    v0 = d.A * v0;
    e1 = d.A * e1;
    e2 = d.A * e2;
  }
  v0 += d.t;
  hit.p = v0 + double(d.a) * e1 + double(d.c) * e2;
  // cross(A e1, A e2) = det(A) A^-T (e1 x e2): the sign of det restores the normal's side.
  hit.n = double(d.sign) * glm::cross(e1, e2);
  hit.id = d.id + e.ref;
  hit.leaf = tree;
  hit.meshIndex = e.ref;
}

}  // namespace lzb::rzb
