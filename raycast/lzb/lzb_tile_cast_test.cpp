#include "raycast/lzb/lzb_tile_cast.hpp"

#include <gtest/gtest.h>

#include "raycast/lzb/lzb_cull.hpp"
#include "raycast/lzb/lzb_renderer.hpp"
#include "src/image/metrics.hpp"
#include "src/scene/load.hpp"
#include "src/zbuffer/zbuffer_renderer.hpp"
#include "tests/support/cameras.hpp"

namespace lzb::localz {
namespace {

using test::pathFrame;

// With OOR, a tile's rays stop at the deepest far object whose bounding box holds their pixel:
// the exact hit of every such ray lies within that reach, and the bound is tighter than the far
// plane for some rays (those that would otherwise walk on to it).
TEST(LzbTileCast, OorReachHoldsEveryExactHit) {
  const Scene scene = loadScene("builtin:city?blocks=4", true);
  const LzbAccel accel(scene, LzbAccelParams{});
  const EmbreeScene embree(scene, {});
  for (int f : {0, 1}) {
    const Camera cam = pathFrame(scene, f, 4, 160, 120);
    const CulledScene culled = cullScene(accel, cam);
    const double tMin = cam.nearPlane();
    const ScreenTiles tiles(cam.width(), cam.height());
    const OorObjects oor(accel, culled, cam, tMin, tiles, 2);
    const std::vector<uint8_t> unfinished(size_t(cam.width()) * size_t(cam.height()), 1);
    const TileCastInput in{&cam, unfinished.data(), tMin, cam.farPlane(), &oor};
    TileScratch scratch;
    TileCastCounts counts;
    size_t rays = 0, hits = 0, bounded = 0;
    for (int t = 0; t < tiles.count(); ++t) {
      const TileRays r = tileRaysToCast(tiles.tile(t), t, in, scratch, counts);
      ASSERT_EQ(r.pixels.size(), r.reach.size());
      for (size_t k = 0; k < r.pixels.size(); ++k) {
        const int x = int(r.pixels[k]) % cam.width(), y = int(r.pixels[k]) / cam.width();
        const RayHit h =
            embree.intersect(cam.position(), cam.pixelDirection(x + 0.5, y + 0.5), tMin,
                             cam.farPlane());
        ++rays;
        bounded += r.reach[k] < cam.farPlane();
        if (!h.hit()) continue;
        ++hits;
        EXPECT_LE(double(h.t), r.reach[k]) << "frame " << f << " pixel " << x << "," << y;
      }
    }
    EXPECT_EQ(counts.cast, rays) << f;
    EXPECT_GT(hits, rays / 2) << f;
    EXPECT_EQ(bounded, rays) << f << ": every OOR ray has a finite object behind its pixel";
  }
}

}  // namespace
}  // namespace lzb::localz
