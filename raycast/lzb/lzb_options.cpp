#include "raycast/lzb/lzb_options.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "src/core/error.hpp"

namespace lzb::localz {

namespace {

template <typename E, size_t N>
E parseName(const std::string& text, const std::string& field, const char* const (&names)[N],
            const E (&values)[N]) {
  std::string known;
  for (size_t i = 0; i < N; ++i) {
    if (text == names[i]) return values[i];
    known += (i ? ", " : "") + std::string(names[i]);
  }
  throw InputError(field + ": unknown value '" + text + "' (known: " + known + ")");
}

constexpr const char* kStageNames[] = {"naive", "lazy", "selective", "oor", "final"};
constexpr LzbStage kStages[] = {LzbStage::kNaive, LzbStage::kLazy, LzbStage::kSelective,
                                LzbStage::kOor, LzbStage::kFinal};
constexpr const char* kModeNames[] = {"static", "dynamic", "hybrid"};
constexpr OccluderMode kModes[] = {OccluderMode::kStatic, OccluderMode::kDynamic,
                                   OccluderMode::kHybrid};
constexpr const char* kWalkNames[] = {"topdown", "coherent"};
constexpr OctreeWalk kWalks[] = {OctreeWalk::kTopDown, OctreeWalk::kCoherent};
constexpr const char* kZBufferKindNames[] = {"native", "gl"};
constexpr ZBufferKind kZBufferKinds[] = {ZBufferKind::kNative, ZBufferKind::kGl};
constexpr const char* kFarRaysNames[] = {"embree", "walk"};
constexpr FarRays kFarRays[] = {FarRays::kEmbree, FarRays::kWalk};

}  // namespace

LzbStage parseLzbStage(const std::string& text, const std::string& field) {
  return parseName(text, field, kStageNames, kStages);
}

OccluderMode parseOccluderMode(const std::string& text, const std::string& field) {
  return parseName(text, field, kModeNames, kModes);
}

OctreeWalk parseOctreeWalk(const std::string& text, const std::string& field) {
  return parseName(text, field, kWalkNames, kWalks);
}

ZBufferKind parseZBufferKind(const std::string& text, const std::string& field) {
  return parseName(text, field, kZBufferKindNames, kZBufferKinds);
}

FarRays parseFarRays(const std::string& text, const std::string& field) {
  return parseName(text, field, kFarRaysNames, kFarRays);
}

void parsePlane(const std::string& text, const std::string& field, LzbOptions& options) {
  options.planeFraction = 0.0;
  options.costPlane = text == "cost";
  if (text == "auto" || text == "cost") return;
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double f = std::strtod(begin, &end);
  const bool number = end != begin && *end == '\0' && errno == 0;
  require(
      number && std::isfinite(f) && f > 0.0 && f < 1.0, field,
      "must be 'auto', 'cost' or a fraction of the frustum depth in (0, 1), got '" + text + "'");
  options.planeFraction = f;
}

std::string toString(LzbStage stage) {
  return kStageNames[int(stage)];
}
std::string toString(OccluderMode mode) {
  return kModeNames[int(mode)];
}
std::string toString(OctreeWalk walk) {
  return kWalkNames[int(walk)];
}
std::string toString(ZBufferKind kind) {
  return kZBufferKindNames[int(kind)];
}
std::string toString(FarRays rays) {
  return kFarRaysNames[int(rays)];
}

void validate(const LzbOptions& o) {
  require(o.planeFraction == 0.0 || (o.planeFraction > 0.0 && o.planeFraction < 1.0), "--plane",
          "must be 'auto', 'cost' or a fraction of the frustum depth in (0, 1), got " +
              std::to_string(o.planeFraction));
  require(o.planeGrid >= 1 && o.planeGrid <= 4096, "--plane-grid",
          "must be in [1, 4096], got " + std::to_string(o.planeGrid));
  require(o.planeReuse >= 0 && o.planeReuse <= 1000000, "--plane-reuse",
          "must be in [0, 1000000] frames, got " + std::to_string(o.planeReuse));
  require(o.occluders >= 0 && o.occluders <= 1000, "--occluders",
          "must be in [0, 1000] (K local occluders per leaf), got " + std::to_string(o.occluders));
  require(o.depthComplexityGrid >= 0 && o.depthComplexityGrid <= 4096, "--lzb-depth-complexity",
          "must be in [0, 4096], got " + std::to_string(o.depthComplexityGrid));
  require(o.leafEntries >= 1 && o.leafEntries <= 1000000, "--lzb-leaf",
          "must be in [1, 1000000], got " + std::to_string(o.leafEntries));
  require(o.instanceLeafEntries >= 1 && o.instanceLeafEntries <= 1000000, "--lzb-instance-leaf",
          "must be in [1, 1000000], got " + std::to_string(o.instanceLeafEntries));
}

}  // namespace lzb::localz
