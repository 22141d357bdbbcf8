#pragma once
// --eps auto (section 8.2): box selection cost grows as eps falls, reconstruction cost (samples)
// grows with eps; their sum has one minimum, found by golden-section search over log(eps - 1)
// with the cost model of deal.hpp (fixed constants, so every rank finds the same eps). A
// selection whose node count alone exceeds the best cost so far is cut short.
#include "src/core/camera.hpp"
#include "src/rzb/box_selection.hpp"

namespace lzb::rzb {

struct EpsSearch {
  double eps = 1.5;
  int evaluations = 0;
  double modelSeconds = 0.0;  // modelled cost at eps
};

// Modelled frame cost of a selection (seconds).
double modelledCost(const Selection& s);

// previous: the last frame's eps (<= 1: none, search the whole range [1.1, 5] with 11
// selections; else 4 selections in a bracket of a factor e^0.5 around it in eps - 1).
EpsSearch searchEps(const SampleScene& scene, const Camera& camera, const SelectParams& base,
                    const SampleStream& rounding, double previous);

}  // namespace lzb::rzb
