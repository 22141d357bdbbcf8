#include "src/zbuffer/triangle_rasterizer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <numeric>
#include <random>
#include <stdexcept>
#include <vector>

#include "src/zbuffer/mesh_buffers.hpp"
#include "tests/support/cameras.hpp"

namespace lzb {
namespace {

const Rgba8 kGrey = packRgba8(180, 180, 180);

// count random triangles in a cube of side `extent` around the origin, edges about `size`.
void addSoup(Mesh& m, size_t count, float extent, float size, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> pos(-0.5f * extent, 0.5f * extent), off(-size, size);
  m.positions.reserve(3 * count);
  m.colors.reserve(count);
  while (m.size() < count) {
    const glm::vec3 c(pos(rng), pos(rng), pos(rng));
    auto corner = [&] { return c + glm::vec3(off(rng), off(rng), off(rng)); };
    m.add(corner(), corner(), corner(), kGrey);
  }
}

void addQuad(Mesh& m, float halfSize, float z) {
  ASSERT_TRUE(
      m.add({-halfSize, -halfSize, z}, {halfSize, -halfSize, z}, {halfSize, halfSize, z}, kGrey));
  ASSERT_TRUE(
      m.add({-halfSize, -halfSize, z}, {halfSize, halfSize, z}, {-halfSize, halfSize, z}, kGrey));
}

// Node 0: an empty root placing node 1 (a soup) by a rotation and a translation.
struct SoupScene {
  Scene scene;
  glm::dmat4 world;
  SoupScene(size_t triangles, float size) {
    const uint32_t root = scene.addNode("root"), soup = scene.addNode("soup");
    addSoup(scene.nodes[soup].mesh, triangles, 4.0f, size, 5);
    world = glm::rotate(glm::translate(glm::dmat4(1.0), {0.3, -0.2, -6.0}), 0.6,
                        glm::dvec3(0.3, 1.0, 0.2));
    scene.nodes[root].instances = {{soup, world}};
    scene.root = root;
    scene.finalize();
  }
  uint32_t soup() const { return 1; }
  size_t size() const { return scene.nodes[1].mesh.size(); }
};

// One pass set: begin, the draws, end.
Framebuffer pass(TriangleRasterizer& r, const Camera& camera, double farClip,
                 const std::function<void()>& draws) {
  Framebuffer fb(camera.width(), camera.height());
  r.begin(camera, farClip);
  draws();
  r.end(fb);
  return fb;
}

bool sameBits(float a, float b) {
  return std::memcmp(&a, &b, sizeof(float)) == 0;
}

// IDs equal and depths bit-identical everywhere; returns the number of differing pixels.
size_t differences(const Framebuffer& a, const Framebuffer& b) {
  EXPECT_EQ(a.size(), b.size());
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i)
    n += a.id[i] != b.id[i] || !sameBits(a.depth[i], b.depth[i]);
  return n;
}

std::vector<uint32_t> iota(size_t n) {
  std::vector<uint32_t> v(n);
  std::iota(v.begin(), v.end(), 0u);
  return v;
}

TEST(TriangleRasterizer, ListMatchesRangeInAnyOrderWithDuplicates) {
  const SoupScene s(3000, 0.4f);
  const Camera camera = test::lookAtCamera({0.5, 1.0, 0.0}, {0.0, 0.0, -6.0}, 0.5, 30.0, 96, 72);
  TriangleRasterizer r(s.scene);
  const uint64_t base = 1000;
  const Framebuffer range =
      pass(r, camera, 0.0, [&] { r.drawRange(s.soup(), s.world, 0, s.size(), base); });
  EXPECT_GT(range.coveredCount(), range.size() / 3);
  std::vector<uint32_t> list = iota(s.size());
  EXPECT_EQ(
      differences(range, pass(r, camera, 0.0, [&] { r.drawList(s.soup(), s.world, list, base); })),
      0u);
  // Shuffled, with every tenth triangle twice.
  std::mt19937 rng(1);
  for (size_t t = 0; t < s.size(); t += 10) list.push_back(uint32_t(t));
  std::shuffle(list.begin(), list.end(), rng);
  EXPECT_EQ(
      differences(range, pass(r, camera, 0.0, [&] { r.drawList(s.soup(), s.world, list, base); })),
      0u);
  EXPECT_EQ(r.counts().triangles, list.size());
  // A subset in descending order against one range draw per listed triangle.
  std::vector<uint32_t> subset;
  for (uint32_t t = 0; t < s.size(); t += 3) subset.push_back(t);
  const Framebuffer ranges = pass(r, camera, 0.0, [&] {
    for (const uint32_t t : subset) r.drawRange(s.soup(), s.world, t, 1, base + t);
  });
  EXPECT_EQ(r.counts().drawCalls, subset.size());
  std::reverse(subset.begin(), subset.end());
  const Framebuffer listed =
      pass(r, camera, 0.0, [&] { r.drawList(s.soup(), s.world, subset, base); });
  EXPECT_EQ(differences(ranges, listed), 0u);
  size_t fromSubset = 0;
  for (const uint64_t id : listed.id) {
    if (id == kNoId) continue;
    ASSERT_EQ((id - base) % 3, 0u) << id;
    ++fromSubset;
  }
  EXPECT_GT(fromSubset, listed.size() / 5);
}

TEST(TriangleRasterizer, IdsCarryIntoTheHighWord) {
  const SoupScene s(500, 0.5f);
  const Camera camera = test::lookAtCamera({0.5, 1.0, 0.0}, {0.0, 0.0, -6.0}, 0.5, 30.0, 96, 72);
  TriangleRasterizer r(s.scene);
  const uint64_t base = (uint64_t(7) << 32) - 250;  // the soup's IDs cross a 2^32 boundary
  const Framebuffer range =
      pass(r, camera, 0.0, [&] { r.drawRange(s.soup(), s.world, 100, 400, base + 100); });
  const std::vector<uint32_t> list = iota(s.size());
  const Framebuffer listed = pass(
      r, camera, 0.0, [&] { r.drawList(s.soup(), s.world, std::span(list).subspan(100), base); });
  EXPECT_EQ(differences(range, listed), 0u);
  bool low = false, high = false;
  for (const uint64_t id : listed.id) {
    if (id == kNoId) continue;
    ASSERT_GE(id, base + 100);
    ASSERT_LT(id, base + 500);
    low |= id < (uint64_t(7) << 32);
    high |= id >= (uint64_t(7) << 32);
  }
  EXPECT_TRUE(low && high);
}

TEST(TriangleRasterizer, TwoPassesIntoOneTargetKeepTheNearer) {
  Scene scene;
  scene.addNode("quads");
  addQuad(scene.nodes[0].mesh, 2.0f, -5.0f);  // triangles 0, 1: big, far
  addQuad(scene.nodes[0].mesh, 0.5f, -4.0f);  // triangles 2, 3: small, near
  scene.finalize();
  const Camera camera = test::lookAtCamera({0.0, 0.0, 0.0}, {0.0, 0.0, -1.0}, 0.1, 100.0, 96, 72);
  TriangleRasterizer r(scene);
  const std::vector<uint32_t> nearList = {3, 2}, farList = {0, 1};
  const glm::dmat4 id(1.0);
  const Framebuffer farThenNear = pass(r, camera, 0.0, [&] {
    r.drawRange(0, id, 0, 2, 0);
    r.drawList(0, id, nearList, 0);
  });
  const Framebuffer nearThenFar = pass(r, camera, 0.0, [&] {
    r.drawRange(0, id, 2, 2, 2);
    r.drawList(0, id, farList, 0);
  });
  for (const Framebuffer* fb : {&farThenNear, &nearThenFar}) {
    const size_t centre = fb->index(fb->width / 2, fb->height / 2);
    EXPECT_TRUE(fb->id[centre] == 2 || fb->id[centre] == 3) << fb->id[centre];
    EXPECT_NEAR(fb->depth[centre], 4.0, 4e-6);
    const size_t side = fb->index(fb->width / 2, 3);  // on the big quad only
    EXPECT_TRUE(fb->id[side] == 0 || fb->id[side] == 1) << fb->id[side];
    EXPECT_NEAR(fb->depth[side], 5.0, 5e-6);
  }
  EXPECT_EQ(differences(farThenNear, nearThenFar), 0u);
}

// read() mid-way gives the first pass alone and leaves the pass set open: the draws after it land
// in the same buffers, as if there had been no read (nor flush).
TEST(TriangleRasterizer, ReadKeepsThePassSetOpen) {
  const SoupScene s(3000, 0.3f);
  const Camera camera = test::lookAtCamera({0.5, 1.0, 0.0}, {0.0, 0.0, -6.0}, 0.5, 30.0, 96, 72);
  TriangleRasterizer r(s.scene);
  const std::vector<uint32_t> all = iota(3000);
  const std::span<const uint32_t> first(all.data(), 1500), second(all.data() + 1500, 1500);
  const double clip = 6.0;
  const Framebuffer firstAlone =
      pass(r, camera, clip, [&] { r.drawList(s.soup(), s.world, first, 0); });
  const Framebuffer both = pass(r, camera, clip, [&] {
    r.drawList(s.soup(), s.world, first, 0);
    r.setFarClip(0.0);
    r.drawList(s.soup(), s.world, second, 0);
  });
  Framebuffer midway(1, 1), last(1, 1);
  r.begin(camera, clip);
  r.drawList(s.soup(), s.world, first, 0);
  r.flush();  // changes nothing
  r.read(midway);
  r.setFarClip(0.0);
  r.drawList(s.soup(), s.world, second, 0);
  r.end(last);
  EXPECT_EQ(r.counts().triangles, 3000u);
  EXPECT_EQ(differences(midway, firstAlone), 0u);
  EXPECT_EQ(differences(last, both), 0u);
  EXPECT_GT(differences(last, midway), 100u);  // the second half did land
  EXPECT_GT(firstAlone.coveredCount(), 100u);
  EXPECT_THROW(r.read(midway), std::logic_error);  // after end(): no pass set
}

// A triangle leaning away from the camera, from view depth 2 to 10.
Scene leaningTriangle() {
  Scene scene;
  scene.addNode("tri");
  EXPECT_TRUE(scene.nodes[0].mesh.add({-3.0f, -1.0f, -2.0f}, {3.0f, -1.0f, -2.0f},
                                      {0.0f, 4.0f, -10.0f}, kGrey));
  scene.finalize();
  return scene;
}

TEST(TriangleRasterizer, FarClipDrawsOnlyInFrontWithUnchangedDepths) {
  const Scene scene = leaningTriangle();
  const Camera camera = test::lookAtCamera({0.0, 0.0, 0.0}, {0.0, 0.0, -1.0}, 0.5, 50.0, 160, 120);
  TriangleRasterizer r(scene);
  const std::vector<uint32_t> list = {0};
  const glm::dmat4 id(1.0);
  const Framebuffer whole = pass(r, camera, 0.0, [&] { r.drawRange(0, id, 0, 1, 42); });
  for (const double clip : {3.3, 5.0, 6.5}) {
    const Framebuffer ranged = pass(r, camera, clip, [&] { r.drawRange(0, id, 0, 1, 42); });
    const Framebuffer listed = pass(r, camera, clip, [&] { r.drawList(0, id, list, 42); });
    EXPECT_EQ(differences(ranged, listed), 0u);
    size_t kept = 0, dropped = 0;
    for (size_t i = 0; i < whole.size(); ++i) {
      if (whole.covered(i) && double(whole.depth[i]) <= clip) {
        ++kept;
        ASSERT_EQ(ranged.id[i], 42u) << i;
        ASSERT_TRUE(sameBits(ranged.depth[i], whole.depth[i])) << i;
      } else {
        dropped += whole.covered(i);
        ASSERT_EQ(ranged.id[i], kNoId) << i;
        ASSERT_EQ(ranged.depth[i], kEmptyDepth) << i;
      }
    }
    EXPECT_GT(kept, 100u) << clip;
    EXPECT_GT(dropped, 100u) << clip;
  }
  // At or beyond the camera's far plane, farClip changes nothing.
  EXPECT_EQ(differences(whole, pass(r, camera, 50.0, [&] { r.drawRange(0, id, 0, 1, 42); })), 0u);
}

TEST(TriangleRasterizer, ClippedNearPassPlusUnclippedFarPassEqualsOnePass) {
  const SoupScene s(1500, 0.4f);
  const Camera camera = test::lookAtCamera({0.5, 1.0, 0.0}, {0.0, 0.0, -6.0}, 0.5, 30.0, 128, 96);
  const Mesh& mesh = s.scene.nodes[s.soup()].mesh;
  const double plane = 5.3;
  // The far pass: triangles reaching beyond the plane, chosen with a margin because a fragment's
  // float depth may exceed its triangle's largest vertex depth by rounding and vertex snapping.
  std::vector<uint32_t> reaching;
  for (uint32_t t = 0; t < mesh.size(); ++t) {
    double deepest = 0.0;
    for (int k = 0; k < 3; ++k)
      deepest = std::max(
          deepest,
          camera.viewDepth(glm::dvec3(s.world * glm::dvec4(glm::dvec3(mesh.vertex(t, k)), 1.0))));
    if (deepest > plane * (1.0 - 1e-3)) reaching.push_back(t);
  }
  ASSERT_GT(reaching.size(), mesh.size() / 4);
  ASSERT_LT(reaching.size(), 9 * mesh.size() / 10);
  TriangleRasterizer r(s.scene);
  const uint64_t base = 17;
  const Framebuffer single =
      pass(r, camera, 0.0, [&] { r.drawRange(s.soup(), s.world, 0, s.size(), base); });
  // Both passes into one target.
  const Framebuffer shared = pass(r, camera, plane, [&] {
    r.drawRange(s.soup(), s.world, 0, s.size(), base);
    r.setFarClip(0.0);
    r.drawList(s.soup(), s.world, reaching, base);
  });
  EXPECT_EQ(differences(single, shared), 0u);
  // Each pass on its own, then composited.
  Framebuffer composite =
      pass(r, camera, plane, [&] { r.drawRange(s.soup(), s.world, 0, s.size(), base); });
  size_t inFront = 0;
  for (size_t i = 0; i < composite.size(); ++i)
    if (composite.covered(i)) {
      ASSERT_LE(composite.depth[i], plane);
      ++inFront;
    }
  const Framebuffer farPass =
      pass(r, camera, 0.0, [&] { r.drawList(s.soup(), s.world, reaching, base); });
  compositeNearer(composite, farPass);
  EXPECT_EQ(differences(single, composite), 0u);
  // Both passes matter.
  size_t beyond = 0;
  for (size_t i = 0; i < single.size(); ++i) beyond += single.covered(i) && single.depth[i] > plane;
  EXPECT_GT(inFront, single.size() / 10);
  EXPECT_GT(beyond, single.size() / 10);
}

TEST(TriangleRasterizer, FarClipCanChangeBetweenDraws) {
  Scene scene;
  scene.addNode("quads");
  addQuad(scene.nodes[0].mesh, 4.0f, -8.0f);  // triangles 0, 1: big, far
  addQuad(scene.nodes[0].mesh, 0.5f, -4.0f);  // triangles 2, 3: small, near
  scene.finalize();
  const Camera camera = test::lookAtCamera({0.0, 0.0, 0.0}, {0.0, 0.0, -1.0}, 0.1, 100.0, 96, 72);
  const glm::dmat4 id(1.0);
  TriangleRasterizer r(scene);
  const size_t side = size_t(camera.width()) * 3 + size_t(camera.width() / 2);
  const size_t centre =
      size_t(camera.width()) * size_t(camera.height() / 2) + size_t(camera.width() / 2);
  // Clipped at 6: the far quad is dropped, the near one kept.
  Framebuffer fb = pass(r, camera, 6.0, [&] { r.drawRange(0, id, 0, 4, 0); });
  EXPECT_EQ(fb.id[side], kNoId);
  EXPECT_TRUE(fb.id[centre] == 2 || fb.id[centre] == 3);
  // The clip given to begin() lasts until setFarClip; setFarClip(0) lifts it.
  fb = pass(r, camera, 6.0, [&] {
    r.drawRange(0, id, 0, 2, 0);
    r.setFarClip(0.0);
    r.drawRange(0, id, 2, 2, 2);
  });
  EXPECT_EQ(fb.id[side], kNoId);
  fb = pass(r, camera, 6.0, [&] {
    r.setFarClip(0.0);
    r.drawRange(0, id, 0, 2, 0);
    r.setFarClip(3.0);
    r.drawRange(0, id, 2, 2, 2);  // the near quad is beyond 3 now
  });
  EXPECT_TRUE(fb.id[side] == 0 || fb.id[side] == 1);
  EXPECT_TRUE(fb.id[centre] == 0 || fb.id[centre] == 1);
  EXPECT_NEAR(fb.depth[centre], 8.0, 8e-6);
  // A new begin() without a clip draws everything.
  fb = pass(r, camera, 0.0, [&] { r.drawRange(0, id, 0, 4, 0); });
  EXPECT_TRUE(fb.id[side] == 0 || fb.id[side] == 1);
  EXPECT_TRUE(fb.id[centre] == 2 || fb.id[centre] == 3);
}

TEST(TriangleRasterizer, BeginClearsAndResetsCounts) {
  Scene scene;
  scene.addNode("quad");
  addQuad(scene.nodes[0].mesh, 2.0f, -5.0f);
  scene.finalize();
  const Camera camera = test::lookAtCamera({0.0, 0.0, 0.0}, {0.0, 0.0, -1.0}, 0.1, 100.0, 96, 72);
  TriangleRasterizer r(scene);
  EXPECT_NE(r.description().find("Core Profile"), std::string::npos);
  Framebuffer fb = pass(r, camera, 0.0, [&] { r.drawRange(0, glm::dmat4(1.0), 0, 2, 0); });
  EXPECT_GT(fb.coveredCount(), fb.size() / 4);
  EXPECT_EQ(r.counts().triangles, 2u);
  EXPECT_EQ(r.counts().drawCalls, 1u);
  EXPECT_GT(r.counts().uploadSeconds, 0.0);
  fb = pass(r, camera, 0.0, [] {});
  EXPECT_EQ(fb.coveredCount(), 0u);
  for (const float d : fb.depth) ASSERT_EQ(d, kEmptyDepth);
  EXPECT_EQ(r.counts().triangles, 0u);
  EXPECT_EQ(r.counts().drawCalls, 0u);
  // Uploaded once: a later pass set pays nothing.
  const std::vector<uint32_t> list = {1};
  fb = pass(r, camera, 0.0, [&] { r.drawList(0, glm::dmat4(1.0), list, 0); });
  EXPECT_EQ(r.counts().uploadSeconds, 0.0);
  EXPECT_EQ(r.counts().triangles, 1u);
  EXPECT_GT(fb.coveredCount(), fb.size() / 8);
  // end() sizes a framebuffer of another size to the camera.
  Framebuffer small(3, 2);
  r.begin(camera);
  r.end(small);
  EXPECT_EQ(small.width, camera.width());
  EXPECT_EQ(small.height, camera.height());
  EXPECT_EQ(small.coveredCount(), 0u);
}

TEST(TriangleRasterizer, TwoRasterizersInterleaveInOneThread) {
  Scene scene;
  scene.addNode("quads");
  addQuad(scene.nodes[0].mesh, 2.0f, -5.0f);
  addQuad(scene.nodes[0].mesh, 0.5f, -4.0f);
  scene.finalize();
  const Camera camera = test::lookAtCamera({0.0, 0.0, 0.0}, {0.0, 0.0, -1.0}, 0.1, 100.0, 96, 72);
  const glm::dmat4 id(1.0);
  TriangleRasterizer a(scene), b(scene);
  const Framebuffer bigAlone = pass(a, camera, 0.0, [&] { a.drawRange(0, id, 0, 2, 0); });
  const Framebuffer smallAlone = pass(b, camera, 0.0, [&] { b.drawRange(0, id, 2, 2, 2); });
  Framebuffer big, small;
  a.begin(camera);
  b.begin(camera);
  a.drawRange(0, id, 0, 2, 0);
  b.drawRange(0, id, 2, 2, 2);
  a.end(big);
  b.end(small);
  EXPECT_EQ(differences(big, bigAlone), 0u);
  EXPECT_EQ(differences(small, smallAlone), 0u);
  EXPECT_GT(big.coveredCount(), small.coveredCount());
}

TEST(TriangleRasterizer, RejectsMisuse) {
  Scene scene;
  scene.addNode("quad");
  addQuad(scene.nodes[0].mesh, 2.0f, -5.0f);
  scene.finalize();
  const Camera camera = test::lookAtCamera({0.0, 0.0, 0.0}, {0.0, 0.0, -1.0}, 0.1, 100.0, 96, 72);
  const glm::dmat4 id(1.0);
  TriangleRasterizer r(scene);
  Framebuffer fb;
  EXPECT_THROW(r.drawRange(0, id, 0, 2, 0), std::logic_error);
  EXPECT_THROW(r.end(fb), std::logic_error);
  EXPECT_THROW(r.begin(camera, -1.0), std::invalid_argument);
  EXPECT_THROW(r.setFarClip(1.0), std::logic_error);  // that begin() did not start a pass set
  r.begin(camera);
  EXPECT_THROW(r.setFarClip(std::nan("")), std::invalid_argument);
  EXPECT_THROW(r.drawRange(0, id, 1, 2, 0), std::out_of_range);
  EXPECT_THROW(r.drawRange(1, id, 0, 1, 0), std::out_of_range);
  const std::vector<uint32_t> bad = {0, 2};
  EXPECT_THROW(r.drawList(0, id, bad, 0), std::out_of_range);
  r.end(fb);
  EXPECT_EQ(fb.coveredCount(), 0u);  // nothing of the rejected list was drawn
  EXPECT_THROW(r.end(fb), std::logic_error);
}

// A mesh over one vertex-buffer chunk, drawn by a list of millions in an order that alternates
// between the chunks: the same image as one range draw.
TEST(TriangleRasterizer, ListOfMillionsAcrossBufferChunks) {
  const size_t n = gl::MeshBuffers::kChunkTriangles + 300'000;
  const SoupScene s(n, 0.02f);
  const Camera camera = test::lookAtCamera({0.5, 1.0, 0.0}, {0.0, 0.0, -6.0}, 0.5, 30.0, 160, 120);
  TriangleRasterizer r(s.scene);
  const Framebuffer range = pass(r, camera, 0.0, [&] { r.drawRange(s.soup(), s.world, 0, n, 0); });
  EXPECT_EQ(r.counts().drawCalls, 2u);
  // Reversed: the second chunk's triangles first; the chunked draw takes them in chunk order.
  std::vector<uint32_t> list = iota(n);
  std::reverse(list.begin(), list.end());
  const Framebuffer listed = pass(r, camera, 0.0, [&] { r.drawList(s.soup(), s.world, list, 0); });
  EXPECT_EQ(r.counts().triangles, n);
  EXPECT_EQ(r.counts().drawCalls, 5u);  // 4 + 1 batches of ListIndices::kBatchTriangles
  EXPECT_EQ(differences(range, listed), 0u);
  size_t secondChunk = 0;
  for (const uint64_t id : listed.id)
    secondChunk += id != kNoId && id >= gl::MeshBuffers::kChunkTriangles;
  EXPECT_GT(secondChunk, 50u);
  EXPECT_GT(listed.coveredCount(), listed.size() / 2);
}

}  // namespace
}  // namespace lzb
