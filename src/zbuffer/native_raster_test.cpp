#include "src/zbuffer/native_raster.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <random>

#include "src/zbuffer/triangle_rasterizer.hpp"

namespace lzb {
namespace {

// Pixels rasterizeTriangle writes for one triangle into an empty image (open everywhere).
std::vector<uint8_t> coverage(const ScreenVertex (&v)[3], int w, int h) {
  std::vector<uint8_t> c(size_t(w) * size_t(h), 0);
  RasterTriangle t;
  if (!setupTriangle(v, 7, w, h, t)) return c;
  Framebuffer fb(w, h);
  rasterizeTriangle(t, 0, h, nullptr, 1e30, fb);
  for (size_t i = 0; i < c.size(); ++i) c[i] = fb.id[i] == 7;
  return c;
}

// A jittered grid of vertices, some exactly on pixel centres and on pixel-centre rows and
// columns, split into triangles with random diagonals and random windings: every pixel centre
// strictly inside the grid's outline is covered by exactly one triangle, none outside by any.
TEST(NativeRaster, SharedEdgesCoverEveryPixelCentreExactlyOnce) {
  const int w = 64, h = 48, n = 9;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-1.5, 1.5);
  std::vector<ScreenVertex> grid(size_t(n * n));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      ScreenVertex& v = grid[size_t(j * n + i)];
      // Border vertices stay on the outline x, y in {4.25, 60.25} / {3.75, 43.75}.
      v.x = 4.25 + 7.0 * i + (i > 0 && i < n - 1 ? jitter(rng) : 0.0);
      v.y = 3.75 + 5.0 * j + (j > 0 && j < n - 1 ? jitter(rng) : 0.0);
      if ((i + j) % 3 == 0 && i > 0 && i < n - 1 && j > 0 && j < n - 1) {
        v.x = std::floor(v.x) + 0.5;  // on a pixel centre: its edges pass through centres
        v.y = std::floor(v.y) + 0.5;
      }
      v.depth = 2.0 + 0.1 * i;
    }
  // Vertical and horizontal edges through pixel centres.
  for (int j = 1; j < n - 1; ++j) grid[size_t(j * n + 4)].x = 32.5;
  for (int i = 1; i < n - 1; ++i) grid[size_t(4 * n + i)].y = 23.5;
  std::vector<int> count(size_t(w * h), 0);
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const ScreenVertex a = grid[size_t(j * n + i)], b = grid[size_t(j * n + i + 1)],
                         c = grid[size_t((j + 1) * n + i)], d = grid[size_t((j + 1) * n + i + 1)];
      const bool diag = rng() & 1;
      ScreenVertex t1[3] = {a, b, diag ? d : c};
      ScreenVertex t2[3] = {diag ? a : b, d, c};
      if (rng() & 1) std::swap(t1[1], t1[2]);
      if (rng() & 1) std::swap(t2[0], t2[1]);
      for (const auto* t : {&t1, &t2}) {
        const std::vector<uint8_t> c1 = coverage(*t, w, h);
        for (size_t p = 0; p < c1.size(); ++p) count[p] += c1[p];
      }
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double cx = x + 0.5, cy = y + 0.5;
      const bool inside = cx > 4.25 && cx < 60.25 && cy > 3.75 && cy < 43.75;
      EXPECT_EQ(count[size_t(y * w + x)], inside ? 1 : 0) << x << " " << y;
    }
}

TEST(NativeRaster, TieRuleAtPixelCentres) {
  // A 4 x 2 rectangle whose edges lie exactly on pixel centres: left and bottom edges are in,
  // right and top out (OSMesa's rule, below), whichever diagonal and winding.
  const ScreenVertex a{2.5, 1.5, 1.0}, b{6.5, 1.5, 1.0}, c{6.5, 3.5, 1.0}, d{2.5, 3.5, 1.0};
  for (int diagonal = 0; diagonal < 2; ++diagonal) {
    const ScreenVertex t1[3] = {a, diagonal ? c : d, b}, t2[3] = {diagonal ? a : b, d, c};
    std::vector<uint8_t> c1 = coverage(t1, 10, 6), c2 = coverage(t2, 10, 6);
    for (int y = 0; y < 6; ++y)
      for (int x = 0; x < 10; ++x) {
        const size_t i = size_t(y * 10 + x);
        EXPECT_EQ(c1[i] + c2[i], x >= 2 && x < 6 && y >= 2 && y <= 3 ? 1 : 0) << x << " " << y;
      }
  }
}

