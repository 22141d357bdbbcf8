#include "src/core/camera.hpp"

#include <cmath>
#include <numbers>

#include <glm/gtc/matrix_transform.hpp>

#include "src/core/error.hpp"

namespace lzb {

namespace {

constexpr double kPi = std::numbers::pi;

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

Camera::Camera(const CameraSpec& spec, int width, int height, const std::string& where)
    : spec_(spec), width_(width), height_(height) {
  require(width >= 1 && width <= kMaxImageSide, where + ".width",
          "must be in [1, " + std::to_string(kMaxImageSide) + "], got " + std::to_string(width));
  require(height >= 1 && height <= kMaxImageSide, where + ".height",
          "must be in [1, " + std::to_string(kMaxImageSide) + "], got " + std::to_string(height));
  require(finite(spec.position) && finite(spec.lookAt) && finite(spec.up), where,
          "position, look_at and up must be finite");
  require(spec.fovyDegrees > 0.0 && spec.fovyDegrees < 180.0, where + ".fov",
          "must be in (0, 180) degrees, got " + std::to_string(spec.fovyDegrees));
  require(spec.nearPlane > 0.0, where + ".near", "must be > 0, got " + std::to_string(spec.nearPlane));
  require(spec.farPlane > spec.nearPlane && std::isfinite(spec.farPlane), where + ".far",
          "must be finite and > near (" + std::to_string(spec.nearPlane) + "), got " +
              std::to_string(spec.farPlane));
  glm::dvec3 f = spec.lookAt - spec.position;
  require(glm::length(f) > 0.0, where, "position and look_at coincide");
  forward_ = glm::normalize(f);
  glm::dvec3 r = glm::cross(forward_, spec.up);
  require(glm::length(r) > 1e-12 * glm::length(spec.up), where + ".up",
          "is parallel to the viewing direction");
  right_ = glm::normalize(r);
  up_ = glm::cross(right_, forward_);
  position_ = spec.position;
  near_ = spec.nearPlane;
  far_ = spec.farPlane;
  fovy_ = spec.fovyDegrees;
  tanHalfY_ = std::tan(fovy_ * kPi / 360.0);
  tanHalfX_ = tanHalfY_ * double(width_) / double(height_);
  pixelScale_ = double(height_) / (2.0 * tanHalfY_);
}

glm::dmat4 Camera::view() const {
  glm::dmat4 m(1.0);
  m[0][0] = right_.x, m[1][0] = right_.y, m[2][0] = right_.z;
  m[0][1] = up_.x, m[1][1] = up_.y, m[2][1] = up_.z;
  m[0][2] = -forward_.x, m[1][2] = -forward_.y, m[2][2] = -forward_.z;
  m[3][0] = -glm::dot(right_, position_);
  m[3][1] = -glm::dot(up_, position_);
  m[3][2] = glm::dot(forward_, position_);
  return m;
}

glm::dmat4 Camera::projection() const {
  return glm::perspective(fovy_ * kPi / 180.0, double(width_) / double(height_), near_, far_);
}

glm::dvec3 Camera::pixelDirection(double px, double py) const {
  const double sx = (2.0 * px / width_ - 1.0) * tanHalfX_;
  const double sy = (1.0 - 2.0 * py / height_) * tanHalfY_;
  return forward_ + sx * right_ + sy * up_;
}

glm::dvec3 Camera::project(const glm::dvec3& world) const {
  const glm::dvec3 d = world - position_;
  const double depth = glm::dot(d, forward_);
  const double sx = glm::dot(d, right_) / (depth * tanHalfX_);
  const double sy = glm::dot(d, up_) / (depth * tanHalfY_);
  return {(sx + 1.0) * 0.5 * width_, (1.0 - sy) * 0.5 * height_, depth};
}

Frustum Camera::frustum() const {
  Frustum f;
  // Side planes pass through the eye; their inward normals come from the image-plane edges.
  const glm::dvec3 l = forward_ - tanHalfX_ * right_, r = forward_ + tanHalfX_ * right_;
  const glm::dvec3 b = forward_ - tanHalfY_ * up_, t = forward_ + tanHalfY_ * up_;
  auto through = [&](const glm::dvec3& n) { return Plane{n, -glm::dot(n, position_)}; };
  f.planes[0] = through(glm::normalize(glm::cross(l, up_)));
  f.planes[1] = through(glm::normalize(glm::cross(up_, r)));
  f.planes[2] = through(glm::normalize(glm::cross(right_, b)));
  f.planes[3] = through(glm::normalize(glm::cross(t, right_)));
  f.planes[4] = Plane{forward_, -glm::dot(forward_, position_) - near_};
  f.planes[5] = Plane{-forward_, glm::dot(forward_, position_) + far_};
  return f;
}

Cull Frustum::classify(const Bounds& box) const {
  if (box.empty()) return Cull::kOutside;
  bool inside = true;
  for (const Plane& p : planes) {
    // The box corner farthest along the normal ("p-vertex") and the nearest ("n-vertex").
    const glm::dvec3 pv{p.n.x >= 0 ? box.hi.x : box.lo.x, p.n.y >= 0 ? box.hi.y : box.lo.y,
                        p.n.z >= 0 ? box.hi.z : box.lo.z};
    const glm::dvec3 nv{p.n.x >= 0 ? box.lo.x : box.hi.x, p.n.y >= 0 ? box.lo.y : box.hi.y,
                        p.n.z >= 0 ? box.lo.z : box.hi.z};
    if (p.distance(pv) < 0.0) return Cull::kOutside;
    if (p.distance(nv) < 0.0) inside = false;
  }
  return inside ? Cull::kInside : Cull::kIntersects;
}

bool Frustum::contains(const glm::dvec3& p) const {
  for (const Plane& pl : planes)
    if (pl.distance(p) < 0.0) return false;
  return true;
}

CameraSpec withClipPlanes(CameraSpec spec, const Bounds& bounds) {
  const double radius = std::max(0.5 * bounds.diagonal(), 1e-30);
  const double dist = glm::length(bounds.center() - spec.position);
  if (spec.farPlane <= 0.0) spec.farPlane = (dist + radius) * 1.01;
  if (spec.nearPlane <= 0.0) {
    // In front of the bounds: start just before them; inside: a small fraction of the far plane.
    spec.nearPlane = std::max(dist - radius, 0.0) * 0.99;
    spec.nearPlane = std::max(spec.nearPlane, spec.farPlane * 1e-5);
  }
  return spec;
}

CameraSpec frameBounds(const Bounds& bounds, double fovyDegrees) {
  CameraSpec spec;
  spec.fovyDegrees = fovyDegrees;
  const double radius = std::max(0.5 * bounds.diagonal(), 1e-30);
  const double dist = radius / std::sin(0.5 * fovyDegrees * kPi / 180.0) * 1.05;
  const glm::dvec3 dir = glm::normalize(glm::dvec3(0.6, 0.45, 1.0));
  spec.lookAt = bounds.center();
  spec.position = bounds.center() + dist * dir;
  spec.up = {0.0, 1.0, 0.0};
  return withClipPlanes(spec, bounds);
}

CameraSpec pathCamera(const Scene& scene, const CameraSpec& base, int frame, int frames) {
  if (frames <= 1) return base;
  if (scene.keyframes.size() >= 2) {
    // Piecewise linear through the keyframes, first frame at the first key, last at the last.
    const double s = double(frame) / double(frames - 1) * double(scene.keyframes.size() - 1);
    const size_t k = std::min(size_t(s), scene.keyframes.size() - 2);
    const double u = s - double(k);
    const CameraSpec &a = scene.keyframes[k], &b = scene.keyframes[k + 1];
    CameraSpec c = a;
    c.position = glm::mix(a.position, b.position, u);
    c.lookAt = glm::mix(a.lookAt, b.lookAt, u);
    c.up = glm::mix(a.up, b.up, u);
    c.fovyDegrees = a.fovyDegrees + (b.fovyDegrees - a.fovyDegrees) * u;
    c.nearPlane = a.nearPlane + (b.nearPlane - a.nearPlane) * u;
    c.farPlane = a.farPlane + (b.farPlane - a.farPlane) * u;
    return c;
  }
  // Circle around the vertical axis through the look-at point, keeping height and distance.
  CameraSpec c = base;
  const glm::dvec3 offset = base.position - base.lookAt;
  const double angle = 2.0 * kPi * double(frame) / double(frames);
  const double cs = std::cos(angle), sn = std::sin(angle);
  c.position = base.lookAt + glm::dvec3(cs * offset.x + sn * offset.z, offset.y,
                                        -sn * offset.x + cs * offset.z);
  return c;
}

}  // namespace lzb
