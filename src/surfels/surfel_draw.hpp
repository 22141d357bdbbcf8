#pragma once
// Drawing surfels: a placed level's entries, in the collector's order, through the splatting core
// (src/splat/splatter.hpp) into a key buffer, each as a sprite of its placement's size carrying
// the expanded ID of its representative triangle.
//
// Per entry: the position from the key and data bits (no table look-up), culled when its
// quantized normal faces away from the eye (--backfaces drop; the test runs in the object's
// lattice frame, where it is the world test for any affine placement), mapped to camera space by
// one 3 x 4 matrix and splatted. High quality: a whole key (one normal octant) is skipped when
// that octant faces away from every point of the object's cube, which the per-entry test would
// find of each of its surfels: the same image, fewer reads.
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "src/core/camera.hpp"
#include "src/core/depth_key.hpp"
#include "src/splat/placement_jobs.hpp"
#include "src/surfels/normal_quantizer.hpp"
#include "src/surfels/surfelize.hpp"

namespace lzb::surfels {

// One level at one placement, ready to draw.
struct PlacedLevel {
  const SurfelLevel* level = nullptr;
  uint64_t idBase = 0;
  float toCamera[3][4];  // camera-space x, y, depth of lattice point q: rows . (q, 1)
  glm::vec3 eye{0.0f};   // the eye in lattice units
  uint8_t culledOctants = 0;
  int sprite = 1;
  uint64_t count = 0;  // entries drawn: [0, count) of the collector's order

  static PlacedLevel make(const SurfelLevel& level, const glm::dmat4& world, uint64_t idBase,
                          const Camera& camera, int sprite, uint64_t count, bool cullBackfaces);
};

// A run of entries [begin, end) of placed[placed].
using SurfelJob = PlacementJob;

struct DrawCounts {
  uint64_t drawn = 0;       // entries read
  uint64_t backfacing = 0;  // of those, culled as facing away
  uint64_t splatted = 0;    // sprites that reached the image
};

// Cuts each placed level's [0, count) into jobs of at most `chunk` entries.
std::vector<SurfelJob> makeJobs(std::span<const PlacedLevel> placed,
                                std::span<const uint32_t> which, uint64_t chunk);

// Draws the jobs into keys (sized to the camera) on `threads` threads; the buffer does not
// depend on the thread count or the order of the jobs.
DrawCounts drawSurfels(std::span<const PlacedLevel> placed, std::span<const SurfelJob> jobs,
                       const Camera& camera, bool disc, bool cullBackfaces,
                       const OctahedralNormals& normals, KeyBuffer& keys, int threads);

}  // namespace lzb::surfels