TEST(NativeRaster, InterpolatesViewDepthPerspectiveCorrectly) {
  // A plane tilted in depth: 1/depth is affine on screen, depth is not.
  const ScreenVertex v[3] = {{0.0, 0.0, 1.0}, {40.0, 0.0, 4.0}, {0.0, 40.0, 1.0}};
  RasterTriangle t;
  ASSERT_TRUE(setupTriangle(v, 3, 40, 40, t));
  Framebuffer fb(40, 40);
  EXPECT_GT(rasterizeTriangle(t, 0, 40, nullptr, 100.0, fb), 0u);
  const size_t i = fb.index(19, 5);  // x = 19.5: 1/depth = 1 + (1/4 - 1) * 19.5 / 40
  EXPECT_NEAR(fb.depth[i], 1.0 / (1.0 - 0.75 * 19.5 / 40.0), 1e-5);
  EXPECT_EQ(fb.id[i], 3u);
  // Nearer wins, equal depth: the smaller ID; the far limit drops fragments.
  RasterTriangle u = t;
  u.id = 2;
  rasterizeTriangle(u, 0, 40, nullptr, 100.0, fb);
  EXPECT_EQ(fb.id[i], 2u);
  u.id = 9;
  rasterizeTriangle(u, 0, 40, nullptr, 100.0, fb);
  EXPECT_EQ(fb.id[i], 2u);
  Framebuffer farCut(40, 40);
  rasterizeTriangle(t, 0, 40, nullptr, 1.5, farCut);
  EXPECT_EQ(farCut.id[farCut.index(2, 5)], 3u);  // depth ~1.06
  EXPECT_EQ(farCut.id[i], kNoId);                // depth ~1.95
  // Closed pixels and rows outside the band stay untouched.
  std::vector<uint8_t> open(fb.size(), 1);
  open[fb.index(3, 3)] = 0;
  Framebuffer masked(40, 40);
  rasterizeTriangle(t, 2, 10, open.data(), 100.0, masked);
  EXPECT_EQ(masked.id[masked.index(3, 3)], kNoId);
  EXPECT_EQ(masked.id[masked.index(3, 4)], 3u);
  EXPECT_EQ(masked.id[masked.index(3, 1)], kNoId);
  EXPECT_EQ(masked.id[masked.index(3, 10)], kNoId);
}

// A scene of one triangle and the camera: the native PVL image and OSMesa's of the whole mesh.
struct OneMesh {
  Scene scene;
  explicit OneMesh(const std::vector<std::array<glm::vec3, 3>>& tris) {
    const uint32_t n = scene.addNode("tris");
    scene.root = n;
    for (const auto& t : tris) scene.nodes[n].mesh.add(t[0], t[1], t[2], packRgba8(200, 200, 200));
    scene.finalize();
  }
  DrawLists lists(const glm::dmat4& world = glm::dmat4(1.0)) const {
    DrawLists l;
    DrawList d;
    d.node = 0;
    d.world = world;
    d.idBase = 100;
    for (uint32_t t = 0; t < scene.nodes[0].mesh.size(); ++t) d.triangles.push_back(t);
    l.triangles = d.triangles.size();
    l.lists.push_back(std::move(d));
    return l;
  }
};

Camera lookDownZ(const glm::dvec3& eye, int w, int h) {
  CameraSpec spec;
  spec.position = eye;
  spec.lookAt = eye + glm::dvec3(0.0, 0.0, -1.0);
  spec.fovyDegrees = 60.0;
  spec.nearPlane = 1.0;
  spec.farPlane = 100.0;
  return Camera(spec, w, h);
}

