// Sub-pixel geometry against the papers' definition, proven by rays: a pixel is correct when it
// shows a triangle visible somewhere in that pixel.
//
// The report's reference (src/image/reference.hpp) sees a pixel at 17 points. On the instanced
// armadillo field (about 100 triangles of 0.002 px^2 per pixel at 320x240) most triangles visible
// in a pixel contain none of the 17, so a correct pixel whose triangle is not at one of them is
// scored wrong: the report says 18 % for rzb at d = 1 and 97.9 % for zbuffer against raycast. Here
// such a pixel is checked exactly instead: it is correct when a ray from the eye to a point of its
// triangle inside the pixel hits that triangle first (a witness). Without a witness it stays
// wrong, so the rate below never counts a pixel the definition would not.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>

#include "raycast/embree_scene.hpp"
#include "raycast/raycast_renderer.hpp"
#include "src/image/metrics.hpp"
#include "src/image/test_reference.hpp"
#include "src/rzb/rzb_renderer.hpp"
#include "src/scene/load.hpp"
#include "src/zbuffer/zbuffer_renderer.hpp"

namespace lzb {
namespace {

namespace fs = std::filesystem;

constexpr int kWitnessGrid = 8;      // rays through an 8 x 8 grid of the pixel (large triangles)
constexpr int kWitnessPoints = 64;   // rays to points of the triangle (small triangles)

struct WorldTriangle {
  glm::dvec3 v[3];
};

WorldTriangle worldTriangle(const Scene& scene, uint64_t id) {
  const Scene::TriangleRef ref = *scene.resolve(id);
  const Mesh& mesh = scene.nodes[ref.node].mesh;
  WorldTriangle t;
  for (int k = 0; k < 3; ++k)
    t.v[k] = glm::dvec3(ref.transform * glm::dvec4(glm::dvec3(mesh.vertex(ref.triangle, k)), 1.0));
  return t;
}

// Point i of n on the triangle: a Halton (2, 3) point of the unit square folded onto it.
glm::dvec3 pointOn(const WorldTriangle& t, int i) {
  const auto halton = [](int index, int base) {
    double f = 1.0, r = 0.0;
    for (int k = index + 1; k > 0; k /= base) {
      f /= base;
      r += f * (k % base);
    }
    return r;
  };
  double a = halton(i, 2), b = halton(i, 3);
  if (a + b > 1.0) a = 1.0 - a, b = 1.0 - b;
  return t.v[0] + a * (t.v[1] - t.v[0]) + b * (t.v[2] - t.v[0]);
}

bool firstHitIs(const EmbreeScene& embree, const Camera& camera, const glm::dvec3& dir, uint64_t id) {
  return embree.intersect(camera.position(), dir, camera.nearPlane(), camera.farPlane()).id == id;
}

// True when a ray through pixel (x, y) sees triangle `id` first: through a grid of the pixel, or
// to a point of the triangle that projects into the pixel.
bool witnessed(const Scene& scene, const EmbreeScene& embree, const Camera& camera, int x, int y,
               uint64_t id) {
  for (int b = 0; b < kWitnessGrid; ++b)
    for (int a = 0; a < kWitnessGrid; ++a) {
      const glm::dvec3 dir =
          camera.pixelDirection(x + (a + 0.5) / kWitnessGrid, y + (b + 0.5) / kWitnessGrid);
      if (firstHitIs(embree, camera, dir, id)) return true;
    }
  const WorldTriangle t = worldTriangle(scene, id);
  for (int i = 0; i < kWitnessPoints; ++i) {
    const glm::dvec3 q = pointOn(t, i);
    const glm::dvec3 p = camera.project(q);
    const bool inside = p.z > 0.0 && p.x >= x && p.x < x + 1 && p.y >= y && p.y < y + 1;
    // Divided by the depth, the direction's forward component is 1 (t is the view depth).
    if (inside && firstHitIs(embree, camera, (q - camera.position()) / p.z, id)) return true;
  }
  return false;
}

struct Witnessed {
  Accuracy report;        // the 17-sample figures
  double correctRate;     // correct covered pixels, with witnesses, over covered pixels
};

// The report's accuracy, then every covered pixel it scores wrong that shows a triangle checked
// for a witness (holes stay wrong: they show nothing).
Witnessed witnessedAccuracy(const Framebuffer& test, const ReferenceFrame& ref, const Scene& scene,
                            const EmbreeScene& embree, const Camera& camera) {
  Witnessed w{compare(test, ref), 0.0};
  size_t rescued = 0;
#pragma omp parallel for schedule(dynamic, 4) reduction(+ : rescued)
  for (int y = 0; y < test.height; ++y)
    for (int x = 0; x < test.width; ++x) {
      const size_t i = test.index(x, y);
      const uint64_t id = test.id[i];
      if (id == kNoId || id == ref.centreId[i]) continue;
      const uint64_t* sub = ref.subsamples(i);
      if (std::find(sub, sub + kSubsamples, id) != sub + kSubsamples) continue;
      rescued += witnessed(scene, embree, camera, x, y, id);
    }
  w.correctRate = double(w.report.correctCoveredPixels + rescued) / double(w.report.coveredPixels);
  return w;
}

class SubpixelField : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const fs::path mesh = fs::path(LZB_DATA_DIR) / "armadillo.off";
    if (!fs::exists(mesh)) return;
    // 1024 armadillos of 52 K triangles (53 M), most triangles far smaller than a pixel.
    scene_ = new Scene(loadScene("builtin:replicated?mesh=" + mesh.string() + "&k=32&levels=1", true));
  }
  static void TearDownTestSuite() {
    delete scene_;
    scene_ = nullptr;
  }
  void SetUp() override {
    if (!scene_) GTEST_SKIP() << "armadillo.off missing: run scripts/fetch-test-meshes.sh";
  }
  static RenderOptions options(const std::string& method) {
    RenderOptions o;
    o.method = method;
    o.threads = 2;
    o.quiet = true;
    return o;
  }
  static Camera camera() {
    const CameraSpec base = scene_->camera ? *scene_->camera : frameBounds(scene_->bounds());
    return Camera(withClipPlanes(base, scene_->bounds()), 320, 240);
  }
  static Framebuffer render(Renderer& r, const Camera& cam) {
    Framebuffer fb(cam.width(), cam.height());
    FrameStats stats;
    r.render(cam, 0, WorkShare{}, fb, stats);
    return fb;
  }
  static Scene* scene_;
};

