#include "src/regions/memory_estimate.hpp"

#include <map>

#include "src/core/error.hpp"
#include "src/core/system.hpp"

namespace lzb::regions {

namespace {

struct Model {
  uint64_t bytesPerTriangle;
  uint64_t baseMiB;
  uint64_t compactBytesPerTriangle = 0;  // under --bvh compact (0: no Embree BVH)
};

// runs/distribute/memory_model.csv (2 threads, 640x480): slopes and bases, rounded up; the
// compact slopes from runs/memory/README.md (the 10^7 landscape and PLY, peak less the base).
const std::map<std::string, Model>& models() {
  static const std::map<std::string, Model> m = {
      {"zbuffer", {80, 170}},     {"raycast", {128, 80, 72}}, {"lzb", {136, 110, 112}},
      {"hybrid", {144, 90, 116}}, {"rzb", {208, 90}},         {"surfels", {56, 100}},
      {"sqrt5", {56, 100}},       {"sampletree", {144, 90}}};
  return m;
}

}  // namespace

bool parseCompactBvh(const std::string& value, const std::string& where) {
  require(value == "fast" || value == "compact", where, "must be fast or compact");
  return value == "compact";
}

bool hasMemoryModel(const std::string& method) {
  return models().count(method) > 0;
}

uint64_t methodPeakBytes(const std::string& method, uint64_t triangles, bool compactBvh) {
  const auto found = models().find(method);
  // A method without a model is estimated as the costliest one.
  const Model m = found != models().end() ? found->second : Model{280, 180};
  const uint64_t slope =
      compactBvh && m.compactBytesPerTriangle ? m.compactBytesPerTriangle : m.bytesPerTriangle;
  return (m.baseMiB << 20) + slope * triangles;
}

uint64_t streamedCutBytes(uint64_t triangles) {
  return triangles * (32 + 4);
}

void requireEstimate(uint64_t bytes, const std::string& scene, const std::string& what,
                     const std::string& hint, uint64_t usable) {
  if (bytes <= usable) return;
  throw InputError(scene + ": " + what + " needs an estimated " + memoryShortfall(bytes, usable) +
                   hint);
}

}  // namespace lzb::regions
