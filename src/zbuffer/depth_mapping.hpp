#pragma once
// How the z-buffer's GL depth relates to THE depth convention (src/core/camera.hpp).
//
// Clipping: a reversed-Z projection for glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE),
//   z_ndc = near * (far - d) / (d * (far - near)),   d = view depth,
// maps near -> 1 and far -> 0 and keeps both clip planes precise in float for any far/near.
// w_clip = d, so the fragment shader reads d back as 1 / gl_FragCoord.w (the one conversion).
//
// Storage: the shader writes gl_FragDepth = d * 2^-k (exact: a power of two) into a
// GL_DEPTH_COMPONENT32F buffer with GL_LESS, cleared to 1. Readback multiplies by 2^k (exact), so
// the buffer orders fragments by exactly the float depth the framebuffer stores, and GL_LESS keeps
// the first drawn (smaller ID) on ties: the same (depth, id) minimum as compositeNearer.
#include <glm/glm.hpp>

#include "src/core/camera.hpp"

namespace lzb {

// Camera -> clip space with reversed-Z (see above); x, y as Camera::projection().
glm::dmat4 reversedZProjection(const Camera& camera);

// 2^-k, the smallest power of two with far * 2^-k <= 0.5, so every depth up to far stays below
// the clear value 1 even after rounding. Depths below 2^-126 * 2^k (far / near > 1e37) would be
// float denormals and lose precision.
float depthStorageScale(double farPlane);

}  // namespace lzb
