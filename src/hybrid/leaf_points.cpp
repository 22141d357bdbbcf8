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

PathView pathView(const CullPath& path, const Camera& camera) {
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

// Splats samples [first, first + count) of one leaf.
template <class Splatter>
void splatLeaf(const LzbAccel& accel, const LeafAreas& areas, const CullPath& path,
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
      const uint32_t t = tris[j];
      float a = unit24(w[2][i]), c = unit24(w[3][i]);
      foldUnitSquare(a, c);
      const glm::vec3& v0 = mesh.vertex(t, 0);
      const glm::vec3 p = v0 + a * (mesh.vertex(t, 1) - v0) + c * (mesh.vertex(t, 2) - v0);
      if (params.dropBackfaces &&
          glm::dot(glm::dvec3(mesh.normals[t]), view.eyeLocal - glm::dvec3(p)) < 0.0) {
        ++back;
        continue;
      }
      const glm::dvec3 q = view.toCamera.point(glm::dvec3(p));
      out.add(float(q.x), float(q.y), float(q.z), path.idBase + t);
    }
  }
}

template <bool kWide, bool kPixel>
PointCounts runJobs(const LzbAccel& accel, const LeafAreas& areas, const CulledScene& culled,
                    std::span<const SampledLeaf> leaves, std::span<const uint32_t> mine,
                    const std::vector<Job>& jobs, const std::vector<PathView>& views,
                    const Camera& camera, const PointParams& params, const SampleStream& stream,
                    KeyBuffer& keys, int threads) {
  const SplatSetup setup = SplatSetup::from(camera, params.splat);
  uint64_t drawn = 0, back = 0, splatted = 0;
  const long n = long(jobs.size());
#pragma omp parallel num_threads(threads) reduction(+ : drawn, back, splatted)
  {
    PointSplatter<kWide, kPixel> out(setup, keys);
    std::vector<uint32_t> w[4];
    for (auto& v : w) v.resize(kBatch);
#pragma omp for schedule(dynamic, 1)
    for (long k = 0; k < n; ++k) {
      const Job& job = jobs[size_t(k)];
      for (uint32_t m = job.begin; m < job.end; ++m) {
        const SampledLeaf& sl = leaves[mine[m]];
        const bool part = job.end == job.begin + 1;
        splatLeaf(accel, areas, culled.paths[sl.path], views[sl.path], sl, part ? job.first : 0,
                  part ? job.count : sl.samples, params, stream, w, out, back);
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

bool SampledLeafRule::drawnElsewhere(uint32_t node, uint32_t leaf, const LeafPlacement& p) const {
  double lo, hi;
  depthRange(accel_.node(node).contentBox(leaf), p.depthGrad, p.depthOffset, lo, hi);
  return sampled(node, leaf, lo, p.areaScale);
}

bool SampledLeafRule::nodeDrawnElsewhere(uint32_t node, const LeafPlacement& p) const {
  const NodeAccel& a = accel_.node(node);
  if (a.empty() || accel_.scene().nodes[node].mesh.empty()) return false;
  double lo, hi;
  depthRange(a.contentBox(0), p.depthGrad, p.depthOffset, lo, hi);  // the root's: all triangles
  if (!(lo > 0.0) || (hi / lo) * (hi / lo) > kNodeDepthRatio) return false;
  const double ppu = pixelScale_ / lo;
  return areas_.nodeMaxArea(node) * p.areaScale * ppu * ppu < thresholdPx_;
}

SampledUnits sampledLeaves(const LzbAccel& accel, const LeafAreas& areas,
                           const CulledScene& culled, const SampledLeafRule& rule,
                           const Camera& camera, const PointParams& params,
                           const SampleStream& stream) {
  const double pixels = double(camera.width()) * double(camera.height());
  const double maxSamples = kMaxLayers * pixels * params.samplesPerPixel;
  SampledUnits out;
  // A unit gets area x areaScale x (pixels per unit at depthMin)^2 x spp samples, stochastically
  // rounded by a Philox number keyed by the unit: the expected count on average.
  const auto add = [&](uint32_t path, uint32_t leaf, double area, double areaScale, double depthMin) {
    const CullPath& p = culled.paths[path];
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
  size_t l = 0;  // culled.leaves are grouped by path, in path order
  for (uint32_t path = 0; path < culled.paths.size(); ++path) {
    const CullPath& p = culled.paths[path];
    const LeafPlacement placement{p.depthGrad, p.depthOffset, maxAreaScale(glm::dmat3(p.world))};
    const bool whole = p.drawnElsewhere;  // the cull applied the whole-node rule
    if (whole) {
      double lo, hi;
      depthRange(accel.node(p.node).contentBox(0), p.depthGrad, p.depthOffset, lo, hi);
      const std::span<const double> prefix = areas.nodePrefix(p.node);
      add(path, kWholeNode, prefix.back(), placement.areaScale, lo);
    }
    for (; l < culled.leaves.size() && culled.leaves[l].path == path; ++l) {
      const CullLeaf& leaf = culled.leaves[l];
      if (!whole && rule.sampled(p.node, leaf.leaf, leaf.depthMin, placement.areaScale))
        add(path, leaf.leaf, areas.total(p.node, leaf.leaf), placement.areaScale, leaf.depthMin);
    }
  }
  return out;
}

PointCounts splatLeaves(const LzbAccel& accel, const LeafAreas& areas, const CulledScene& culled,
                        std::span<const SampledLeaf> leaves, std::span<const uint32_t> mine,
                        const Camera& camera, const PointParams& params,
                        const SampleStream& stream, KeyBuffer& keys, int threads) {
  const std::vector<Job> jobs = makeJobs(leaves, mine);
  // Every path's view once per frame (paths without sampled leaves of this rank stay unset).
  std::vector<PathView> views(culled.paths.size());
  std::vector<uint8_t> used(culled.paths.size(), 0);
  for (uint32_t i : mine) used[leaves[i].path] = 1;
  const long paths = long(views.size());
#pragma omp parallel for schedule(static) num_threads(threads)
  for (long p = 0; p < paths; ++p)
    if (used[size_t(p)]) views[size_t(p)] = pathView(culled.paths[size_t(p)], camera);
  const bool pixel = params.splat == 1;
  if (keys.wide())
    return pixel ? runJobs<true, true>(accel, areas, culled, leaves, mine, jobs, views, camera, params, stream, keys, threads)
                 : runJobs<true, false>(accel, areas, culled, leaves, mine, jobs, views, camera, params, stream, keys, threads);
  return pixel ? runJobs<false, true>(accel, areas, culled, leaves, mine, jobs, views, camera, params, stream, keys, threads)
               : runJobs<false, false>(accel, areas, culled, leaves, mine, jobs, views, camera, params, stream, keys, threads);
}

}  // namespace lzb::hybrid
