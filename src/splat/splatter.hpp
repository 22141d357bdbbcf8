#pragma once
// The splatting core: camera-space points (x right, y up, z view depth) projected into a key
// buffer (src/core/depth_key.hpp) by atomic minimum, one pixel each or d x d pixels (splat size
// d). Every point-based method (rzb, and the sample tree, surfels and sqrt5 that reuse it) puts
// its samples here, so all of them composite with each other and with the z-buffer passes by the
// one (depth, ID) rule, and any thread or rank order gives the same buffer.
//
// Depth is THE convention of src/core/camera.hpp; points nearer than the near plane or beyond the
// far plane are dropped, as the z-buffer clips them. A point at pixel position (px, py) lands in
// pixel (floor(px), floor(py)); a d x d splat covers the d x d pixels whose centres are nearest to
// it, or with `disc` only those of them whose centres lie within d / 2 of it (the surfels' round
// sprites). Colour is not in the key: it is shaded afterwards from the resolved ID.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "src/core/camera.hpp"
#include "src/core/depth_key.hpp"

namespace lzb {

// The splat sizes a method may ask for (--splat): larger ones only blur the image.
constexpr int kMaxSplat = 64;
// Throws InputError naming `field` unless 1 <= splat <= kMaxSplat.
void validateSplat(int splat, const std::string& field = "--splat");

struct SplatSetup {
  int width = 0, height = 0;
  double pixelScale = 1.0;  // camera.pixelsPerUnitAt(1)
  double nearPlane = 0.1, farPlane = 1e30;
  int splat = 1;     // d: splats of d x d pixels
  bool disc = false;  // only the pixel centres within d / 2 of the point
  static SplatSetup from(const Camera& camera, int splat);
};

// Puts points into a key buffer (kWide: 128-bit keys; kPixel: d == 1). Points are buffered and
// written in flush() (or when kBatch are waiting): the caller's own loads and the key buffer then
// take turns in the cache instead of evicting each other.
template <bool kWide, bool kPixel>
class PointSplatter {
 public:
  static constexpr size_t kBatch = 4096;

  PointSplatter(const SplatSetup& setup, KeyBuffer& kb)
      : s_(setup),
        keys_(kWide ? static_cast<void*>(kb.wideKeys()) : static_cast<void*>(kb.narrow())),
        cx_(0.5 * setup.width),
        cy_(0.5 * setup.height) {
    pending_.reserve(kBatch);
    if constexpr (kPixel) targets_.resize(kBatch);
  }

  // One point in camera space (float is ample for the pixel and the depth key).
  void add(float x, float y, float z, uint64_t id) {
    pending_.push_back(Pending{x, y, z, id});
    if (pending_.size() == kBatch) flush();
  }

  void flush() {
    if constexpr (kPixel) {
      // Pixel indices first, then the atomic minima with the key buffer's lines prefetched a few
      // points ahead (the buffer is larger than L2, and a locked compare-and-swap waits for the
      // loads before it, so misses would otherwise come one at a time).
      if (targets_.size() < pending_.size()) targets_.resize(pending_.size());
      size_t m = 0;
      for (const Pending& q : pending_) {
        if (!(q.z >= s_.nearPlane && q.z <= s_.farPlane)) continue;
        const double inv = s_.pixelScale / q.z;
        const double px = cx_ + q.x * inv, py = cy_ - q.y * inv;
        if (!(px >= 0.0 && px < s_.width && py >= 0.0 && py < s_.height)) continue;
        targets_[m++] = Target{size_t(int(py)) * size_t(s_.width) + size_t(int(px)),
                               q.z, q.id};
      }
      constexpr size_t kAhead = 16;
      for (size_t k = 0; k < m; ++k) {
        if (k + kAhead < m) prefetchKey(targets_[k + kAhead].pixel);
        write(targets_[k].pixel, targets_[k].depth, targets_[k].id);
      }
      splatted_ += m;
    } else {
      for (const Pending& q : pending_) putSplat(q);
    }
    pending_.clear();
  }

  // Points that reached the image (inside the clip planes and the image).
  uint64_t splatted() const { return splatted_; }

 private:
  struct Pending {
    float x, y, z;
    uint64_t id;
  };
  struct Target {
    size_t pixel;
    float depth;
    uint64_t id;
  };

  void prefetchKey(size_t i) const {
    if constexpr (kWide)
      __builtin_prefetch(static_cast<WideKey*>(keys_) + i, 1);
    else
      __builtin_prefetch(static_cast<uint64_t*>(keys_) + i, 1);
  }

  void write(size_t i, float depth, uint64_t id) {
    if constexpr (kWide)
      atomicMinKey(static_cast<WideKey*>(keys_) + i, wideKey(depth, id));
    else
      atomicMinKey(static_cast<uint64_t*>(keys_) + i, narrowKey(depth, id));
  }

  void putSplat(const Pending& q) {
    if (!(q.z >= s_.nearPlane && q.z <= s_.farPlane)) return;
    const double inv = s_.pixelScale / q.z;
    const double px = cx_ + q.x * inv, py = cy_ - q.y * inv;
    const double d = s_.splat, off = 0.5 - 0.5 * d;
    const double fx = std::floor(px + off), fy = std::floor(py + off);
    if (!(fx > -d && fx < s_.width && fy > -d && fy < s_.height)) return;
    const int x0 = std::max(int(fx), 0), x1 = std::min(int(fx) + s_.splat, s_.width);
    const int y0 = std::max(int(fy), 0), y1 = std::min(int(fy) + s_.splat, s_.height);
    if (s_.disc) {
      const double r2 = 0.25 * d * d;
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
          const double ex = x + 0.5 - px, ey = y + 0.5 - py;
          if (ex * ex + ey * ey <= r2) write(size_t(y) * size_t(s_.width) + size_t(x), q.z, q.id);
        }
    } else {
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) write(size_t(y) * size_t(s_.width) + size_t(x), q.z, q.id);
    }
    ++splatted_;
  }

  const SplatSetup s_;  // a copy: the atomics would make the compiler reload a reference's fields
  void* keys_;
  double cx_, cy_;
  std::vector<Pending> pending_;
  std::vector<Target> targets_;
  uint64_t splatted_ = 0;
};

// The one place the key buffer's width becomes a template argument: fn.template
// operator()<kWide>(), for a lambda []<bool kWide>() {...}.
template <class Fn>
auto withKeyWidth(const KeyBuffer& keys, Fn&& fn) {
  if (keys.wide()) return fn.template operator()<true>();
  return fn.template operator()<false>();
}

// The PointSplatter<kWide, kPixel> for `keys` and splat size d: fn.template
// operator()<kWide, kPixel>(), for a lambda []<bool kWide, bool kPixel>() {...}.
template <class Fn>
auto withSplatter(const KeyBuffer& keys, int splat, Fn&& fn) {
  return withKeyWidth(keys, [&]<bool kWide>() {
    if (splat == 1) return fn.template operator()<kWide, true>();
    return fn.template operator()<kWide, false>();
  });
}

// The atomic-min scatter limit: random 64-bit atomic minima into a width x height buffer, per
// second, on `threads` threads for about `seconds` (the bar every splatting pass is measured by).
double measureScatterLimit(int width, int height, int threads, double seconds);

}  // namespace lzb
