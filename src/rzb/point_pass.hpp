#pragma once
// The point pass: native, multithreaded splatting of samples into a key buffer by atomic minimum.
//
// Payload choice. A pixel keeps the minimum over its samples of the packed key
//   (float bits of the view depth) << 32 | expanded triangle ID        (64 bits)
// Positive floats order like their bit patterns, so the minimum is the nearest sample, and equal
// depths break on the smaller ID: exactly compositeNearer's (depth, id) order, which is what makes
// ranks and threads interchangeable (any order of atomic minima gives the same buffer, and
// compositing rank buffers by (depth, id) gives the buffer of one rank doing everything). The ID
// fits the 32-bit payload when the scene has fewer than 2^32 expanded triangles. Larger scenes
// (10^12-triangle instancing) use a 128-bit key (depth bits, 64-bit ID) updated by a 16-byte
// compare-and-swap loop. Colour is not in the key: it is shaded afterwards from the resolved ID by
// the one shading rule (shadeFromIds), as for the exact methods.
//
// Depth is THE convention of src/core/camera.hpp (view depth along forward, float), computed in
// double from the box's node-frame -> camera-space map; samples nearer than the near plane or
// beyond the far plane are dropped like the z-buffer clips them.
#include <cstdint>
#include <span>
#include <vector>

#include "src/core/camera.hpp"
#include "src/core/framebuffer.hpp"
#include "src/rzb/box_selection.hpp"
#include "src/rzb/philox_stream.hpp"
#include "src/rzb/sample_cache.hpp"

namespace lzb::rzb {

struct alignas(16) Key128 {
  uint64_t lo, hi;  // hi: depth bits; lo: ID (little-endian 128-bit layout)
};

class KeyBuffer {
 public:
  // Sizes and clears to empty; wide: 128-bit keys.
  void reset(int width, int height, bool wide, int threads);
  int width() const { return width_; }
  int height() const { return height_; }
  bool wide() const { return wide_; }
  uint64_t* narrow() { return narrow_.data(); }
  Key128* wideKeys() { return wide_keys_.data(); }
  // Depth and ID of every pixel into fb (colour untouched); empty pixels get kEmptyDepth / kNoId.
  void resolve(Framebuffer& fb, int threads) const;

 private:
  int width_ = 0, height_ = 0;
  bool wide_ = false;
  std::vector<uint64_t> narrow_;
  std::vector<Key128> wide_keys_;
};

struct SplatSetup {
  int width = 0, height = 0;
  double pixelScale = 1.0;  // camera.pixelsPerUnitAt(1)
  double nearPlane = 0.1, farPlane = 1e30;
  int splat = 1;            // d: splats of d x d pixels
  bool dropBackfaces = true;
  static SplatSetup from(const Camera& camera, int splat, bool dropBackfaces);
};

// A piece of work: samples [first, first + count) of boxes[box], drawn from the stream or read
// from a cached set (cached != null).
struct SplatJob {
  uint32_t box;
  uint64_t first, count;
  const CachedSample* cached;
};

struct PassCounts {
  uint64_t drawn = 0;     // samples generated or read
  uint64_t backfacing = 0;
  uint64_t splatted = 0;  // samples that reached the image
};

// Splits every box's samples (or cached set) into jobs of at most chunk samples, in box order.
void appendJobs(std::vector<SplatJob>& jobs, uint32_t box, uint64_t count,
                const CachedSample* cached, uint64_t chunk = 1 << 14);

PassCounts splatJobs(std::span<const SplatJob> jobs, std::span<const SelectedBox> boxes,
                     const SampleStream& stream, const SplatSetup& setup, KeyBuffer& keys,
                     int threads);

// Gaussian reconstruction's second pass: every sample visible against `depth` (the composited
// depth buffer of the splat pass) adds its shaded colour with a Gaussian weight (sigma = d / 2
// pixels) to the pixels within 2 sigma, in fixed point (integer sums: any order, same result).
// accum: 4 per pixel (r, g, b, weight).
PassCounts gaussAccumulate(std::span<const SplatJob> jobs, std::span<const SelectedBox> boxes,
                           const SampleStream& stream, const SplatSetup& setup,
                           const std::vector<float>& depth, const Scene& scene,
                           std::vector<uint64_t>& accum, int threads);

// The atomic-min scatter limit: random 64-bit atomic minima into a width x height buffer, per
// second, on `threads` threads for about `seconds`.
double measureScatterLimit(int width, int height, int threads, double seconds);

}  // namespace lzb::rzb
