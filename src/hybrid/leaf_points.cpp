#include "src/hybrid/leaf_points.hpp"

#include <algorithm>
#include <cmath>

#include "src/core/affine.hpp"
#include "src/core/area_sampling.hpp"

namespace lzb::hybrid {

namespace {

// A sampled leaf never gets more samples than this many image-covering layers (as rzb's boxes).
constexpr double kMaxLayers = 16.0;
// Samples per job: the unit of threads.
constexpr uint64_t kJobSamples = 1 << 14;
// Philox words are drawn this many samples at a time (vectorized).
constexpr uint32_t kBatch = 4096;

uint64_t leafKey(uint64_t idBase, uint32_t node, uint32_t leaf) {
  return hashCombine(hashCombine(mix64(idBase), node), leaf);
}

// A job: samples [first, first + count) of one leaf, or every sample of leaves [begin, end)
// (small leaves go together, so a job always carries about kJobSamples samples).
struct Job {
  uint32_t begin, end;  // positions in `mine`
  uint64_t first, count;
};

// A path's node frame -> camera space, and the eye in the node frame.
struct PathView {
  Affine toCamera;
  glm::dvec3 eyeLocal;
};

PathView pathView(const localz::CullPath& path, const Camera& camera) {
  const Affine world = Affine::from(path.world);
  const Affine cam = worldToCamera(camera.position(), camera.right(), camera.up(), camera.forward());
  const glm::dmat4 inverse = glm::inverse(path.world);
  return {cam * world, glm::dvec3(inverse * glm::dvec4(camera.position(), 1.0))};
}

std::vector<Job> makeJobs(std::span<const SampledLeaf> leaves, std::span<const uint32_t> mine) {
  std::vector<Job> jobs;
  uint32_t begin = 0;
  uint64_t pending = 0;
  for (uint32_t k = 0; k < mine.size(); ++k) {
    const uint64_t n = leaves[mine[k]].samples;
    if (n >= kJobSamples) {  // a large leaf: jobs of its own
      if (pending) jobs.push_back({begin, k, 0, pending});
      for (uint64_t first = 0; first < n; first += kJobSamples)
        jobs.push_back({k, k + 1, first, std::min(kJobSamples, n - first)});
      begin = k + 1, pending = 0;
      continue;
    }
    pending += n;
    if (pending >= kJobSamples) {
      jobs.push_back({begin, k + 1, 0, pending});
      begin = k + 1, pending = 0;
    }
  }
  if (pending) jobs.push_back({begin, uint32_t(mine.size()), 0, pending});
  return jobs;
}

// A uniform point of triangle t from two Philox words, splatted with its expanded ID unless it
// faces away from the eye (given in the mesh's frame).
template <class Splatter>
void splatPoint(const Mesh& mesh, uint32_t t, uint32_t wa, uint32_t wc, const Affine& toCamera,
                const glm::dvec3& eyeLocal, uint64_t idBase, bool dropBackfaces, Splatter& out,
                uint64_t& back) {
  float a = unit24(wa), c = unit24(wc);
  foldUnitSquare(a, c);
  const glm::vec3& v0 = mesh.vertex(t, 0);
  const glm::vec3 p = v0 + a * (mesh.vertex(t, 1) - v0) + c * (mesh.vertex(t, 2) - v0);
  if (dropBackfaces && glm::dot(glm::dvec3(mesh.normal(t)), eyeLocal - glm::dvec3(p)) < 0.0) {
    ++back;
    return;
  }
  const glm::dvec3 q = toCamera.point(glm::dvec3(p));
  out.add(float(q.x), float(q.y), float(q.z), idBase + t);
}

// Splats samples [first, first + count) of one leaf.
template <class Splatter>
void splatLeaf(const localz::LzbAccel& accel, const LeafAreas& areas, const localz::CullPath& path,
               const PathView& view, const SampledLeaf& sl, uint64_t first, uint64_t count,
               const PointParams& params, const SampleStream& stream, std::vector<uint32_t> (&w)[4],
               Splatter& out, uint64_t& back) {
  const Mesh& mesh = accel.scene().nodes[path.node].mesh;
  const bool whole = sl.leaf == kWholeNode;
  const std::span<const uint32_t> tris =
      whole ? areas.nodeOrder(path.node) : areas.order(path.node, sl.leaf);
  const std::span<const double> prefix =
      whole ? areas.nodePrefix(path.node) : areas.prefix(path.node, sl.leaf);
  const double total = prefix.back(), inv = 1.0 / double(sl.samples);
  uint64_t j = 0;
  for (uint64_t s0 = first; s0 < first + count; s0 += kBatch) {
    const uint32_t m = uint32_t(std::min<uint64_t>(kBatch, first + count - s0));
    philoxBatch(stream, sl.key, s0, m, w[0].data(), w[1].data(), w[2].data(), w[3].data());
    for (uint32_t i = 0; i < m; ++i) {
      // Stratum s0 + i of the leaf's area, jittered; a uniform point of its triangle.
      const double jitter = (double(w[0][i]) + 0.5) * 0x1p-32;
      const double u = std::min((double(s0 + i) + jitter) * inv, 1.0 - 0x1p-53);
      j = searchForward(prefix.data(), prefix.size(), j, u * total);
      splatPoint(mesh, tris[j], w[2][i], w[3][i], view.toCamera, view.eyeLocal, path.idBase,
                 params.dropBackfaces, out, back);
    }
  }
}

// One level of a subtree unit's descent: a placed node covering [lo, hi) of the unit's area
// coordinate, lo + scale x its own area coordinate.
struct SubtreeLevel {
  uint32_t node;
  Affine toCamera;
  glm::dvec3 eyeLocal;
  uint64_t idBase;
  double lo, scale, hi;
  uint64_t tri, entry;  // search positions in its triangles and flat entries (targets grow)
};

// The first k in [from, n) with lo + P[k] x scale > target (n - 1 if none): a forward gallop,
// the boundaries computed as the descent's levels compute theirs.
uint64_t firstAbove(const double* P, uint64_t n, uint64_t from, double lo, double scale,
                    double target) {
  const auto above = [&](uint64_t k) { return lo + P[k] * scale > target; };
  uint64_t step = 1, k = from;
  while (k < n && !above(k)) {
    const uint64_t next = std::min(n, k + step);
    if (next == n || above(next - 1)) {
      for (uint64_t hi = next; k + 1 < hi;) {  // above(hi - 1) or hi == n; !above(k)
        const uint64_t mid = k + (hi - k) / 2;
        if (above(mid)) hi = mid; else k = mid;
      }
      return std::min(k + 1, n - 1);
    }
    k = next;
    step <<= 1;
  }
  return std::min(k, n - 1);
}

// Splats samples [first, first + count) of a subtree unit: sample i's stratum of the unit's area
// is found by descending through the (flattened) instances by their area shares to one node's
// triangles. The previous sample's descent is kept while the next target stays below each
// level's upper boundary, the value the descent compared it with, so a sample's triangle never
// depends on where its job began.
template <class Splatter>
void splatSubtree(const localz::LzbAccel& accel, const LeafAreas& areas,
                  const localz::CullPath& path, const PathView& view, const SampledLeaf& sl,
                  uint64_t first, uint64_t count, const PointParams& params,
                  const SampleStream& stream, std::vector<uint32_t> (&w)[4],
                  std::vector<SubtreeLevel>& stack, Splatter& out, uint64_t& back) {
  const Scene& scene = accel.scene();
  const double total = areas.subtreeArea(path.node), inv = 1.0 / double(sl.samples);
  stack.assign(1, {path.node, view.toCamera, view.eyeLocal, path.idBase, 0.0, 1.0,
                   std::numeric_limits<double>::infinity(), 0, 0});
  for (uint64_t s0 = first; s0 < first + count; s0 += kBatch) {
    const uint32_t m = uint32_t(std::min<uint64_t>(kBatch, first + count - s0));
    philoxBatch(stream, sl.key, s0, m, w[0].data(), w[1].data(), w[2].data(), w[3].data());
    for (uint32_t i = 0; i < m; ++i) {
      const double jitter = (double(w[0][i]) + 0.5) * 0x1p-32;
      const double target = std::min((double(s0 + i) + jitter) * inv, 1.0 - 0x1p-53) * total;
      size_t keep = 1;  // root first: the levels that still hold the target
      while (keep < stack.size() && target < stack[keep].hi) ++keep;
      stack.resize(keep);
      for (;;) {  // down to the node whose own triangles hold the target
        SubtreeLevel& l = stack.back();
        const std::span<const double> P = areas.flatPrefix(l.node);
        if (P.size() == 1 || l.lo + P[0] * l.scale > target) break;
        // Entry k covers [P[k], P[k + 1]): the first with its upper boundary above the target,
        // never one of weight 0 (an unusable instance) at the end.
        uint64_t k = firstAbove(P.data() + 1, P.size() - 1, l.entry, l.lo, l.scale, target);
        while (k > 0 && P[k + 1] == P[k]) --k;
        l.entry = k;
        const LeafAreas::FlatInstance& e = areas.flat(l.node)[k];
        const SubtreeLevel child{e.node,
                          l.toCamera * e.transform,
                          e.inverse.point(l.eyeLocal),
                          l.idBase + e.idOffset,
                          l.lo + P[k] * l.scale,
                          l.scale * (P[k + 1] - P[k]) / areas.subtreeArea(e.node),
                          l.lo + P[k + 1] * l.scale,
                          0,
                          0};
        stack.push_back(child);
      }
      SubtreeLevel& l = stack.back();
      const std::span<const double> prefix = areas.nodePrefix(l.node);
      const double local = (target - l.lo) / l.scale;
      l.tri = searchForward(prefix.data(), prefix.size(),
                            std::max(l.tri, areas.nodeGuide(l.node, local)), local);
      splatPoint(scene.nodes[l.node].mesh, areas.nodeOrder(l.node)[l.tri], w[2][i], w[3][i],
                 l.toCamera, l.eyeLocal, l.idBase, params.dropBackfaces, out, back);
    }
  }
}

template <bool kWide, bool kPixel>
PointCounts runJobs(const localz::LzbAccel& accel, const LeafAreas& areas,
                    const localz::CulledScene& culled, std::span<const SampledLeaf> leaves,
                    std::span<const uint32_t> mine, const std::vector<Job>& jobs,
                    const std::vector<PathView>& views, const Camera& camera,
                    const PointParams& params, const SampleStream& stream, KeyBuffer& keys,
                    int threads) {
  const SplatSetup setup = SplatSetup::from(camera, params.splat);
  uint64_t drawn = 0, back = 0, splatted = 0;
  const long n = long(jobs.size());
#pragma omp parallel num_threads(threads) reduction(+ : drawn, back, splatted)
  {
    PointSplatter<kWide, kPixel> out(setup, keys);
    std::vector<uint32_t> w[4];
    for (auto& v : w) v.resize(kBatch);
    std::vector<SubtreeLevel> stack;
#pragma omp for schedule(dynamic, 1)
    for (long k = 0; k < n; ++k) {
      const Job& job = jobs[size_t(k)];
      for (uint32_t m = job.begin; m < job.end; ++m) {
        const SampledLeaf& sl = leaves[mine[m]];
        const bool part = job.end == job.begin + 1;
        const uint64_t from = part ? job.first : 0, n = part ? job.count : sl.samples;
        if (sl.leaf == kSubtree)
          splatSubtree(accel, areas, culled.paths[sl.path], views[sl.path], sl, from, n, params,
                       stream, w, stack, out, back);
        else
          splatLeaf(accel, areas, culled.paths[sl.path], views[sl.path], sl, from, n, params,
                    stream, w, out, back);
      }
      drawn += job.count;
    }
    out.flush();
    splatted += out.splatted();
  }
  return {drawn, back, splatted};
}

}  // namespace

bool SampledLeafRule::sampled(uint32_t node, uint32_t leaf, double depthMin, double areaScale) const {
  if (!(depthMin >= zClip_) || depthMin <= 0.0) return false;
  const double ppu = pixelScale_ / depthMin;
  return areas_.maxArea(node, leaf) * areaScale * ppu * ppu < thresholdPx_;
}

bool SampledLeafRule::mayTakeLeaves(uint32_t node, const localz::LeafPlacement& p) const {
  double lo, hi;
  localz::depthRange(accel_.node(node).contentBox(0), p.depthGrad, p.depthOffset, lo, hi);
  if (!(hi >= zClip_) || hi <= 0.0) return false;  // every leaf's nearest depth is at most hi
  const double ppu = pixelScale_ / hi;
  return areas_.leastLeafMaxArea(node) * p.areaScale * ppu * ppu < thresholdPx_;
}

bool SampledLeafRule::drawnElsewhere(uint32_t node, uint32_t leaf,
                                     const localz::LeafPlacement& p) const {
  double lo, hi;
  localz::depthRange(accel_.node(node).contentBox(leaf), p.depthGrad, p.depthOffset, lo, hi);
  return sampled(node, leaf, lo, p.areaScale);
}

bool SampledLeafRule::wholeUnit(const Bounds& box, double maxArea,
                                const localz::LeafPlacement& p) const {
  double lo, hi;
  localz::depthRange(box, p.depthGrad, p.depthOffset, lo, hi);
  if (!(lo > 0.0) || (hi / lo) * (hi / lo) > kNodeDepthRatio) return false;
  const double ppu = pixelScale_ / lo;
  return maxArea * p.areaScale * ppu * ppu < thresholdPx_;
}

bool SampledLeafRule::nodeDrawnElsewhere(uint32_t node, const localz::LeafPlacement& p) const {
  const localz::NodeAccel& a = accel_.node(node);
  if (a.empty() || accel_.scene().nodes[node].mesh.empty()) return false;
  return wholeUnit(a.contentBox(0), areas_.nodeMaxArea(node), p);  // the root's: all triangles
}

bool SampledLeafRule::subtreeDrawnElsewhere(uint32_t node, const localz::LeafPlacement& p) const {
  if (accel_.node(node).empty() || accel_.scene().nodes[node].instances.empty()) return false;
  return wholeUnit(accel_.scene().nodeBounds[node], areas_.subtreeMaxArea(node), p);
}

SampledUnits sampledLeaves(const localz::LzbAccel& accel, const LeafAreas& areas,
                           const localz::CulledScene& culled, const SampledLeafRule& rule,
                           const Camera& camera, const PointParams& params,
                           const SampleStream& stream) {
  const double pixels = double(camera.width()) * double(camera.height());
  const double maxSamples = kMaxLayers * pixels * params.samplesPerPixel;
  SampledUnits out;
  // A unit gets area x areaScale x (pixels per unit at depthMin)^2 x spp samples, stochastically
  // rounded by a Philox number keyed by the unit: the expected count on average.
  const auto add = [&](uint32_t path, uint32_t leaf, double area, double areaScale,
                       double depthMin) {
    const localz::CullPath& p = culled.paths[path];
    const double ppu = camera.pixelsPerUnitAt(depthMin);
    const double expected =
        std::min(maxSamples, area * areaScale * ppu * ppu * params.samplesPerPixel);
    const uint64_t key = leafKey(p.idBase, p.node, leaf);
    const auto w = stream.draw(key, 0, kBoxRounding);
    const double whole = std::floor(expected);
    const uint64_t samples = uint64_t(whole) + (unit53(w[0], w[1]) < expected - whole ? 1 : 0);
    ++out.accepted;
    if (samples > 0) out.leaves.push_back({path, leaf, key, samples, depthMin});
  };
  for (uint32_t path = 0; path < culled.paths.size(); ++path) {
    const localz::CullPath& p = culled.paths[path];
    const localz::LeafPlacement placement{p.depthGrad, p.depthOffset,
                                          maxAreaScale(glm::dmat3(p.world))};
    const bool whole = p.drawnElsewhere;  // the cull applied the whole-node rule
    const bool leaves = !whole && !p.subtree && rule.mayTakeLeaves(p.node, placement);
    if (p.subtree) {
      double lo, hi;
      localz::depthRange(accel.scene().nodeBounds[p.node], p.depthGrad, p.depthOffset, lo, hi);
      areas.prepareSampling();
      add(path, kSubtree, areas.subtreeArea(p.node), placement.areaScale, lo);
    } else if (whole) {
      double lo, hi;
      localz::depthRange(accel.node(p.node).contentBox(0), p.depthGrad, p.depthOffset, lo, hi);
      areas.prepareSampling();
      add(path, kWholeNode, areas.nodePrefix(p.node).back(), placement.areaScale, lo);
    }
    if (!leaves) continue;
    for (uint32_t l = p.firstLeaf; l < p.firstLeaf + p.leafCount; ++l) {
      const localz::CullLeaf& leaf = culled.leaves[l];
      if (!rule.sampled(p.node, leaf.leaf, leaf.depthMin, placement.areaScale)) continue;
      areas.prepareSampling();
      add(path, leaf.leaf, areas.total(p.node, leaf.leaf), placement.areaScale, leaf.depthMin);
    }
  }
  return out;
}

PointCounts splatLeaves(const localz::LzbAccel& accel, const LeafAreas& areas,
                        const localz::CulledScene& culled, std::span<const SampledLeaf> leaves,
                        std::span<const uint32_t> mine, const Camera& camera,
                        const PointParams& params, const SampleStream& stream, KeyBuffer& keys,
                        int threads) {
  const std::vector<Job> jobs = makeJobs(leaves, mine);
  // Every path's view once per frame (paths without sampled leaves of this rank stay unset).
  std::vector<PathView> views(culled.paths.size());
  std::vector<uint8_t> used(culled.paths.size(), 0);
  for (uint32_t i : mine) used[leaves[i].path] = 1;
  const long paths = long(views.size());
#pragma omp parallel for schedule(static) num_threads(threads)
  for (long p = 0; p < paths; ++p)
    if (used[size_t(p)]) views[size_t(p)] = pathView(culled.paths[size_t(p)], camera);
  return withSplatter(keys, params.splat, [&]<bool kWide, bool kPixel>() {
    return runJobs<kWide, kPixel>(accel, areas, culled, leaves, mine, jobs, views, camera, params,
                                  stream, keys, threads);
  });
}

}  // namespace lzb::hybrid
