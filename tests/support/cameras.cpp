#include "tests/support/cameras.hpp"

namespace lzb::test {

Camera lookAtCamera(const glm::dvec3& position, const glm::dvec3& lookAt, double nearPlane,
                    double farPlane, int width, int height, double fovyDegrees) {
  CameraSpec spec;
  spec.position = position;
  spec.lookAt = lookAt;
  spec.nearPlane = nearPlane;
  spec.farPlane = farPlane;
  spec.fovyDegrees = fovyDegrees;
  return Camera(spec, width, height);
}

Camera sceneCamera(const Scene& scene, int width, int height) {
  const CameraSpec base = scene.camera ? *scene.camera : frameBounds(scene.bounds());
  return Camera(withClipPlanes(base, scene.bounds()), width, height);
}

Camera pathFrame(const Scene& scene, int f, int frames, int width, int height) {
  const CameraSpec base = scene.camera ? *scene.camera : frameBounds(scene.bounds());
  return Camera(withClipPlanes(pathCamera(scene, base, f, frames), scene.bounds()), width, height);
}

CameraSpec closeSpec(const Scene& scene) {
  CameraSpec spec = frameBounds(scene.bounds());
  spec.position = spec.lookAt + 0.4 * (spec.position - spec.lookAt);
  spec.nearPlane = 0.05 * glm::length(spec.position - spec.lookAt);
  return spec;
}

Camera closeCamera(const Scene& scene, int width, int height) {
  return Camera(closeSpec(scene), width, height);
}

}  // namespace lzb::test
