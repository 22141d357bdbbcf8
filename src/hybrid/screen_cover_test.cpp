// The screen cover is exact (every pixel where a ray hits lies in it, through rotated, scaled
// and nested instances), saves rays where the scene is small on screen, and gives way where it
// would save nothing or its walk would cost too much.
#include "src/hybrid/screen_cover.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "src/scene/load.hpp"
#include "tests/support/cameras.hpp"
#include "tests/support/scenes.hpp"

namespace lzb {
namespace {

// Casts the frame without a cover and with screenCover's; checks that the cover holds every
// hit and that the covered cast is the same image. Returns the blocks covered (0 without one).
uint64_t checkCover(const Scene& scene, const Camera& cam) {
  const localz::LzbAccel accel(scene, {});
  const EmbreeScene embree(scene, {});
  std::vector<uint8_t> touched;
  Framebuffer whole(cam.width(), cam.height());
  castEveryPixel(embree, cam, WorkShare{}, whole, touched, 2);
  const std::optional<BlockCover> cover = hybrid::screenCover(accel, cam, 1u << 20);
  if (!cover) return 0;
  for (int y = 0; y < cam.height(); ++y)
    for (int x = 0; x < cam.width(); ++x)
      if (whole.id[whole.index(x, y)] != kNoId) {
        EXPECT_TRUE(cover->covers(x, y)) << x << ", " << y;
      }
  Framebuffer fb(cam.width(), cam.height());
  castEveryPixel(embree, cam, WorkShare{}, fb, touched, 2, true, &*cover);
  EXPECT_EQ(fb.id, whole.id);
  EXPECT_EQ(fb.depth, whole.depth);
  return cover->blocks();
}

TEST(ScreenCover, HoldsEveryHitThroughNestedRotatedInstances) {
  for (uint64_t seed : {7u, 8u, 9u}) {
    const Scene scene = test::nestedScene(seed);
    for (int f = 0; f < 4; ++f) {
      CameraSpec spec = frameBounds(scene.bounds());
      // Small on screen, its instances' boxes larger than the boxes marked whole.
      spec.position = spec.lookAt + 3.0 * (spec.position - spec.lookAt);
      spec.nearPlane = spec.farPlane = 0.0;  // (withClipPlanes: from the bounds)
      const Camera cam(withClipPlanes(pathCamera(scene, spec, f, 4), scene.bounds()), 384, 256);
      const uint64_t blocks = checkCover(scene, cam);
      EXPECT_GT(blocks, 0u) << seed << " " << f;
      EXPECT_LT(blocks, 96u * 64u / 2u) << "less than half the frame: " << seed << " " << f;
    }
  }
}

// The city's distant frames (its circle passes outside it): a skyline across the frame.
TEST(ScreenCover, CoversTheCitysSkylineOnly) {
  const Scene city = loadScene("builtin:city?blocks=3", true);
  for (int f : {4, 5, 6}) {
    const Camera cam = test::pathFrame(city, f, 11, 192, 144);
    const uint64_t blocks = checkCover(city, cam);
    EXPECT_GT(blocks, 0u) << f;
    EXPECT_LT(blocks, 48u * 36u / 4u) << f;
  }
}

TEST(ScreenCover, GivesWayWhereItWouldSaveNothingOrCostTooMuch) {
  const Scene scene = test::nestedScene();
  const localz::LzbAccel accel(scene, {});
  CameraSpec inside = frameBounds(scene.bounds());
  inside.position = scene.bounds().center() + glm::dvec3(1e-3);  // boxes around the eye
  inside.nearPlane = 1e-3;
  EXPECT_FALSE(hybrid::screenCover(accel, Camera(inside, 64, 48), 1u << 20));
  const Camera far = test::sceneCamera(scene, 64, 48);
  EXPECT_TRUE(hybrid::screenCover(accel, far, 1u << 20));
  EXPECT_FALSE(hybrid::screenCover(accel, far, 3)) << "over the budget";
}

}  // namespace
}  // namespace lzb
