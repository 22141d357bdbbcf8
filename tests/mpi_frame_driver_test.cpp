// The frame driver on any number of ranks: its frame equals the ranks' shares composited and
// shaded in one process, and a frame rendered into the buffer of the previous one (whose driver
// clears only the tiles that frame left in use) equals the same frame rendered into a new buffer,
// whether the renderer records its touched tiles or not.
#include <gtest/gtest.h>

#include "mpi/frame_driver.hpp"
#include "mpi/frame_tiles.hpp"
#include "mpi/group.hpp"
#include "src/core/shading.hpp"
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
                      uint64_t(x * 3 + y + share.rank * 5) % triangles_);
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

// The ranks' tiles shaded by their owners and gathered at the root give the frame of every
// rank's share composited in one process and shaded there, ties between ranks included.
TEST(MpiFrameDriver, EqualsTheSerialComposite) {
  const mpi::Group g = mpi::Group::world();
  const Scene scene = test::nestedScene();
  const Camera camera = test::sceneCamera(scene, 83, 45);
  BlockRenderer renderer(scene.expandedTriangles(), true);
  const mpi::FrameDriver driver(g, scene, mpi::CompositeStrategy::kTiles);
  Framebuffer frame;
  for (int f = 0; f < 3; ++f) {
    driver.render(renderer, camera, f, frame);
    if (!g.root()) continue;
    Framebuffer expected(camera.width(), camera.height());
    for (int r = 0; r < g.size; ++r) {
      Framebuffer part(camera.width(), camera.height());
      FrameStats unused;
      renderer.render(camera, f, WorkShare{r, g.size}, part, unused);
      compositeNearer(expected, part);
    }
    shadeFromIds(scene, camera, expected);
    expectFrame(frame, expected, f);
  }
}

}  // namespace
}  // namespace lzb