// The exact view depth at pixel centre i of the triangle with expanded ID id (ray-plane, double).
double exactDepth(const OneMesh& m, const Camera& cam, const glm::dmat4& world, uint64_t id,
                  size_t i) {
  const Mesh& mesh = m.scene.nodes[0].mesh;
  glm::dvec3 p[3];
  for (int k = 0; k < 3; ++k)
    p[k] = glm::dvec3(world * glm::dvec4(glm::dvec3(mesh.vertex(size_t(id - 100), k)), 1.0));
  const glm::dvec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
  const glm::dvec3 dir = cam.pixelDirection(double(i % size_t(cam.width())) + 0.5,
                                            double(i / size_t(cam.width())) + 0.5);
  return glm::dot(n, p[0] - cam.position()) / glm::dot(n, dir);
}

// Native and OSMesa images of the same lists: IDs equal on all but `slack` pixels; native depths
// within 1e-5 of the exact ones, OSMesa's within 1e-3 (float arithmetic throughout).
void expectSameAsGl(const OneMesh& m, const Camera& cam, const glm::dmat4& world, int threads,
                    long slack, long* covered = nullptr) {
  TriangleRasterizer gl(m.scene);
  Framebuffer ref;
  gl.begin(cam);
  for (const DrawList& l : m.lists(world).lists)
    gl.drawList(l.node, l.world, l.triangles, l.idBase);
  gl.end(ref);
  Framebuffer img(cam.width(), cam.height());
  NativeRasterizer native;
  native.draw(m.scene, cam, m.lists(world), {}, threads, img);
  long differ = 0, n = 0;
  for (size_t i = 0; i < img.size(); ++i) {
    n += img.id[i] != kNoId;
    if (img.id[i] != ref.id[i]) {
      ++differ;
    } else if (img.id[i] != kNoId) {
      const double exact = exactDepth(m, cam, world, img.id[i], i);
      EXPECT_NEAR(img.depth[i], exact, 1e-5 * exact) << i;
      EXPECT_NEAR(ref.depth[i], exact, 1e-3 * exact) << i;
    }
  }
  EXPECT_LE(differ, slack);
  if (covered) *covered = n;
}

TEST(NativeRaster, ClipsATriangleCrossingTheNearPlaneLikeOsMesa) {
  // One vertex behind the camera, one between the eye and the near plane, one in front; and a
  // triangle wholly behind the camera (drawn nowhere).
  const OneMesh m(
      {{glm::vec3(-3.0f, -2.0f, 4.0f), glm::vec3(0.5f, -1.0f, -0.5f),
        glm::vec3(1.0f, 2.0f, -12.0f)},
       {glm::vec3(-1.0f, -1.0f, 2.0f), glm::vec3(1.0f, -1.0f, 2.0f), glm::vec3(0.0f, 1.0f, 3.0f)}});
  const Camera cam = lookDownZ(glm::dvec3(0.0), 96, 72);
  long covered = 0;
  expectSameAsGl(m, cam, glm::dmat4(1.0), 2, 10, &covered);
  EXPECT_GT(covered, 500);
  NativeRasterizer native;
  Framebuffer img(96, 72);
  native.draw(m.scene, cam, m.lists(), {}, 1, img);
  EXPECT_EQ(native.counts().clipped, 1u);
  for (uint64_t id : img.id) EXPECT_NE(id, 101u);  // the one behind the camera
  // Every drawn depth is at or beyond the near plane.
  for (float d : img.depth) EXPECT_GE(d, 1.0f);
}

TEST(NativeRaster, ClipsHugeTrianglesAtTheGuardBandLikeOsMesa) {
  // Vertices ~13 K pixels off screen (beyond the guard band), through a translated instance
  // transform far from the origin (camera-relative arithmetic keeps the precision).
  const OneMesh m({{glm::vec3(-5000.0f, -3000.0f, -20.0f), glm::vec3(4000.0f, -10.0f, -5.0f),
                    glm::vec3(-2.0f, 6000.0f, -30.0f)}});
  const glm::dvec3 far(3.0e6, -2.0e6, 1.0e6);
  const Camera cam = lookDownZ(far, 80, 60);
  long covered = 0;
  expectSameAsGl(m, cam, glm::translate(glm::dmat4(1.0), far), 2, 10, &covered);
  EXPECT_EQ(covered, 80 * 60);
}

