// The frame driver's sparse frames: a frame rendered into the buffer of the previous one (whose
// driver clears only the tiles that frame left in use) equals the same frame rendered into a new
// buffer, on any number of ranks, whether the renderer records its touched tiles or not.
#include <gtest/gtest.h>

#include "mpi/frame_driver.hpp"
#include "mpi/frame_tiles.hpp"
#include "mpi/group.hpp"
#include "tests/support/cameras.hpp"
#include "tests/support/scenes.hpp"

namespace lzb {
namespace {

// Frame f covers, on each rank, a small block that moves with f and the rank (so each frame
// leaves tiles the next does not cover), with ties between ranks.
class BlockRenderer : public Renderer {
 public:
  BlockRenderer(uint64_t triangles, bool record) : triangles_(triangles), record_(record) {}
  std::string name() const override { return "block"; }
  std::string decomposition() const override { return "a block a rank"; }
  void render(const Camera&, int frame, const WorkShare& share, Framebuffer& fb,
              FrameStats& stats) override {
    const int x0 = (frame * 37 + share.rank * 11) % (fb.width - 20);
    const int y0 = (frame * 23 + share.rank * 7) % (fb.height - 10);
    for (int y = y0; y < y0 + 10; ++y)
      for (int x = x0; x < x0 + 20; ++x)
        fb.keepNearer(fb.index(x, y), float(1 + (x + y) % 3), kBackground,
                      uint64_t(x * 3 + y) % triangles_);
    if (record_) stats.touchedTiles = touchedTiles(fb, ScreenTiles(fb.width, fb.height));
  }

 private:
  uint64_t triangles_;
  bool record_;
};

void expectFrame(const Framebuffer& a, const Framebuffer& b, int f) {
  EXPECT_EQ(a.depth, b.depth) << "frame " << f;
  EXPECT_EQ(a.id, b.id) << "frame " << f;
  EXPECT_EQ(a.color, b.color) << "frame " << f;
}

TEST(MpiFrameDriver, ReusedBufferEqualsFreshBuffer) {
  const mpi::Group g = mpi::Group::world();
  const Scene scene = test::nestedScene();
  const Camera camera = test::sceneCamera(scene, 83, 45);
  for (const bool record : {false, true}) {
    BlockRenderer renderer(scene.expandedTriangles(), record);
    const mpi::FrameDriver driver(g, scene, mpi::CompositeStrategy::kTiles);
    Framebuffer reused;
    for (int f = 0; f < 4; ++f) {
      driver.render(renderer, camera, f, reused);
      Framebuffer fresh;
      driver.render(renderer, camera, f, fresh);
      if (!g.root()) continue;
      EXPECT_GT(fresh.coveredCount(), 0u);
      expectFrame(reused, fresh, f);
    }
  }
}

}  // namespace
}  // namespace lzb
