#pragma once
// The tests' camera builders, one family: a look-at camera, the scene's own (or framing) camera,
// frame f of the default path, and a close view of hand-built scenes.
#include <glm/glm.hpp>

#include "src/core/camera.hpp"
#include "src/core/scene.hpp"

namespace lzb::test {

// A camera at `position` looking at `lookAt` with the given clip planes and vertical fov.
Camera lookAtCamera(const glm::dvec3& position, const glm::dvec3& lookAt, double nearPlane,
                    double farPlane, int width, int height, double fovyDegrees = 45.0);

// The scene's own camera (or one framing its bounds) with clip planes from the bounds.
Camera sceneCamera(const Scene& scene, int width, int height);

// Frame f of `frames` on the default path (from the scene's camera, else framed), with clip
// planes from the bounds.
Camera pathFrame(const Scene& scene, int f, int frames, int width, int height);

// Closer than frameBounds: the bounds of rotated nested boxes are loose, the triangles compact.
CameraSpec closeSpec(const Scene& scene);
Camera closeCamera(const Scene& scene, int width, int height);

}  // namespace lzb::test
