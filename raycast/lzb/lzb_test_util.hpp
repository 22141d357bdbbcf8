#pragma once
// Scenes and helpers for the LZB renderer tests: small versions of the benchmark scenes (a city,
// instanced scenes, a real scanned mesh), rendering one frame, accuracy against the z-buffer
// (testing_util::renderReference).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "raycast/lzb/lzb_renderer.hpp"
#include "src/image/metrics.hpp"
#include "src/image/test_reference.hpp"
#include "src/scene/load.hpp"
#include "src/zbuffer/zbuffer_renderer.hpp"

namespace lzb::testing {

inline RenderOptions lzbRenderOptions(int threads = 2) {
  RenderOptions o;
  o.method = "lzb";
  o.threads = threads;
  o.quiet = true;
  return o;
}

inline localz::LzbOptions stageOptions(localz::LzbStage stage) {
  localz::LzbOptions o;
  o.stage = stage;
  return o;
}

inline Framebuffer renderFrame(Renderer& r, const Camera& cam, WorkShare share = {},
                               FrameStats* statsOut = nullptr) {
  Framebuffer fb(cam.width(), cam.height());
  FrameStats stats;
  r.render(cam, 0, share, fb, stats);
  if (statsOut) *statsOut = std::move(stats);
  return fb;
}

// Camera of frame f of `frames` on the default path (the scene's camera, else framed), with
// clip planes from the bounds.
inline Camera pathFrame(const Scene& scene, int f, int frames, int w, int h) {
  const CameraSpec base = scene.camera ? *scene.camera : frameBounds(scene.bounds());
  return Camera(withClipPlanes(pathCamera(scene, base, f, frames), scene.bounds()), w, h);
}

// A real scanned mesh from the CGAL demo data (scripts/fetch-test-meshes.sh), extracted into
// the build's data folder on first use. Empty when it cannot be had.
inline std::string scannedMesh(const std::string& name) {
  const std::filesystem::path data = LZB_DATA_DIR;
  const std::filesystem::path file = data / name;
  if (std::filesystem::exists(file)) return file.string();
  const char* source = std::getenv("LZB_SOURCE_DIR");
  if (!source) return "";
  const std::string cmd = "bash '" + std::string(source) + "/scripts/fetch-test-meshes.sh' '" +
                          data.string() + "' >/dev/null 2>&1";
  if (std::system(cmd.c_str()) != 0 || !std::filesystem::exists(file)) return "";
  return file.string();
}

}  // namespace lzb::testing
