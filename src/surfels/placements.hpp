#pragma once
// The frame's objects and the switch between surfels and polygons (Tobor et al., section 5).
//
// An object is a scene node with triangles; a placement is one of its instances in the fully
// instanced scene (node, world matrix, expanded ID of its triangle 0). The traversal walks the
// scene graph in expanded-ID order, dropping subtrees outside the frustum, so every rank lists the
// same placements in the same order (src/core/visible_placements.hpp).
//
// The switch, per placement: a grid level is hole-free when its cell, projected at the object's
// nearest view depth, spans at most `cellFraction` x the sprite's covered side (a surfel sits
// anywhere in its cell, so a sprite that covers twice the projected cell around its point covers
// the cell from anywhere in it: cellFraction 0.5; squares cover d pixels, discs d / sqrt 2). The
// placement takes the coarsest level that passes with the largest sprite (--splat), and the
// smallest sprite that passes at that level (the paper's per-object sprite size); when even the
// finest level fails, or the object reaches the near plane, it stays polygons, drawn by the native
// z-buffer with the same (depth, ID) key: near objects are exact.
//
// The projected cell of a grid n is cellPx1 / n, with cellPx1 the cube's projected extent at the
// nearest depth of the object's bounding box: a box edge e spans |right . e| + |x / z| |forward .
// e| per unit of depth in x (the second term: its depth change seen off axis, with the largest |x /
// z| of the object), likewise in y.
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "src/core/camera.hpp"
#include "src/core/scene.hpp"
#include "src/surfels/surfel_params.hpp"
#include "src/surfels/surfelize.hpp"

namespace lzb::surfels {

constexpr int kPolygons = -1;

struct SurfelPlacement {
  uint32_t node = 0;
  glm::dmat4 world{1.0};
  uint64_t idBase = 0;
  double depthMin = 0.0;  // nearest view depth of the object's bounding box
  double cellPx1 = 0.0;   // the cube's projected extent in pixels (grid 1)
  int level = kPolygons;  // index into SurfelParams::grids, or kPolygons
  int sprite = 0;         // d, for surfels
};

// The level and sprite of a placement whose cube projects to cellPx1 pixels (at grid 1).
struct LevelChoice {
  int level = kPolygons;
  int sprite = 0;
};
LevelChoice chooseLevel(double cellPx1, const SurfelParams& params);

// Every placement of an object whose cube meets the frustum, in expanded-ID order, with its
// depth, projected size and level (domains: per node, its surfel cube; meshBounds: per node, the
// bounds of its own triangles).
std::vector<SurfelPlacement> visiblePlacements(const Scene& scene, const std::vector<Domain>& domains,
                                         const std::vector<Bounds>& meshBounds,
                                         const Camera& camera, const SurfelParams& params);

}  // namespace lzb::surfels
