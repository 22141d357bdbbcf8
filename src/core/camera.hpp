#pragma once
// Perspective camera and the one depth convention every pass uses.
//
// Depth convention: a pixel's depth is the view depth of the surface point it shows, that is its
// distance along the camera's forward axis (positive, larger = farther), stored as float. Empty
// pixels hold +inf. OSMesa depth is converted to it once (src/zbuffer), Embree hits give it
// directly (pixelRay's direction has forward component 1, so the hit distance t is the depth),
// and splats compute it. Positive floats order like their bit patterns, which compositing uses.
//
// Pixel coordinates: x to the right, y down, pixel (i, j) has its centre at (i + 0.5, j + 0.5),
// where OpenGL rasterization also samples.
#include <array>
#include <vector>

#include <glm/glm.hpp>

#include "src/core/bounds.hpp"
#include "src/core/scene.hpp"

namespace lzb {

// The largest image side a Camera accepts.
inline constexpr int kMaxImageSide = 16384;

struct Plane {
  glm::dvec3 n;  // points into the inside
  double d;      // inside when dot(n, p) + d >= 0
  double distance(const glm::dvec3& p) const { return glm::dot(n, p) + d; }
};

enum class Cull { kOutside, kIntersects, kInside };

struct Frustum {
  std::array<Plane, 6> planes;  // left, right, bottom, top, near, far
  Cull classify(const Bounds& b) const;
  bool contains(const glm::dvec3& p) const;
};

class Camera {
 public:
  Camera() = default;
  // Validates the fields (near > 0, near < far, fov in (0, 180), image size) naming `where`.
  Camera(const CameraSpec& spec, int width, int height, const std::string& where = "camera");

  const glm::dvec3& position() const { return position_; }
  const glm::dvec3& forward() const { return forward_; }
  const glm::dvec3& right() const { return right_; }
  const glm::dvec3& up() const { return up_; }
  double nearPlane() const { return near_; }
  double farPlane() const { return far_; }
  double fovyDegrees() const { return fovy_; }
  double tanHalfX() const { return tanHalfX_; }  // tan of half the horizontal field of view
  double tanHalfY() const { return tanHalfY_; }
  int width() const { return width_; }
  int height() const { return height_; }
  const CameraSpec& spec() const { return spec_; }

  glm::dmat4 view() const;        // world -> camera space (right-handed, looking down -z)
  glm::dmat4 projection() const;  // camera -> OpenGL clip space (near/far map to -1/+1)
  double viewDepth(const glm::dvec3& world) const { return glm::dot(world - position_, forward_); }
  // Ray through a point in pixel coordinates; dir has forward component exactly 1 (t == depth).
  glm::dvec3 pixelDirection(double px, double py) const;
  // Pixel coordinates of a world point (x right, y down) and its depth; depth <= 0 is behind.
  glm::dvec3 project(const glm::dvec3& world) const;
  // Size in pixels of a length `worldSize` seen at view depth `depth`.
  double pixelsPerUnitAt(double depth) const { return pixelScale_ / depth; }
  Frustum frustum() const;

 private:
  CameraSpec spec_;
  glm::dvec3 position_{0.0}, forward_{0, 0, -1}, right_{1, 0, 0}, up_{0, 1, 0};
  double near_ = 0.1, far_ = 100.0, fovy_ = 45.0;
  double tanHalfY_ = 0.0, tanHalfX_ = 0.0, pixelScale_ = 1.0;
  int width_ = 640, height_ = 480;
};

// A camera spec framing bounds (looking at the centre from above and to the side), with near/far
// from the bounds. Near is kept > 0 even when the camera is inside the bounds.
CameraSpec frameBounds(const Bounds& bounds, double fovyDegrees = 45.0);
// Fills in nearPlane/farPlane that are 0 from the scene bounds and the camera position.
CameraSpec withClipPlanes(CameraSpec spec, const Bounds& bounds);

// The camera of frame f (0-based) of `frames`: keyframes interpolated linearly when the scene has
// them, else a circle around the scene centre at the framing distance (the LZB paper's path).
CameraSpec pathCamera(const Scene& scene, const CameraSpec& base, int frame, int frames);

}  // namespace lzb
