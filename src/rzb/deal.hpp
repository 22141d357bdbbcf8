#pragma once
// The cost model of the point pass, and the selected boxes dealt to ranks by it (the decomposition
// rule is mpi/decomposition.hpp's dealByCost: contiguous runs of about equal cost, in selection
// order, which does not depend on the number of ranks).
#include <cstdint>
#include <vector>

#include "src/core/renderer.hpp"
#include "src/rzb/box_selection.hpp"

namespace lzb::rzb {

// Relative costs of the cost model (seconds on the reference machine, 2 threads): one sample
// drawn and splatted, one triangle rasterized by the fallback, one octree node visited by box
// selection. Fixed constants, so that every rank computes the same deal and the same eps.
constexpr double kSampleSeconds = 12e-9;
constexpr double kTriangleSeconds = 110e-9;
constexpr double kNodeSeconds = 600e-9;

double boxCost(const SelectedBox& box);

// Indices of the boxes rank share.rank renders.
std::vector<uint32_t> dealBoxes(const std::vector<SelectedBox>& boxes, const WorkShare& share);

}  // namespace lzb::rzb