TEST(NativeRaster, OwnsEdgesThroughPixelCentresLikeOsMesa) {
  // Seen from the origin along -z with a 90 degree field on 64 x 64 pixels, z = -32 maps x, y
  // to pixel (32 + x, 32 - y) exactly: rectangles and diagonals through pixel centres, every
  // pixel's owner the same as OSMesa's.
  const float z = -32.0f;
  auto at = [z](double px, double py) { return glm::vec3(float(px - 32.0), float(32.0 - py), z); };
  std::vector<std::array<glm::vec3, 3>> tris;
  for (int k = 0; k < 4; ++k) {
    const double x0 = 2.5 + 14.0 * k, y0 = 1.5 + 3.0 * k, x1 = x0 + 4.0 + k, y1 = y0 + 2.0 + 3 * k;
    const glm::vec3 a = at(x0, y0), b = at(x1, y0), c = at(x1, y1), d = at(x0, y1);
    if (k % 2) {
      tris.push_back({a, c, b});
      tris.push_back({a, d, c});
    } else {
      tris.push_back({a, b, d});
      tris.push_back({b, c, d});
    }
  }
  tris.push_back({at(10.5, 40.5), at(30.5, 40.5), at(20.5, 60.5)});  // slopes through centres
  tris.push_back({at(30.5, 40.5), at(20.5, 60.5), at(40.5, 60.5)});
  const OneMesh m(tris);
  CameraSpec spec;
  spec.position = glm::dvec3(0.0);
  spec.lookAt = glm::dvec3(0.0, 0.0, -1.0);
  spec.fovyDegrees = 90.0;
  spec.nearPlane = 1.0;
  spec.farPlane = 100.0;
  long covered = 0;
  expectSameAsGl(m, Camera(spec, 64, 64), glm::dmat4(1.0), 2, 0, &covered);
  EXPECT_GT(covered, 300);
}

TEST(NativeRaster, SameImageForAnyThreadCountAndOrder) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-4.0f, 4.0f), z(-30.0f, -2.0f);
  std::vector<std::array<glm::vec3, 3>> tris;
  for (int i = 0; i < 400; ++i) {
    const glm::vec3 c(u(rng), u(rng), z(rng));
    tris.push_back({c, c + glm::vec3(u(rng), u(rng), u(rng)) * 0.3f,
                    c + glm::vec3(u(rng), u(rng), u(rng)) * 0.3f});
  }
  const OneMesh m(tris);
  const Camera cam = lookDownZ(glm::dvec3(0.0), 70, 50);
  Framebuffer one(70, 50), three(70, 50);
  NativeRasterizer r;
  r.draw(m.scene, cam, m.lists(), {}, 1, one);
  r.draw(m.scene, cam, m.lists(), {}, 3, three);
  EXPECT_EQ(one.id, three.id);
  EXPECT_EQ(one.depth, three.depth);
  // Two halves of the list drawn separately and composited: the same image.
  DrawLists all = m.lists(), a = all, b = all;
  const auto& t = all.lists[0].triangles;
  a.lists[0].triangles.assign(t.begin(), t.begin() + 200);
  b.lists[0].triangles.assign(t.begin() + 200, t.end());
  Framebuffer fa(70, 50), fbb(70, 50);
  r.draw(m.scene, cam, a, {}, 2, fa);
  r.draw(m.scene, cam, b, {}, 2, fbb);
  compositeNearer(fa, fbb);
  EXPECT_EQ(fa.id, one.id);
  EXPECT_EQ(fa.depth, one.depth);
  // Three ranks' contiguous parts of two lists (the cuts fall inside lists), composited.
  DrawLists two = all;
  two.lists = {a.lists[0], b.lists[0]};
  Framebuffer parts(70, 50);
  uint64_t drawn = 0;
  for (int rank = 0; rank < 3; ++rank) {
    Framebuffer part(70, 50);
    r.draw(m.scene, cam, two, {}, 2, part, 0.0, shareRange(400, WorkShare{rank, 3}));
    drawn += r.counts().triangles;
    EXPECT_LT(r.counts().triangles, 400u);
    compositeNearer(parts, part);
  }
  EXPECT_EQ(drawn, 400u);
  EXPECT_EQ(parts.id, one.id);
  EXPECT_EQ(parts.depth, one.depth);
  expectSameAsGl(m, cam, glm::dmat4(1.0), 2, 70 * 50 / 1000);
}

