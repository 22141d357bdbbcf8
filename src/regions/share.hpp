#pragma once
// --distribute: every rank holds the whole scene (replicate, the default), or only the regions
// dealt to it (data): the scene is cut into --regions spatial regions balanced by triangle count
// (region_cut.hpp), dealt to the ranks of a frame group by triangle count, and each rank keeps
// the units of its regions (scene_part.hpp). A rank then renders the whole frame
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
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "src/core/method.hpp"
#include "src/core/renderer.hpp"
#include "src/core/scene.hpp"
#include "src/regions/region_cut.hpp"
#include "src/regions/scene_part.hpp"

namespace lzb::regions {

// kAuto: data when a streamed scene would not fit replicated in some rank's memory (render_setup).
enum class Distribution { kReplicate, kData, kAuto };
// Throws InputError naming `field` on an unknown name.
Distribution parseDistribution(const std::string& text, const std::string& field);

// How a rank's regions are held: as one part (exact methods) or one part per region.
enum class Parts { kOne, kPerRegion };

// What a rank holds of the scene.
struct HeldShare {
  uint32_t regions = 0;        // the scene's regions
  uint64_t units = 0;          // the scene's units (scene_part.hpp)
  std::vector<uint32_t> mine;  // the regions this rank holds, in increasing order
  uint64_t triangles = 0;      // their triangles (expanded)
  Parts layout = Parts::kOne;
  std::vector<ScenePart> parts;       // their units: one part, or one per region of `mine`
  std::optional<uint64_t> bytesRead;  // read in slices (sliced_share.hpp): the file's bytes read
};

// The layout `method` renders: kOne for an exact method, else kPerRegion.
Parts partsFor(const Method& method);
// The parts a share of `layout` has once held.mine is set.
uint32_t partCount(const HeldShare& held, Parts layout);

// Cuts `whole` into `regions` regions (0: the default, regionCount) and keeps those of rank
// share.rank (wholeProcedural: procedural objects stay whole units, sceneUnits). A deferred node's
// triangles (a TOML scene's outline, loadTomlOutline) are read through `read` (cutScene).
// beforeKeeping(held) runs once the regions are dealt, before any triangle of the share is read
// or kept (it may throw to refuse the share).
HeldShare holdShare(const Scene& whole, uint32_t regions, const WorkShare& share, Parts layout,
                    bool wholeProcedural, const DeferredReader& read = {},
                    const std::function<void(const HeldShare&)>& beforeKeeping = {});

// The triangles (expanded) each of `ranks` ranks would hold of `whole` cut into `regions` regions
// (0: the default) for a method of `layout`: what holdShare keeps, without keeping it (a
// deferred node's centres read through `read`).
std::vector<uint64_t> trianglesPerRank(const Scene& whole, uint32_t regions, Parts layout,
                                       bool wholeProcedural, int ranks,
                                       const DeferredReader& read = {});
// Deals the regions (regionsOfRank), with held.regions set: sets held.mine, held.triangles and
// held.layout. The one deal of the loaded, the streamed and the slice-read scene.
void dealRegions(std::span<const uint64_t> regionTriangles, HeldShare& held, const WorkShare& share,
                 Parts layout);
// The part of this rank each region goes to (kNoPart: another rank's), once dealt.
std::vector<uint32_t> partOfRegion(const HeldShare& held);
// Which of this rank's parts each unit of `cut` goes to, the regions dealt (dealRegions).
PartOf partOfRank(const RegionCut& cut, HeldShare& held, const WorkShare& share, Parts layout);

}  // namespace lzb::regions
