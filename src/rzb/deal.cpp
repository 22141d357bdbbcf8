#include "src/rzb/deal.hpp"

#include <algorithm>
#include <cmath>

namespace lzb::rzb {

double boxCost(const SelectedBox& box) {
  return box.fallback ? double(box.entries) * kTriangleSeconds
                      : double(box.samples) * kSampleSeconds + kNodeSeconds;
}

std::vector<uint32_t> dealBoxes(const std::vector<SelectedBox>& boxes, const WorkShare& share) {
  std::vector<uint32_t> mine;
  if (share.size <= 1) {
    mine.resize(boxes.size());
    for (uint32_t i = 0; i < mine.size(); ++i) mine[i] = i;
    return mine;
  }
  double total = 0.0;
  for (const SelectedBox& b : boxes) total += boxCost(b);
  double before = 0.0;
  for (uint32_t i = 0; i < boxes.size(); ++i) {
    const double c = boxCost(boxes[i]);
    const double mid = total > 0.0 ? (before + 0.5 * c) / total : 0.0;
    const int rank = std::min(share.size - 1, int(std::floor(mid * share.size)));
    if (rank == share.rank) mine.push_back(i);
    before += c;
  }
  return mine;
}

}  // namespace lzb::rzb
