#include "src/rzb/eps_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "src/rzb/deal.hpp"

namespace lzb::rzb {

double modelledCost(const Selection& s) {
  return double(s.nodesVisited) * kNodeSeconds + double(s.samples) * kSampleSeconds +
         double(s.fallbackEntries) * kTriangleSeconds;
}

EpsSearch searchEps(const SampleScene& scene, const Camera& camera, const SelectParams& base,
                    const SampleStream& rounding, double previous) {
  EpsSearch out;
  double best = std::numeric_limits<double>::infinity();
  auto cost = [&](double x) {
    SelectParams p = base;
    p.eps = 1.0 + std::exp(x);
    if (std::isfinite(best)) p.maxNodes = uint64_t(std::max(best / kNodeSeconds, 1.0));
    const Selection s = selectBoxes(scene, camera, p, rounding);
    ++out.evaluations;
    const double c = s.aborted ? std::numeric_limits<double>::infinity() : modelledCost(s);
    if (c < best) {
      best = c;
      out.eps = p.eps;
      out.modelSeconds = c;
    }
    return c;
  };
  const double xMin = std::log(0.1), xMax = std::log(4.0);
  double lo = xMin, hi = xMax;
  int iterations = 9;
  if (previous > 1.0) {
    // Later frames: a narrow bracket around the last eps, the minimum moves little per frame.
    const double x = std::log(previous - 1.0);
    lo = std::max(xMin, x - 0.5);
    hi = std::min(xMax, x + 0.5);
    iterations = 2;
  }
  // Start from the wide end: large eps is cheap to select, so it sets a bound early.
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double b = lo + g * (hi - lo), a = hi - g * (hi - lo);
  double fb = cost(b), fa = cost(a);
  for (int i = 0; i < iterations; ++i) {
    if (fa <= fb) {
      hi = b;
      b = a;
      fb = fa;
      a = hi - g * (hi - lo);
      fa = cost(a);
    } else {
      lo = a;
      a = b;
      fa = fb;
      b = lo + g * (hi - lo);
      fb = cost(b);
    }
  }
  return out;
}

}  // namespace lzb::rzb
