#include "src/zbuffer/soup_prefilter.hpp"

#include <algorithm>
#include <cmath>

namespace lzb {

namespace {

// Eight lanes: two SSE registers each on any x86-64, one AVX register in the AVX2 clone.
typedef float V8f __attribute__((vector_size(32)));
typedef int32_t V8i __attribute__((vector_size(32)));

// Lane-wise helpers as macros: a function taking or returning 8-lane vectors would have another
// ABI in each clone (clang refuses it, GCC warns); a macro is expanded within each clone.
#define LZB_VMIN(a, b) ((a) < (b) ? (a) : (b))
#define LZB_VMAX(a, b) ((a) > (b) ? (a) : (b))
#define LZB_VABS(a) ((a) < 0.0f ? -(a) : (a))
// floor, of x clamped to +-2^24 first (a NaN becomes a bound): the lanes it matters for lie in
// the guard band, the others are passed on whatever it gives. A true comparison lane is -1.
#define LZB_VCLAMP(x) LZB_VMIN(LZB_VMAX(x, -big), big)
#define LZB_VFLOOR(x)                                               \
  (__builtin_convertvector(LZB_VCLAMP(x), V8i) +                    \
   (LZB_VCLAMP(x) < __builtin_convertvector(                        \
                        __builtin_convertvector(LZB_VCLAMP(x), V8i), V8f)))

// The view coordinates' rounding error is at most 19 u D + u^2 |eye|, u = 2^-24, D = |corner -
// eye| (max norms): the eye is split into a float and the float of its remainder, so the
// subtractions cost 2 u D (not u |eye|: far from the origin that is what float cannot resolve),
// the rounded axes 3 u D, the 3-term dot product 9 u D and its inputs' errors 3.5 * 2 u D. This
// is 2x that, and 2^-40 |eye| for the remainder's rounding.
constexpr float kViewError = 1.0f / float(1 << 18);
constexpr double kEyeRemainderError = 1.0 / double(uint64_t(1) << 40);
// Relative rounding of the divide and the screen mapping, with the same slack.
constexpr float kScreenError = 1.0f / float(1 << 19);
// The exact set-up's own slack (half a subpixel of snapping) and then some.
constexpr float kSnapSlack = 2.0f / 256.0f;

}  // namespace

SoupPrefilter::SoupPrefilter(const glm::dvec3& eye, const glm::dmat3& rows, double s, int width,
                             int height, double nearDepth, double guard)
    : s_(float(s)),
      halfWidth_(0.5f * float(width)),
      halfHeight_(0.5f * float(height)),
      near_(float(nearDepth)),
      loX_(float(-guard)),
      hiX_(float(width + guard)),
      loY_(float(-guard)),
      hiY_(float(height + guard)),
      eyeError_(float(kEyeRemainderError *
                      std::max({std::abs(eye.x), std::abs(eye.y), std::abs(eye.z)}))),
      width_(width),
      height_(height) {
  for (int k = 0; k < 3; ++k) {
    eye_[k] = float(eye[k]);
    eyeRemainder_[k] = float(eye[k] - double(eye_[k]));
    for (int j = 0; j < 3; ++j) row_[k][j] = float(rows[j][k]);  // glm: rows[column][row]
  }
}

__attribute__((target_clones("avx2", "default"))) unsigned SoupPrefilter::mayCover8(
    const glm::vec3* c) const {
  const V8f zero = {}, big = zero + 16777216.0f;
  V8f minX = zero + INFINITY, maxX = zero - INFINITY, minY = minX, maxY = maxX;
  V8f minZ = zero + INFINITY, magnitude = zero, slope = zero;
  for (int k = 0; k < 3; ++k) {
    V8f p[3];
    for (int a = 0; a < 3; ++a)
      p[a] = V8f{c[k][a],      c[3 + k][a],  c[6 + k][a],  c[9 + k][a],
                 c[12 + k][a], c[15 + k][a], c[18 + k][a], c[21 + k][a]};
    V8f d[3], v[3];
    for (int a = 0; a < 3; ++a) {
      d[a] = (p[a] - eye_[a]) - eyeRemainder_[a];
      magnitude = LZB_VMAX(magnitude, LZB_VABS(d[a]));
    }
    for (int r = 0; r < 3; ++r) v[r] = row_[r][0] * d[0] + row_[r][1] * d[1] + row_[r][2] * d[2];
    const V8f inverse = 1.0f / v[2], f = s_ * inverse;
    const V8f x = halfWidth_ + f * v[0], y = halfHeight_ - f * v[1];
    minX = LZB_VMIN(minX, x), maxX = LZB_VMAX(maxX, x);
    minY = LZB_VMIN(minY, y), maxY = LZB_VMAX(maxY, y);
    minZ = LZB_VMIN(minZ, v[2]);
    slope = LZB_VMAX(slope, (LZB_VABS(v[0]) + LZB_VABS(v[1])) * inverse);
  }
  const V8f viewError = kViewError * magnitude + eyeError_;
  const V8f margin = s_ * viewError * (1.0f + slope) / (minZ - viewError) +
                     kScreenError * (halfWidth_ + halfHeight_ + s_ * slope) + kSnapSlack;
  // Passed on: a corner near or behind the near plane, near the guard band, or not a number
  // (every comparison with NaN is false, so `settled` is then false).
  const V8i settled = (minZ - viewError > near_) & (minX - margin > loX_) &
                      (maxX + margin < hiX_) & (minY - margin > loY_) & (maxY + margin < hiY_) &
                      (margin < 1.0f);
  // A centre i + 0.5 with 0 <= i < n in [lo, hi]: ceil(lo - 0.5) <= floor(hi - 0.5), clamped.
  const V8i none0 = {}, lastX = none0 + (width_ - 1), lastY = none0 + (height_ - 1);
  V8i x0 = -LZB_VFLOOR(0.5f - (minX - margin)), x1 = LZB_VFLOOR(maxX + margin - 0.5f);
  V8i y0 = -LZB_VFLOOR(0.5f - (minY - margin)), y1 = LZB_VFLOOR(maxY + margin - 0.5f);
  x0 = LZB_VMAX(x0, none0), y0 = LZB_VMAX(y0, none0);
  x1 = LZB_VMIN(x1, lastX), y1 = LZB_VMIN(y1, lastY);
  const V8i none = (x0 > x1) | (y0 > y1);
  const V8i reject = settled & none;
  unsigned keep = 0;
  for (int t = 0; t < 8; ++t) keep |= unsigned(reject[t] == 0) << t;
  return keep;
}

#undef LZB_VFLOOR
#undef LZB_VCLAMP
#undef LZB_VABS
#undef LZB_VMAX
#undef LZB_VMIN

}  // namespace lzb
