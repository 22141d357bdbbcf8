#pragma once
// A float pre-pass of the native z-buffer's set-up, eight triangles at a time: which of them may
// cover a pixel centre. Most triangles a sample tree draws are smaller than a pixel and cover
// none; the exact set-up (double precision, three divides a triangle) finds that one at a time.
// This pass rejects only triangles the exact set-up would drop silently too: each screen bound is
// widened by a margin above the float path's rounding error (bounded from the corners' distances
// to the eye, which is held as two floats), and a triangle with a vertex near or behind the near
// plane, or near the guard band, is always passed on. So the image and the set-up counts stay the
// exact path's.
#include <cstdint>

#include <glm/glm.hpp>

namespace lzb {

struct SoupPrefilter {
  // eye: the camera position; rows: its right, up and forward axes (world -> view);
  // s: pixels per unit at depth 1; guard: the exact set-up's clip band in pixels.
  SoupPrefilter(const glm::dvec3& eye, const glm::dmat3& rows, double s, int width, int height,
                double nearDepth, double guard);
  // For triangles t = 0..7 with corners at `corners[3 t + k]`: bit t set when t may cover a
  // pixel centre (pass it to the exact set-up).
  unsigned mayCover8(const glm::vec3* corners) const;

 private:
  float eye_[3], eyeRemainder_[3], row_[3][3];  // eye = eye_ + eyeRemainder_ (+ eyeError_)
  float s_, halfWidth_, halfHeight_, near_, loX_, hiX_, loY_, hiY_, eyeError_;
  int width_, height_;
};

}  // namespace lzb
