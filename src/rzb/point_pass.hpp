#pragma once
// The point pass of the randomized z-buffer: the samples of the selected boxes, drawn fresh from
// the frame's Philox stream or read from the sample cache, splatted by the splatting core
// (src/splat/splatter.hpp) into a key buffer (src/core/depth_key.hpp) on every thread at once.
// Samples on faces turned away from the eye are dropped first (when asked). Colour is shaded
// afterwards from the resolved IDs (shadeFromIds), as for the exact methods; the Gaussian
// reconstruction below is the one exception.
#include <cstdint>
#include <span>
#include <vector>

#include "src/core/camera.hpp"
#include "src/core/framebuffer.hpp"
#include "src/rzb/box_selection.hpp"
#include "src/core/depth_key.hpp"
#include "src/core/philox_stream.hpp"
#include "src/rzb/sample_cache.hpp"
#include "src/splat/splatter.hpp"

namespace lzb::rzb {

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
                     const SampleStream& stream, const SplatSetup& setup, bool dropBackfaces,
                     KeyBuffer& keys, int threads);

// Gaussian reconstruction's second pass: every sample visible against `depth` (the composited
// depth buffer of the splat pass) adds its shaded colour with a Gaussian weight (sigma = d / 2
// pixels) to the pixels within 2 sigma, in fixed point (integer sums: any order, same result).
// accum: 4 per pixel (r, g, b, weight).
PassCounts gaussAccumulate(std::span<const SplatJob> jobs, std::span<const SelectedBox> boxes,
                           const SampleStream& stream, const SplatSetup& setup, bool dropBackfaces,
                           const std::vector<float>& depth, const Scene& scene,
                           std::vector<uint64_t>& accum, int threads);

}  // namespace lzb::rzb
