// The fallback drawn by the native z-buffer against OSMesa (--fallback-render gl): the same
// triangles at the same pixels, except where an edge passes within rounding of a pixel centre or
// two triangles lie within OSMesa's float depth error of each other; and the frames composited
// with the point pass differ only there and where a sample lies between the two fallback depths.
#include "src/rzb/fallback_pass.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "src/image/metrics.hpp"
#include "src/rzb/rzb_renderer.hpp"
#include "src/scene/load.hpp"
#include "src/zbuffer/zbuffer_renderer.hpp"
#include "tests/support/cameras.hpp"
#include "tests/support/meshes.hpp"
#include "tests/support/options.hpp"

namespace lzb::rzb {
namespace {

// Both rasterizers snap vertices to 1/256 pixel (OSMesa from float coordinates): a pixel centre
// whose coverage differs lies within about two subpixels of the exact edge.
constexpr double kEdgePixels = 2.0 / 256.0;
// OSMesa interpolates depth in float (its depths are within 1e-4 of the exact ones on these
// scenes, src/zbuffer/native_raster_test.cpp allows 1e-3): two triangles closer than this may
// swap order.
constexpr double kDepthRelative = 1e-4;

// The screen pieces of expanded triangle id (clipped at the near plane and the guard band as the
// native z-buffer clips it).
std::vector<std::array<ScreenVertex, 3>> screenPieces(const Scene& scene, const Camera& camera,
                                                      uint64_t id) {
  const auto ref = scene.resolve(id);
  EXPECT_TRUE(ref.has_value()) << id;
  std::vector<std::array<ScreenVertex, 3>> pieces;
  if (!ref) return pieces;
  const glm::dmat3 toView =
      glm::transpose(glm::dmat3(camera.right(), camera.up(), camera.forward()));
  glm::dvec3 view[3];
  for (int k = 0; k < 3; ++k) {
    const glm::dvec3 v(scene.nodes[ref->node].mesh.vertex(ref->triangle, k));
    view[k] = toView * (glm::dvec3(ref->transform * glm::dvec4(v, 1.0)) - camera.position());
  }
  clipAndProject(view, camera.nearPlane(), camera.pixelsPerUnitAt(1.0), camera.width(),
                 camera.height(), pieces);
  return pieces;
}

// Distance in pixels from (x, y) to the nearest edge of id's screen pieces (+inf: none).
double edgeDistance(const Scene& scene, const Camera& camera, uint64_t id, double x, double y) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& p : screenPieces(scene, camera, id))
    for (int k = 0; k < 3; ++k) {
      const ScreenVertex &a = p[size_t(k)], &b = p[size_t((k + 1) % 3)];
      const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
      const double t = len2 > 0 ? std::clamp(((x - a.x) * dx + (y - a.y) * dy) / len2, 0.0, 1.0) : 0;
      best = std::min(best, std::hypot(a.x + t * dx - x, a.y + t * dy - y));
    }
  return best;
}

// The exact view depth of id's plane at the centre of pixel (x, y).
double exactDepth(const Scene& scene, const Camera& camera, uint64_t id, int x, int y) {
  const auto ref = scene.resolve(id);
  glm::dvec3 p[3];
  for (int k = 0; k < 3; ++k)
    p[k] = glm::dvec3(ref->transform *
                      glm::dvec4(glm::dvec3(scene.nodes[ref->node].mesh.vertex(ref->triangle, k)), 1.0));
  const glm::dvec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
  const glm::dvec3 dir = camera.pixelDirection(x + 0.5, y + 0.5);
  return glm::dot(n, p[0] - camera.position()) / glm::dot(n, dir);
}

struct Diff {
  long covered = 0;    // pixels either fallback covers
  long differ = 0;     // pixels whose IDs differ
  long edge = 0;       // of those: a pixel centre within kEdgePixels of either triangle's edge
  long depth = 0;      // of the rest: both triangles there, within kDepthRelative in depth
  long unexplained = 0;
  // Largest relative depth errors where the IDs agree, away from the triangle's edges.
  double nativeDepthError = 0.0, glDepthError = 0.0;
};

Diff compareFallbacks(const Scene& scene, const Camera& camera, const Framebuffer& native,
                      const Framebuffer& gl) {
  Diff d;
  for (int y = 0; y < camera.height(); ++y)
    for (int x = 0; x < camera.width(); ++x) {
      const size_t i = native.index(x, y);
      const uint64_t a = native.id[i], b = gl.id[i];
      d.covered += a != kNoId || b != kNoId;
      if (a == b) {
        // Away from its edges (where snapping decides and the plane extrapolates), the native
        // depth is the exact one rounded to float.
        if (a != kNoId && edgeDistance(scene, camera, a, x + 0.5, y + 0.5) > kEdgePixels) {
          const double exact = exactDepth(scene, camera, a, x, y);
          d.nativeDepthError = std::max(d.nativeDepthError, std::abs(native.depth[i] - exact) / exact);
          d.glDepthError = std::max(d.glDepthError, std::abs(gl.depth[i] - exact) / exact);
        }
        continue;
      }
      ++d.differ;
      const double cx = x + 0.5, cy = y + 0.5;
      const bool nearEdge = (a != kNoId && edgeDistance(scene, camera, a, cx, cy) <= kEdgePixels) ||
                            (b != kNoId && edgeDistance(scene, camera, b, cx, cy) <= kEdgePixels);
      if (nearEdge) {
        ++d.edge;
        continue;
      }
      if (a != kNoId && b != kNoId) {
        const double da = exactDepth(scene, camera, a, x, y), db = exactDepth(scene, camera, b, x, y);
        if (std::abs(da - db) <= kDepthRelative * std::max(da, db)) {
          ++d.depth;
          continue;
        }
      }
      ++d.unexplained;
      ADD_FAILURE() << "pixel " << x << " " << y << ": native " << a << ", gl " << b;
    }
  return d;
}