Scene* SubpixelField::scene_ = nullptr;

TEST_F(SubpixelField, RzbAtD1ShowsAVisibleTriangleOnAtLeast95PercentOfCoveredPixels) {
  const Camera cam = camera();
  RaycastRenderer raycast(*scene_, options("raycast"));
  rzb::RzbRenderer r(*scene_, options("rzb"), rzb::RzbParams{});
  const Witnessed w = witnessedAccuracy(render(r, cam), testing_util::renderReference(raycast, *scene_, cam),
                                        *scene_, raycast.embreeScene(), cam);
  std::printf("[ subpixel ] rzb d=1 320x240: report %.4f, with witnesses %.4f of %zu covered\n",
              w.report.correctRateCovered, w.correctRate, w.report.coveredPixels);
  EXPECT_GE(w.correctRate, 0.95);
}

TEST_F(SubpixelField, ZBufferShowsAVisibleTriangleOnAtLeast995PermilleOfCoveredPixels) {
  const Camera cam = camera();
  RaycastRenderer raycast(*scene_, options("raycast"));
  ZBufferRenderer zbuffer(*scene_, options("zbuffer"));
  const Witnessed w = witnessedAccuracy(render(zbuffer, cam),
                                        testing_util::renderReference(raycast, *scene_, cam), *scene_,
                                        raycast.embreeScene(), cam);
  std::printf("[ subpixel ] zbuffer vs raycast 320x240: report %.4f, with witnesses %.4f of %zu "
              "covered\n", w.report.correctRateCovered, w.correctRate, w.report.coveredPixels);
  EXPECT_GE(w.correctRate, 0.995);
}

// The check is no rubber stamp: the z-buffer's image moved by 2 pixels shows triangles of the
// wrong pixels, and few of them get a witness.
TEST_F(SubpixelField, AShiftedImageIsMostlyWrongEvenWithWitnesses) {
  const Camera cam = camera();
  RaycastRenderer raycast(*scene_, options("raycast"));
  ZBufferRenderer zbuffer(*scene_, options("zbuffer"));
  const Framebuffer image = render(zbuffer, cam);
  Framebuffer shifted = image;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      shifted.id[shifted.index(x, y)] = image.id[image.index(std::max(x - 2, 0), y)];
  const Witnessed w = witnessedAccuracy(shifted, testing_util::renderReference(raycast, *scene_, cam),
                                        *scene_, raycast.embreeScene(), cam);
  std::printf("[ subpixel ] zbuffer shifted by 2 px: report %.4f, with witnesses %.4f\n",
              w.report.correctRateCovered, w.correctRate);
  EXPECT_LT(w.correctRate, 0.5);
}

}  // namespace
}  // namespace lzb
