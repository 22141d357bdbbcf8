#pragma once
// The exact reference a frame is judged against (the papers' "a pixel is correct when it shows a
// triangle visible somewhere in that pixel"): per pixel, the triangle IDs an exact method sees at
// the pixel centre and at a 4 x 4 grid of sub-samples, and the box-filtered colour.
//
// Sub-sample (a, b) of pixel (i, j), a, b in 0..3, sits at the centre of its stratum:
// (i + (a + 0.5) / 4, j + (b + 0.5) / 4). Camera maps one frustum onto any pixel grid, so pixel
// (4i + a, 4j + b) of the same camera spec at 4W x 4H is exactly that sub-sample: the reference
// is the exact method rendered once at W x H (the centres) and once at 4W x 4H, then reduced here.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "src/core/camera.hpp"
#include "src/core/framebuffer.hpp"

namespace lzb {

inline constexpr int kSubsampleSide = 4;
inline constexpr int kSubsamples = kSubsampleSide * kSubsampleSide;
inline constexpr int kReferenceSamplesPerPixel = kSubsamples + 1;  // the sub-samples + the centre

struct ReferenceFrame {
  int width = 0, height = 0;
  std::vector<uint64_t> centreId;  // per pixel: the ID at the pixel centre (kNoId: empty)
  // Per pixel, kSubsamples IDs in row-major order k = a + 4b: subsampleId[pixel * 16 + k].
  std::vector<uint64_t> subsampleId;
  // Per pixel, the mean of the 16 sub-samples' R, G, B in [0, 255] (empty samples count as
  // kBackground); a mean of bytes over 16 is a multiple of 1/16, held exactly by a float.
  std::vector<std::array<float, 3>> boxColor;

  ReferenceFrame() = default;
  ReferenceFrame(int w, int h);
  size_t size() const { return size_t(width) * size_t(height); }
  size_t index(int x, int y) const { return size_t(y) * size_t(width) + size_t(x); }
  const uint64_t* subsamples(size_t pixel) const { return &subsampleId[pixel * kSubsamples]; }
};

// Throws InputError naming `option` when a width x height frame's sub-sample image
// (4 width x 4 height) would exceed kMaxImageSide. Call it before any rendering or output.
void checkSubsampleSize(int width, int height, const std::string& option);

// The same camera spec on the 4W x 4H grid of sub-samples.
Camera subsampleCamera(const Camera& camera);

// Reduces the centre render (W x H) and the sub-sample render (4W x 4H) of one exact method to
// the reference. Throws InputError when the sizes do not match that way.
ReferenceFrame reduceReference(const Framebuffer& centres, const Framebuffer& subsamples);

}  // namespace lzb
