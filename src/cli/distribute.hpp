#pragma once
// --distribute: every rank holds the whole scene (replicate, the default), or only the regions
// dealt to it (data): the scene is cut into --regions spatial regions balanced by triangle count
// (mpi/decomposition.hpp), dealt to the ranks of a frame group by triangle count, and each rank
// keeps the units of its regions (src/core/scene_part.hpp). A rank then renders the whole frame
// of its part, shades its own pixels and gives its IDs in the whole scene's numbering, and the
// ranks' frames are composited by depth, colour travelling with each pixel.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "src/core/renderer.hpp"
#include "src/core/scene.hpp"
#include "src/core/scene_part.hpp"

namespace lzb {

enum class Distribution { kReplicate, kData };
// Throws InputError naming `field` on an unknown name.
Distribution parseDistribution(const std::string& text, const std::string& field);

// The regions of a scene when --regions is 0: one per 2^16 unique triangles, at least 16 and at
// most 4096, from the scene's size alone (never the rank count).
uint32_t defaultRegions(uint64_t uniqueTriangles);

// Whether `method` renders a part (the exact references so far); the others are refused.
bool rendersParts(const std::string& method);

// What a rank holds of the scene.
struct HeldShare {
  uint32_t regions = 0;             // the scene's regions
  uint64_t units = 0;               // the scene's units (src/core/scene_part.hpp)
  std::vector<uint32_t> mine;       // the regions this rank holds
  std::unique_ptr<ScenePart> part;  // their units
};

// Cuts `whole` into `regions` regions (0: defaultRegions) and keeps those of rank share.rank.
HeldShare holdShare(const Scene& whole, uint32_t regions, const WorkShare& share);

// Which units rank share.rank keeps, given the units' world centres and triangles (empty: one
// each), with held.regions set: cuts the regions (splitIntoRegions), deals them (regionsOfRank)
// and sets held.mine. The one cut of both the loaded and the streamed scene (streamed_share.hpp).
std::vector<bool> keepOfRank(std::span<const glm::dvec3> centres,
                             std::span<const uint64_t> triangles, HeldShare& held,
                             const WorkShare& share);

// A renderer of a rank's part, wrapping `inner` (made on part.scene; none when the part is
// empty): it renders the whole frame of the part, shades it and maps its IDs to the whole
// scene's. Its set-up reports the regions and triangles this rank holds.
std::unique_ptr<Renderer> makePartRenderer(const HeldShare& held, std::unique_ptr<Renderer> inner,
                                           const std::string& method);

}  // namespace lzb
