#include "src/splat/placement_jobs.hpp"

#include <algorithm>

namespace lzb {

void PlacementJobs::addRuns(uint32_t placed, uint64_t count, uint64_t per, uint64_t itemCost) {
  for (uint64_t b = 0; b < count; b += per) {
    list.push_back({placed, b, std::min(count, b + per)});
    costs.push_back(double((list.back().end - b) * itemCost));
  }
}

void PlacementJobs::addPolygons(uint32_t placed, uint64_t triangles) {
  list.push_back({placed, 0, 0});
  costs.push_back(double(triangles) * kTriangleCost);
}

}  // namespace lzb
