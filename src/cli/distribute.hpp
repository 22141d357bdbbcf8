#pragma once
// --distribute: every rank holds the whole scene (replicate, the default), or only the regions
// dealt to it (data): the scene is cut into --regions spatial regions balanced by triangle count
// (mpi/decomposition.hpp), dealt to the ranks of a frame group by triangle count, and each rank
// keeps the units of its regions (src/core/scene_part.hpp). A rank then renders the whole frame
// of its part, shades its own pixels and gives its IDs in the whole scene's numbering, and the
// ranks' frames are composited by depth, colour travelling with each pixel.
//
// An exact method renders the nearest surface whatever else is held, so a rank's regions make
// one part and the image is the replicated run's. Every other method samples, culls or chooses
// from what it holds, so each region is a part of its own with its own renderer, composited by
// depth on the rank: a region's image then depends on the region alone, and the same --regions
// give the same image on any number of ranks. The one decision the regions share is the
// hybrid's frame way (src/core/frame_probe.hpp), reduced over every region of every rank.
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "src/core/renderer.hpp"
#include "src/core/scene.hpp"
#include "src/core/scene_part.hpp"

namespace lzb {

// kAuto: data when a streamed scene would not fit replicated in some rank's memory (render_setup).
enum class Distribution { kReplicate, kData, kAuto };
// Throws InputError naming `field` on an unknown name.
Distribution parseDistribution(const std::string& text, const std::string& field);

// How a rank's regions are held: as one part (exact methods) or one part per region.
enum class Parts { kOne, kPerRegion };

// The regions of a scene when --regions is 0, from the scene's size alone (never the rank
// count), at least 16 and at most 4096: one per 2^16 unique triangles held as one part, one per
// 2^20 held a part per region (each region then costs a renderer's whole frame pass:
// runs/distribute/README.md).
uint32_t defaultRegions(uint64_t uniqueTriangles, Parts layout);

// What a rank holds of the scene.
struct HeldShare {
  uint32_t regions = 0;        // the scene's regions
  uint64_t units = 0;          // the scene's units (src/core/scene_part.hpp)
  std::vector<uint32_t> mine;  // the regions this rank holds, in increasing order
  uint64_t triangles = 0;      // their triangles (expanded)
  Parts layout = Parts::kOne;
  std::vector<ScenePart> parts;  // their units: one part, or one per region of `mine`
};

// The layout `method` renders: kOne for an exact method, else kPerRegion.
Parts partsFor(const std::string& method);
// Method::samplesProceduralObjects of `method`: its cut keeps procedural objects whole.
bool wholeProceduralFor(const std::string& method);
// The parts a share of `layout` has once held.mine is set.
uint32_t partCount(const HeldShare& held, Parts layout);

// Cuts `whole` into `regions` regions (0: defaultRegions) and keeps those of rank share.rank
// (wholeProcedural: procedural objects stay whole units, sceneUnits). A deferred node's
// triangles (a TOML scene's outline, loadTomlOutline) are read through `read` (cutScene).
// beforeKeeping(held) runs once the regions are dealt, before any triangle of the share is read
// or kept (it may throw to refuse the share).
HeldShare holdShare(const Scene& whole, uint32_t regions, const WorkShare& share, Parts layout,
                    bool wholeProcedural, const DeferredReader& read = {},
                    const std::function<void(const HeldShare&)>& beforeKeeping = {});

// The triangles (expanded) each of `ranks` ranks would hold of `whole` cut into `regions` regions
// (0: defaultRegions) for a method of `layout`: what holdShare keeps, without keeping it (a
// deferred node's centres read through `read`).
std::vector<uint64_t> trianglesPerRank(const Scene& whole, uint32_t regions, Parts layout,
                                       bool wholeProcedural, int ranks,
                                       const DeferredReader& read = {});
// The same from the units' world centres and triangles (empty: one each), `regions` regions.
std::vector<uint64_t> trianglesPerRank(std::span<const glm::dvec3> centres,
                                       std::span<const uint64_t> triangles, uint32_t regions,
                                       int ranks);

// Which of this rank's parts each unit goes to, given the units' world centres and triangles
// (empty: one each), with held.regions set: cuts the regions (splitIntoRegions), deals them
// (regionsOfRank) and sets held.mine, held.triangles and held.layout. The one cut of both the
// loaded and the streamed scene (streamed_share.hpp).
PartOf partOfRank(std::span<const glm::dvec3> centres, std::span<const uint64_t> triangles,
                  HeldShare& held, const WorkShare& share, Parts layout);

// A renderer of a rank's parts, wrapping one renderer per part (`inner[p]` made on
// held.parts[p].scene; none for an empty part): it renders the whole frame of each part,
// composites the parts by depth with the whole scene's IDs, then shades each pixel once by the
// part that won it. Its set-up reports the regions and triangles this rank holds.
std::unique_ptr<Renderer> makePartRenderer(const HeldShare& held,
                                           std::vector<std::unique_ptr<Renderer>> inner,
                                           const std::string& method);

}  // namespace lzb
