#include "raycast/lzb/lzb_plane.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace lzb::localz {

std::pair<int, int> PartitionPlane::coarseGrid(const Camera& camera, int grid) {
  return {std::clamp(grid, 1, camera.width()), std::clamp(grid, 1, camera.height())};
}

std::vector<double> PartitionPlane::coarseRayDepths(const EmbreeScene& embree, const Camera& camera,
                                                    int grid, int threads) {
  const auto [gx, gy] = coarseGrid(camera, grid);
  std::vector<Ray> rays;
  rays.reserve(size_t(gx) * size_t(gy));
  for (int j = 0; j < gy; ++j)
    for (int i = 0; i < gx; ++i) {
      const double px = (i + 0.5) * camera.width() / gx, py = (j + 0.5) * camera.height() / gy;
      rays.push_back({camera.position(), camera.pixelDirection(px, py), camera.nearPlane(),
                      camera.farPlane()});
    }
  std::vector<RayHit> hits(rays.size());
  // Blocks of rays on the threads (each ray on its own: the same hits for any thread count).
  constexpr size_t kBlock = 128;
  const long blocks = long((rays.size() + kBlock - 1) / kBlock);
#pragma omp parallel for schedule(dynamic, 1) num_threads(std::max(threads, 1)) if (blocks > 1)
  for (long b = 0; b < blocks; ++b) {
    const size_t first = size_t(b) * kBlock, count = std::min(kBlock, rays.size() - first);
    embree.intersect(std::span<const Ray>(rays).subspan(first, count),
                     std::span<RayHit>(hits).subspan(first, count));
  }
  std::vector<double> depths(hits.size());
  for (size_t k = 0; k < hits.size(); ++k)  // t is the view depth (forward component 1)
    depths[k] = hits[k].hit() ? double(hits[k].t) : std::numeric_limits<double>::infinity();
  return depths;
}

CoarseHits PartitionPlane::coarseHitsOf(std::span<const double> perRay, const Camera& camera) {
  CoarseHits c;
  c.mean.coarseRays = perRay.size();
  double sum = 0.0;
  for (double t : perRay)
    if (std::isfinite(t)) {
      sum += t;
      ++c.mean.coarseHits;
      c.depths.push_back(t);
    }
  c.mean.depth = c.mean.coarseHits ? sum / double(c.mean.coarseHits) : camera.farPlane();
  c.mean.depth = std::clamp(c.mean.depth, camera.nearPlane(), camera.farPlane());
  return c;
}

PlaneDecision PartitionPlane::coarseRayCast(const EmbreeScene& embree, const Camera& camera,
                                            int grid, std::vector<double>* hitDepths, int threads) {
  CoarseHits c = coarseHitsOf(coarseRayDepths(embree, camera, grid, threads), camera);
  if (hitDepths) hitDepths->insert(hitDepths->end(), c.depths.begin(), c.depths.end());
  return c.mean;
}

namespace {

// Near triangles per candidate: [0] leaves starting before the near plane, [k + 1] leaves whose
// start is first exceeded by candidate hits[k] (sorted); candidates from there on draw them.
std::vector<uint64_t> nearHistogram(const std::vector<double>& hits, double nearPlane,
                                    std::span<const LeafLoad> loads, int threads) {
  const size_t n = hits.size();
  std::vector<uint64_t> near(n + 1, 0);
  const long count = long(loads.size());
#pragma omp parallel num_threads(std::max(threads, 1)) if (count >= 65536)
  {
    std::vector<uint64_t> part(n + 1, 0);
#pragma omp for schedule(static) nowait
    for (long i = 0; i < count; ++i) {
      const LeafLoad& l = loads[size_t(i)];
      const size_t k =
          size_t(std::upper_bound(hits.begin(), hits.end(), l.depthMin) - hits.begin());
      if (l.depthMin < nearPlane)
        part[0] += l.triangles;
      else if (k < n)
        part[k + 1] += l.triangles;
    }
#pragma omp critical
    for (size_t k = 0; k <= n; ++k) near[k] += part[k];
  }
  return near;
}

}  // namespace

