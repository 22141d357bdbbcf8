#include "src/rzb/deal.hpp"

#include "mpi/decomposition.hpp"

namespace lzb::rzb {

double boxCost(const SelectedBox& box) {
  return box.fallback ? double(box.entries) * kTriangleSeconds
                      : double(box.samples) * kSampleSeconds + kNodeSeconds;
}

std::vector<uint32_t> dealBoxes(const std::vector<SelectedBox>& boxes, const WorkShare& share) {
  std::vector<double> costs(boxes.size());
  for (size_t i = 0; i < boxes.size(); ++i) costs[i] = boxCost(boxes[i]);
  return dealByCost(costs, share);
}

}  // namespace lzb::rzb