// The pixels and depths rasterizeTriangle writes, against a direct evaluation of every pixel of
// the box (exact edge functions with the tie rule, the same depth formula), on many overlapping
// triangles of every size with vertices often on the subpixel grid and on pixel centres (ties),
// some flat at equal depths, drawn in bands at open pixels only: the row spans and the early
// depth reject change nothing.
TEST(NativeRaster, RowSpansAndEarlyRejectMatchAPerPixelReference) {
  const int w = 97, h = 61;
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> pos(-20.0, 110.0), size(0.0, 1.0), depth(1.0, 50.0);
  std::uniform_int_distribution<int> kind(0, 3);
  std::vector<uint8_t> open(size_t(w) * size_t(h));
  for (auto& o : open) o = rng() % 5 != 0;
  Framebuffer fb(w, h), ref(w, h);
  for (int n = 0; n < 3000; ++n) {
    ScreenVertex v[3];
    const double cx = pos(rng), cy = pos(rng), r = std::pow(size(rng), 3.0) * 80.0;
    // A third are flat at one of two depths: equal depths, decided by the IDs.
    const double flat = rng() % 3 == 0 ? 4.0 * double(1 + rng() % 2) : 0.0;
    for (auto& p : v) {
      p = {cx + r * (size(rng) - 0.5), cy + r * (size(rng) - 0.5), flat > 0 ? flat : depth(rng)};
      const int k = kind(rng);
      if (k == 0) {  // on a pixel centre
        p.x = std::floor(p.x) + 0.5;
        p.y = std::floor(p.y) + 0.5;
      } else if (k == 1) {  // on the subpixel grid
        p.x = std::round(p.x * 256.0) / 256.0;
        p.y = std::round(p.y * 256.0) / 256.0;
      }
    }
    RasterTriangle t;
    if (!setupTriangle(v, uint64_t(rng() % 50), w, h, t)) continue;
    const double far = n % 7 == 0 ? 20.0 : 1e30;
    for (int b = 0; b < h; b += 16) rasterizeTriangle(t, b, b + 16, open.data(), far, fb);
    for (int y = t.y0; y < t.y1; ++y)
      for (int x = t.x0; x < t.x1; ++x) {
        bool inside = true;
        for (int k = 0; k < 3; ++k) {
          const int a = (k + 1) % 3, c = (k + 2) % 3;
          const int64_t dx = int64_t(t.x[c]) - t.x[a], dy = int64_t(t.y[c]) - t.y[a];
          const int64_t e =
              dx * (int64_t(y) * 256 + 128 - t.y[a]) - dy * (int64_t(x) * 256 + 128 - t.x[a]);
          inside = inside && (e > 0 || (e == 0 && (dy < 0 || (dy == 0 && dx < 0))));
        }
        const size_t i = ref.index(x, y);
        if (!inside || !open[i]) continue;
        const double d = 1.0 / std::clamp(t.a * (x + 0.5) + (t.b * (y + 0.5) + t.c), t.invDepthMin,
                                          t.invDepthMax);
        if (d <= far) ref.keepNearer(i, float(d), Rgba8{}, t.id);
      }
  }
  EXPECT_EQ(fb.id, ref.id);
  EXPECT_EQ(fb.depth, ref.depth);
}

}  // namespace
}  // namespace lzb
