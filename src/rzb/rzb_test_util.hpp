#pragma once
// Helpers shared by the rzb tests: cameras, small scenes, rendering with either method.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "src/core/camera.hpp"
#include "src/core/framebuffer.hpp"
#include "src/core/renderer.hpp"
#include "src/core/test_camera.hpp"
#include "src/image/metrics.hpp"
#include "src/image/test_reference.hpp"
#include "src/rzb/rzb_renderer.hpp"
#include "src/scene/load.hpp"
#include "src/zbuffer/zbuffer_renderer.hpp"

namespace lzb::rzb::testing_util {

inline Camera makeCamera(const glm::dvec3& position, const glm::dvec3& lookAt, double n, double f,
                         int width, int height, double fov = 45.0) {
  return lzb::testing_util::lookAtCamera(position, lookAt, n, f, width, height, fov);
}

// The scene's own camera (or a framing one) at width x height.
inline Camera sceneCamera(const Scene& scene, int width, int height) {
  const CameraSpec base = scene.camera ? *scene.camera : frameBounds(scene.bounds());
  return Camera(withClipPlanes(base, scene.bounds()), width, height);
}

inline Framebuffer renderWith(Renderer& r, const Camera& camera, int frame = 0,
                              WorkShare share = {}, FrameStats* stats = nullptr) {
  Framebuffer fb(camera.width(), camera.height());
  FrameStats local;
  r.render(camera, frame, share, fb, stats ? *stats : local);
  return fb;
}

inline Framebuffer renderZBuffer(const Scene& scene, const Camera& camera) {
  ZBufferRenderer z(scene, RenderOptions{});
  return renderWith(z, camera);
}

inline RenderOptions options(int threads, uint64_t seed = 7) {
  RenderOptions o;
  o.method = "rzb";
  o.threads = threads;
  o.seed = seed;
  o.quiet = true;
  return o;
}

inline bool sameImage(const Framebuffer& a, const Framebuffer& b) {
  return a.width == b.width && a.height == b.height && a.id == b.id && a.color == b.color &&
         std::equal(a.depth.begin(), a.depth.end(), b.depth.begin(), [](float x, float y) {
           return std::bit_cast<uint32_t>(x) == std::bit_cast<uint32_t>(y);
         });
}

// The exact z-buffer's reference of `camera`: centres and 4x4 sub-samples (src/image/reference.hpp).
inline ReferenceFrame zbufferReference(const Scene& scene, const Camera& camera) {
  ZBufferRenderer z(scene, RenderOptions{});
  return lzb::testing_util::renderReference(z, scene, camera);
}

// The papers' correct-pixel rate measured closely for sub-pixel triangles: a pixel is correct
// when its ID (or emptiness) is seen by an exact z-buffer rendered at `factor` times the
// resolution anywhere in the pixel's factor x factor sub-pixels, widened by `margin` sub-pixels.
// An odd factor keeps the pixel's own centre among the sub-pixel centres.
inline double visibleInPixelRate(const Framebuffer& test, const Scene& scene, const Camera& camera,
                                 int factor = 5, int margin = 1) {
  const Camera fine(camera.spec(), camera.width() * factor, camera.height() * factor);
  const Framebuffer ref = renderZBuffer(scene, fine);
  size_t correct = 0;
  for (int y = 0; y < test.height; ++y)
    for (int x = 0; x < test.width; ++x) {
      const uint64_t id = test.id[test.index(x, y)];
      bool ok = false;
      for (int sy = y * factor - margin; sy < (y + 1) * factor + margin && !ok; ++sy)
        for (int sx = x * factor - margin; sx < (x + 1) * factor + margin && !ok; ++sx)
          if (sx >= 0 && sy >= 0 && sx < ref.width && sy < ref.height)
            ok = ref.id[ref.index(sx, sy)] == id;
      correct += ok;
    }
  return double(correct) / double(test.size());
}

// A real scanned mesh (CGAL's data, extracted by scripts/fetch-test-meshes.sh), or "" if none.
inline std::string realMesh(const std::string& name) {
  namespace fs = std::filesystem;
  const char* src = std::getenv("LZB_SOURCE_DIR");
  // Without the variable (the test run directly): the repository this file is in.
  const fs::path root = src ? fs::path(src) : fs::path(__FILE__).parent_path().parent_path().parent_path();
  for (const fs::path& dir : {root / "build" / "data", fs::temp_directory_path() / "lzb_rzb_meshes"})
    if (fs::exists(dir / name)) return (dir / name).string();
  const fs::path dir = fs::temp_directory_path() / "lzb_rzb_meshes";
  const std::string cmd = "bash '" + (root / "scripts" / "fetch-test-meshes.sh").string() + "' '" +
                          dir.string() + "' >/dev/null 2>&1";
  if (std::system(cmd.c_str()) == 0 && fs::exists(dir / name)) return (dir / name).string();
  return "";
}

}  // namespace lzb::rzb::testing_util
