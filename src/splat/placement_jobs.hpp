#pragma once
// A frame's point work cut into jobs, the unit dealt to ranks (mpi/decomposition.hpp:
// dealByCost) and to threads, in placement order: points (or lines of a grid) in runs, and a
// placement drawn as polygons whole. The costs weigh a triangle against a point; they move only
// the load balance, never the image. sqrt5 and surfels cut their placements here.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace lzb {

// Points per job.
constexpr uint64_t kJobPoints = 16384;
// The dealing cost of one polygon against one point: an estimate of the native z-buffer's cost of
// a small triangle (set-up, edge functions, a few fragments) over one splat.
constexpr double kTriangleCost = 4.0;

// Items [begin, end) of placement `placed` (points, or lines of a grid), or (begin == end == 0)
// all its triangles, drawn as polygons.
struct PlacementJob {
  uint32_t placed;
  uint64_t begin, end;
};

struct PlacementJobs {
  std::vector<PlacementJob> list;
  std::vector<double> costs;  // per job, for dealByCost

  // Items [0, count) of `placed` in runs of `per`, each item costing `itemCost` points.
  void addRuns(uint32_t placed, uint64_t count, uint64_t per = kJobPoints, uint64_t itemCost = 1);
  // `placed` drawn as `triangles` polygons: one job.
  void addPolygons(uint32_t placed, uint64_t triangles);
  const PlacementJob& operator[](size_t k) const { return list[k]; }
};

}  // namespace lzb
