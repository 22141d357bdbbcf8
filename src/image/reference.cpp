#include "src/image/reference.hpp"

#include "src/core/error.hpp"

namespace lzb {

ReferenceFrame::ReferenceFrame(int w, int h) : width(w), height(h) {
  centreId.assign(size(), kNoId);
  subsampleId.assign(size() * kSubsamples, kNoId);
  boxColor.assign(size(), {0.0f, 0.0f, 0.0f});
}

void checkSubsampleSize(int width, int height, const std::string& option) {
  const long w = long(width) * kSubsampleSide, h = long(height) * kSubsampleSide;
  require(w <= kMaxImageSide && h <= kMaxImageSide, option,
          "the 4x4 sub-sample image of a " + std::to_string(width) + "x" + std::to_string(height) +
              " frame would be " + std::to_string(w) + "x" + std::to_string(h) +
              ", over the limit of " + std::to_string(kMaxImageSide) + " per side (use at most " +
              std::to_string(kMaxImageSide / kSubsampleSide) + ")");
}

Camera subsampleCamera(const Camera& camera) {
  checkSubsampleSize(camera.width(), camera.height(), "sub-sample camera");
  return Camera(camera.spec(), camera.width() * kSubsampleSide, camera.height() * kSubsampleSide);
}

namespace {

// Copies pixel (x, y)'s 16 sub-sample IDs and box-filters their colours.
void reducePixel(const Framebuffer& fine, int x, int y, ReferenceFrame& ref) {
  const size_t pixel = ref.index(x, y);
  uint32_t sum[3] = {0, 0, 0};
  for (int b = 0; b < kSubsampleSide; ++b)
    for (int a = 0; a < kSubsampleSide; ++a) {
      const size_t s = fine.index(kSubsampleSide * x + a, kSubsampleSide * y + b);
      ref.subsampleId[pixel * kSubsamples + size_t(a + kSubsampleSide * b)] = fine.id[s];
      for (int c = 0; c < 3; ++c) sum[c] += channel(fine.color[s], c);
    }
  for (int c = 0; c < 3; ++c) ref.boxColor[pixel][size_t(c)] = float(sum[c]) / float(kSubsamples);
}

}  // namespace

ReferenceFrame reduceReference(const Framebuffer& centres, const Framebuffer& subsamples) {
  const bool fits = subsamples.width == kSubsampleSide * centres.width &&
                    subsamples.height == kSubsampleSide * centres.height;
  require(fits && centres.size() > 0, "reference",
          "the sub-sample image must be 4x the centre image (" +
              std::to_string(subsamples.width) + "x" + std::to_string(subsamples.height) + " vs " +
              std::to_string(centres.width) + "x" + std::to_string(centres.height) + ")");
  ReferenceFrame ref(centres.width, centres.height);
  ref.centreId = centres.id;
#pragma omp parallel for schedule(static)
  for (int y = 0; y < ref.height; ++y)
    for (int x = 0; x < ref.width; ++x) reducePixel(subsamples, x, y, ref);
  return ref;
}

}  // namespace lzb
