#include "src/regions/share.hpp"

#include "src/core/error.hpp"

namespace lzb::regions {

Distribution parseDistribution(const std::string& text, const std::string& field) {
  if (text == "replicate") return Distribution::kReplicate;
  if (text == "data") return Distribution::kData;
  if (text == "auto") return Distribution::kAuto;
  throw InputError(field + ": unknown distribution '" + text + "' (replicate | data | auto)");
}

void dealRegions(std::span<const uint64_t> regionTriangles, HeldShare& held, const WorkShare& share,
                 Parts layout) {
  held.mine = regionsOfRank(regionTriangles, share);
  held.layout = layout;
  held.triangles = 0;
  for (uint32_t r : held.mine) held.triangles += regionTriangles[r];
}

std::vector<uint32_t> partOfRegion(const HeldShare& held) {
  std::vector<uint32_t> part(held.regions, kNoPart);
  for (size_t k = 0; k < held.mine.size(); ++k)
    part[held.mine[k]] = held.layout == Parts::kOne ? 0 : uint32_t(k);
  return part;
}

PartOf partOfRank(const RegionCut& cut, HeldShare& held, const WorkShare& share, Parts layout) {
  dealRegions(cut.regionTriangles, held, share, layout);
  const std::vector<uint32_t> part = partOfRegion(held);
  PartOf partOf(cut.regionOf.size());
  for (size_t u = 0; u < partOf.size(); ++u) partOf[u] = part[cut.regionOf[u]];
  return partOf;
}

Parts partsFor(const Method& method) {
  return method.exact() ? Parts::kOne : Parts::kPerRegion;
}

uint32_t partCount(const HeldShare& held, Parts layout) {
  return layout == Parts::kOne ? 1 : uint32_t(held.mine.size());
}

namespace {

// The units' world centres and (when some are instances) triangles, as the cut weighs them.
struct WeightedUnits {
  std::vector<glm::dvec3> centres;
  std::vector<uint64_t> triangles;  // empty: one each (only the main mesh's triangles)
};
WeightedUnits weigh(const Scene& whole, const SceneUnits& units, const DeferredReader& read = {}) {
  WeightedUnits w;
  units.centres(whole, w.centres, read);
  if (!units.opened.empty())
    for (size_t u = 0; u < units.size(); ++u) w.triangles.push_back(units.triangles(u));
  return w;
}

}  // namespace

std::vector<uint64_t> trianglesPerRank(const Scene& whole, uint32_t regions, Parts layout,
                                       bool wholeProcedural, int ranks,
                                       const DeferredReader& read) {
  regions = regionCount(regions, whole.uniqueTriangles(), layout == Parts::kOne);
  const SceneUnits units = sceneUnits(whole, regions, wholeProcedural);
  const WeightedUnits w = weigh(whole, units, read);
  return trianglesPerRank(cutIntoRegions(w.centres, w.triangles, regions).regionTriangles, ranks);
}

HeldShare holdShare(const Scene& whole, uint32_t regions, const WorkShare& share, Parts layout,
                    bool wholeProcedural, const DeferredReader& read,
                    const std::function<void(const HeldShare&)>& beforeKeeping) {
  HeldShare held;
  held.regions = regionCount(regions, whole.uniqueTriangles(), layout == Parts::kOne);
  const SceneUnits units = sceneUnits(whole, held.regions, wholeProcedural);
  held.units = units.size();
  PartOf partOf;
  {
    const WeightedUnits w = weigh(whole, units, read);
    partOf = partOfRank(cutIntoRegions(w.centres, w.triangles, held.regions), held, share, layout);
  }
  if (beforeKeeping) beforeKeeping(held);
  held.parts = cutScene(whole, units, partOf, partCount(held, layout), read);
  return held;
}

}  // namespace lzb::regions
