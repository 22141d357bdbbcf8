#pragma once
// Per-frame box selection (Wand et al. sections 5.3.2 and 7.1).
//
// From the root tree down, through instance entries into the trees they reference: a node outside
// the view frustum is dropped; a node whose view depth range satisfies (zmax / zmin)^2 <= eps
// (the ratio of its largest to smallest depth factor 1/z^2, zmin clamped to the near plane) is
// selected whole; otherwise its children are visited, its own triangles become a box of their
// own, and its own instance entries are entered. A selected box gets
//   samples = area * (pixels per unit at zmin)^2 * samplesPerPixel
// (its area bound times its largest projection factor, in pixels), stochastically rounded. When
// its largest triangle would project to more than fallbackPx pixels, the box goes to the
// z-buffer fallback instead: its triangles are rasterized, and the instance entries inside it are
// entered (their own classes separate small triangles from large ones).
#include <cstdint>
#include <limits>
#include <vector>

#include "src/core/camera.hpp"
#include "src/core/affine.hpp"
#include "src/core/philox_stream.hpp"
#include "src/rzb/sample_scene.hpp"

namespace lzb::rzb {

struct SelectParams {
  double eps = 1.5;              // depth accuracy, > 1
  double samplesPerPixel = 1.0;  // samples per pixel of projected area (oversample * ln v / d^2)
  double fallbackPx = std::numeric_limits<double>::infinity();  // +inf: no fallback
  uint64_t maxNodes = std::numeric_limits<uint64_t>::max();     // stop (aborted) past this
  // At most this many samples per box (a box of huge triangles at the near plane with no
  // fallback would otherwise ask for ~1/near^2 of them); counted in Selection::cappedBoxes.
  double maxBoxSamples = std::numeric_limits<double>::infinity();
};

struct SelectedBox {
  const DistributionTree* tree = nullptr;
  uint32_t node = 0;
  Part part = Part::kSubtree;
  bool fallback = false;
  uint64_t idBase = 0;     // expanded ID of the tree's triangle 0 on this instance path
  uint64_t key = 0;        // identity of (tree, node, part, instance path): the Philox box key
  Affine toWorld;          // node frame -> world
  Affine toCamera;         // node frame -> camera space (x right, y up, z view depth)
  glm::dvec3 eyeLocal{0};  // the eye in the node frame
  double zmin = 0, zmax = 0;   // view depth range of the box (zmin clamped to the near plane)
  double ppu = 0;              // pixels per world unit at zmin
  double areaScale = 1, stretch = 1;  // of the instance path
  double area = 0;             // world area bound
  double expected = 0;         // expected samples
  uint64_t samples = 0;        // this frame's sample count (stochastically rounded)
  uint64_t entries = 0;        // entries of the box (fallback boxes: their cost)
};

struct Selection {
  std::vector<SelectedBox> boxes;  // sample and fallback boxes in selection order
  uint64_t nodesVisited = 0;
  uint64_t sampleBoxes = 0, fallbackBoxes = 0, fallbackEntries = 0, samples = 0, cappedBoxes = 0;
  double projectedArea = 0.0;  // sum of area * ppu^2 over sample boxes (pixels)
  bool aborted = false;        // maxNodes was reached
};

// rounding: the frame's stream (stochastic rounding of sample counts, keyed by box).
Selection selectBoxes(const SampleScene& scene, const Camera& camera, const SelectParams& params,
                      const SampleStream& rounding);

}  // namespace lzb::rzb
