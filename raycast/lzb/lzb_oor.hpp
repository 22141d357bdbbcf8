#pragma once
// Object-oriented ray casting (paper, section III.C): rays only from the unfinished pixels that
// lie inside the screen projection of some object behind the partition plane.
//
// The objects are octree nodes, not the scene's nodes, each with its content box (the box of its
// triangles, cut to the node: NodeAccel::contentBox), chosen coarsest first: for every culled
// placement, its octree is descended from the root, skipping nodes whose content lies in front of
// the plane or outside the frustum; a node whose content projects within 32 x 32 pixels (or a
// leaf) is one object. Why: it is conservative - a pixel whose centre ray hits a far triangle at
// point p lies inside the projection of the content box of every node holding p - and tight
// where it matters (objects large on screen are refined down to leaves), while distant
// placements cost one polygon instead of hundreds of leaves. Whole scene nodes would not remove
// empty pixels in the common cases: a scanned mesh is one node whose box covers the view, a city
// block's box holds the sky above its lower buildings; and the octree cubes themselves are loose
// too (the city's ground triangles make every root leaf non-empty, and its cubes reach into the
// sky).
//
// A content box under its instance transform is a parallelepiped; behind the plane its projection
// is the convex hull of the 8 projected corners, a polygon of 4, 5 or 6 sides (1, 2 or 3 faces
// visible). Corners are projected as the paper suggests: the base corner once, the others by
// adding the projected edge vectors (homogeneous coordinates). Only the part of the box behind
// the plane matters (rays start there), so a box that crosses the plane is clipped at it first:
// its projection is the hull of its corners behind the plane and of its edges' crossings with
// the plane (a few more sides). This keeps the polygon finite and tight even for leaves around
// the camera (the eye inside the octree), which a plain box projection would have to treat as
// covering the whole screen.
//
// Per pixel: the polygon's 2D bounding box first, then the point-in-convex-polygon test at the
// pixel centre (edge functions, 1e-3 pixel tolerance outwards). A boolean mask per pixel records
// that the pixel is cast already, so no pixel is cast twice.
//
// Each object also bounds how far its pixels' rays need to go: a ray can only hit far triangles
// in the content boxes of objects whose polygons (so whose bounding boxes) hold its pixel, none
// deeper than the deepest of those boxes (ScreenPolygon::depthMax). A ray that finds nothing
// stops there instead of walking on to the far plane (see lzb_tile_cast.hpp).
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "raycast/lzb/lzb_accel.hpp"
#include "raycast/lzb/lzb_cull.hpp"
#include "mpi/decomposition.hpp"
#include "src/core/camera.hpp"

namespace lzb::localz {

struct ScreenPolygon {
  static constexpr int kMaxVertices = 16;
  // Bounding box, pixel coordinates (x right, y down); the default box is empty.
  float x0 = 1.0f, y0 = 1.0f, x1 = 0.0f, y1 = 0.0f;
  uint8_t count = 0;           // hull vertices; 0 with a valid box: the whole box (screen)
  double depthMax = 0.0;       // OOR objects: the deepest view depth of the projected box
  glm::dvec2 v[kMaxVertices];  // hull, turning left in (x, y-down) coordinates
  bool contains(double x, double y) const;
  // The pixels [first, last] of row y within columns [xa, xb] whose centres contains() accepts
  // (an interval: the polygon is convex); false when there are none.
  bool rowSpan(int y, int xa, int xb, int& first, int& last) const;
};

// Projects the part of `leaf` of `path` (see CulledScene) behind view depth clipDepth (> 0).
ScreenPolygon projectLeaf(const LzbAccel& accel, const CullPath& path, uint32_t leaf,
                          const Camera& camera, double clipDepth);

// The OOR objects of a frame (see the top): projections of far octree nodes (their parts at view
// depth >= clipDepth, where the rays start), binned to the screen tiles their bounding boxes
// overlap.
class OorObjects {
 public:
  OorObjects() = default;
  OorObjects(const LzbAccel& accel, const CulledScene& culled, const Camera& camera,
             double clipDepth, const ScreenTiles& tiles, int threads) {
    build(accel, culled, camera, clipDepth, tiles, threads);
  }
  // (Re)computes the objects, reusing the memory of the previous frame's.
  void build(const LzbAccel& accel, const CulledScene& culled, const Camera& camera,
             double clipDepth, const ScreenTiles& tiles, int threads);
  size_t size() const { return polygons_.size(); }
  const ScreenPolygon& polygon(uint32_t i) const { return polygons_[i]; }
  // Polygons whose bounding box overlaps tile t, in object order.
  std::span<const uint32_t> tile(int t) const {
    return {binned_.data() + binBegin_[size_t(t)], binBegin_[size_t(t) + 1] - binBegin_[size_t(t)]};
  }

 private:
  std::vector<ScreenPolygon> polygons_;
  std::vector<uint32_t> binBegin_, binned_;
  std::vector<std::vector<ScreenPolygon>> perPath_;  // scratch
};

}  // namespace lzb::localz
