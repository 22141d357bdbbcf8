#pragma once
// Two shares of a scene under --distribute data compared as a renderer sees them, triangle by
// triangle in world space (src/regions: the streamed, the slice-read and the loaded-and-cut
// share must be one). Inline: only the tests of src/regions link its library.
#include <gtest/gtest.h>

#include "src/core/scene_outline.hpp"
#include "src/regions/share.hpp"

namespace lzb::test {

inline void expectSameOutline(const SceneOutline& a, const SceneOutline& b) {
  EXPECT_EQ(a.source, b.source);
  EXPECT_EQ(a.bounds.lo, b.bounds.lo);
  EXPECT_EQ(a.bounds.hi, b.bounds.hi);
  EXPECT_EQ(a.uniqueTriangles, b.uniqueTriangles);
  EXPECT_EQ(a.expandedTriangles, b.expandedTriangles);
  EXPECT_EQ(a.nodes, b.nodes);
  EXPECT_EQ(a.instanceDepth, b.instanceDepth);
  EXPECT_EQ(a.stats.loaded, b.stats.loaded);
  EXPECT_EQ(a.stats.degenerate, b.stats.degenerate);
  EXPECT_EQ(a.camera.has_value(), b.camera.has_value());
}

// Everything a renderer of the part sees, triangle by triangle, in world space.
inline void expectSamePart(const regions::ScenePart& streamed, const regions::ScenePart& cut) {
  const Scene &s = streamed.scene, &c = cut.scene;
  ASSERT_EQ(s.expandedTriangles(), c.expandedTriangles());
  EXPECT_EQ(streamed.units, cut.units);
  if (s.expandedTriangles() == 0) return;
  EXPECT_EQ(s.bounds().lo, c.bounds().lo);
  EXPECT_EQ(s.bounds().hi, c.bounds().hi);
  for (uint64_t id = 0; id < s.expandedTriangles(); ++id) {
    ASSERT_EQ(streamed.ids.global(id), cut.ids.global(id)) << id;
    const auto a = s.resolve(id), b = c.resolve(id);
    ASSERT_TRUE(a && b);
    EXPECT_EQ(a->transform, b->transform) << id;
    EXPECT_EQ(s.nodeBounds[a->node].lo, c.nodeBounds[b->node].lo) << id;
    EXPECT_EQ(s.nodeBounds[a->node].hi, c.nodeBounds[b->node].hi) << id;
    const Mesh &ma = s.nodes[a->node].mesh, &mb = c.nodes[b->node].mesh;
    for (int k = 0; k < 3; ++k) EXPECT_EQ(ma.vertex(a->triangle, k), mb.vertex(b->triangle, k));
    EXPECT_EQ(ma.normal(a->triangle), mb.normal(b->triangle));
    EXPECT_EQ(ma.color(a->triangle), mb.color(b->triangle));
  }
}

inline void expectSameShare(const regions::HeldShare& a, const regions::HeldShare& cut,
                            regions::Parts layout) {
  EXPECT_EQ(a.regions, cut.regions);
  EXPECT_EQ(a.units, cut.units);
  EXPECT_EQ(a.mine, cut.mine);
  EXPECT_EQ(a.triangles, cut.triangles);
  ASSERT_EQ(a.parts.size(), cut.parts.size());
  EXPECT_EQ(cut.parts.size(), layout == regions::Parts::kOne ? 1u : cut.mine.size());
  for (size_t p = 0; p < cut.parts.size(); ++p) expectSamePart(a.parts[p], cut.parts[p]);
}

}  // namespace lzb::test