// One frame's stages on a renderer, up to the splat (the fallback in f.raster, the samples in the
// key buffer); resolve() then composites them.
void runStages(RzbRenderer& r, RzbRenderer::Frame& f) {
  r.select(f);
  r.deal(f);
  r.drawFallback(f);
  r.prepareFreshSamples(f);
  r.splat(f);
}

// Whether key k lies between a and b (inclusive) in the (depth, id) order.
bool between(float kd, uint64_t kid, float ad, uint64_t aid, float bd, uint64_t bid) {
  if (nearer(bd, bid, ad, aid)) {
    std::swap(ad, bd);
    std::swap(aid, bid);
  }
  return !nearer(kd, kid, ad, aid) && !nearer(bd, bid, kd, kid);
}

// The defaults with the native and with the OSMesa fallback on one view.
void expectNativeMatchesGl(const Scene& scene, const Camera& camera, const std::string& name,
                           double maxDifferRate) {
  RzbParams native, gl;
  gl.fallbackRender = FallbackRender::kGl;
  RzbRenderer rn(scene, test::renderOptions("rzb", 2, 7), native),
      rg(scene, test::renderOptions("rzb", 2, 7), gl);
  RzbRenderer::Frame fn(camera, 0, {}, 7), fg(camera, 0, {}, 7);
  runStages(rn, fn);
  runStages(rg, fg);
  ASSERT_TRUE(fn.rastered && fg.rastered) << name;
  ASSERT_EQ(fn.fallback.triangles, fg.fallback.triangles);
  const Diff d = compareFallbacks(scene, camera, fn.raster, fg.raster);
  // The frames: points composited with each fallback.
  Framebuffer points(camera.width(), camera.height()), frameN, frameG;
  fn.rastered = false;
  rn.resolve(fn, points);
  frameN = points;
  compositeNearer(frameN, fn.raster);
  frameG = points;
  compositeNearer(frameG, fg.raster);
  long frameDiffer = 0, bracketed = 0, other = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    if (frameN.id[i] == frameG.id[i]) continue;
    ++frameDiffer;
    if (fn.raster.id[i] != fg.raster.id[i]) continue;
    if (between(points.depth[i], points.id[i], fn.raster.depth[i], fn.raster.id[i],
                fg.raster.depth[i], fg.raster.id[i]))
      ++bracketed;
    else
      ++other;
  }
  std::printf("[ fallback ] %s %dx%d: %llu fallback triangles, %ld covered pixels, %ld differ "
              "(%ld at an edge, %ld at equal depths); depth error native %.2g, gl %.2g; frames "
              "differ at %ld pixels (%ld where a sample lies between the two fallback depths)\n",
              name.c_str(), camera.width(), camera.height(),
              (unsigned long long)fn.fallback.triangles, d.covered, d.differ, d.edge, d.depth,
              d.nativeDepthError, d.glDepthError, frameDiffer, bracketed);
  EXPECT_GT(d.covered, long(points.size()) / 20) << name;
  EXPECT_EQ(d.unexplained, 0) << name;
  EXPECT_LE(double(d.differ), maxDifferRate * double(d.covered)) << name;
  EXPECT_LE(d.nativeDepthError, 1e-6) << name;
  EXPECT_EQ(other, 0) << name;
  EXPECT_LE(double(frameDiffer - d.differ), maxDifferRate * double(d.covered)) << name;
}

TEST(RzbFallback, DrawListsAreAscendingOnceDenseOrSparse) {
  std::mt19937 rng(3);
  // Dense lists (the bitmap) and sparse ones (the sort), with repeats and the mesh's last index.
  for (const auto& [meshSize, count] : {std::pair{1000u, 3000u}, std::pair{1000u, 70u},
                                        std::pair{1u << 20, 100u}, std::pair{64u, 64u}}) {
    std::vector<uint32_t> list(count);
    for (uint32_t& t : list) t = rng() % meshSize;
    list.back() = meshSize - 1;
    std::vector<uint32_t> expected = list;
    std::sort(expected.begin(), expected.end());
    expected.erase(std::unique(expected.begin(), expected.end()), expected.end());
    ascendingOnce(list, meshSize);
    EXPECT_EQ(list, expected) << meshSize << " " << count;
  }
}

TEST(RzbFallback, NativeMatchesOsMesaOnTheCity) {
  const Scene scene = loadScene("builtin:city?blocks=6", true);
  expectNativeMatchesGl(scene, test::sceneCamera(scene, 320, 240), "city", 2.5e-4);
}

TEST(RzbFallback, NativeMatchesOsMesaOnTheForest) {
  const Scene scene = loadScene("builtin:forest", true);
  expectNativeMatchesGl(scene, test::sceneCamera(scene, 320, 240), "forest", 2.5e-4);
}

TEST(RzbFallback, NativeMatchesOsMesaOnARealMesh) {
  const std::string path = test::scannedMesh("bunny00.off");
  if (path.empty()) GTEST_SKIP() << "bunny00.off missing: run scripts/fetch-test-meshes.sh";
  const Scene scene = loadScene(path, true);
  expectNativeMatchesGl(scene, test::sceneCamera(scene, 320, 240), "bunny", 2.5e-4);
}

}  // namespace
}  // namespace lzb::rzb