double PartitionPlane::costPlane(std::vector<double> hits, uint64_t rays, const Camera& camera,
                                 std::span<const LeafLoad> loads, double rayCost, int threads,
                                 double* cost) {
  double ignored;
  if (!cost) cost = &ignored;
  if (hits.empty() || rays == 0) {
    // No coarse ray hit (sparse or sub-pixel geometry slips between them): every pixel may still
    // need a ray, so weigh the whole near scene against a ray for every pixel.
    double triangles = 0.0;
    for (const LeafLoad& l : loads) triangles += l.triangles;
    const double pixels = double(camera.width()) * double(camera.height());
    *cost = std::min(triangles, rayCost * pixels);
    return triangles <= rayCost * pixels ? camera.farPlane() : camera.nearPlane();
  }
  std::sort(hits.begin(), hits.end());
  // Candidate k: z = hits[k - 1] (k = 0: the near plane); its near triangles are the prefix sums
  // of the histogram of leaf starts.
  const size_t n = hits.size();
  std::vector<uint64_t> near = nearHistogram(hits, camera.nearPlane(), loads, threads);
  for (size_t k = 1; k <= n; ++k) near[k] += near[k - 1];
  const double pixelsPerRay = double(camera.width()) * double(camera.height()) / double(rays);
  double best = std::numeric_limits<double>::infinity(), z = camera.nearPlane();
  for (size_t k = 0; k <= n; ++k) {
    const double unfinished = double(n - k) * pixelsPerRay;  // hits beyond the candidate
    const double cost = double(near[k]) + rayCost * unfinished;
    if (cost < best) {
      best = cost;
      z = k == 0 ? camera.nearPlane() : hits[k - 1];
    }
  }
  *cost = best;
  return std::clamp(z, camera.nearPlane(), camera.farPlane());
}

bool PartitionPlane::stillValid(const Camera& c) const {
  if (!have_ || uses_ >= options_.planeReuse) return false;
  if (c.width() != at_.width() || c.height() != at_.height() ||
      c.fovyDegrees() != at_.fovyDegrees())
    return false;
  if (glm::length(c.position() - at_.position()) > kReuseMove * depth_) return false;
  const double cosTurn = std::clamp(glm::dot(c.forward(), at_.forward()), -1.0, 1.0);
  const double turnDegrees = std::acos(cosTurn) * 180.0 / 3.14159265358979323846;
  if (turnDegrees > kReuseTurn * c.fovyDegrees()) return false;
  const double pixels = double(c.width()) * double(c.height());
  if (observed_ &&
      double(lastUnfinished_) > kReuseGrowth * double(unfinishedAtCompute_) + kReuseSlack * pixels)
    return false;
  return true;
}

PlaneDecision PartitionPlane::place(const EmbreeScene& embree, const Camera& camera,
                                    std::span<const LeafLoad> loads, int threads,
                                    bool directRays, const CoarseHits* cast) {
  if (!options_.dynamicPlane()) {
    PlaneDecision d;
    d.depth =
        camera.nearPlane() + options_.planeFraction * (camera.farPlane() - camera.nearPlane());
    return d;
  }
  if (stillValid(camera)) {
    ++uses_;
    PlaneDecision d;
    d.depth = std::clamp(depth_, camera.nearPlane(), camera.farPlane());
    d.reused = true;
    return d;
  }
  std::vector<double> hits;
  PlaneDecision d;
  if (cast) d = cast->mean, hits = cast->depths;
  else d = coarseRayCast(embree, camera, options_.planeGrid, &hits, threads);
  if (options_.costPlane)
    d.depth = costPlane(std::move(hits), d.coarseRays, camera, loads,
                        directRays || !options_.usesPvl() ? kNaiveRayCost : kRayCost, threads,
                        &d.cost);
  have_ = true;
  at_ = camera;
  depth_ = d.depth;
  uses_ = 0;
  observed_ = false;
  return d;
}

void PartitionPlane::observe(uint64_t unfinished) {
  if (!have_) return;
  if (uses_ == 0 && !observed_) unfinishedAtCompute_ = unfinished;
  lastUnfinished_ = unfinished;
  observed_ = true;
}

}  // namespace lzb::localz
