#include "src/image/compare.hpp"

#include <string>

#include "src/core/error.hpp"
#include "src/image/metrics.hpp"

namespace lzb {
namespace {

std::string bothNames(const FramePair& p) {
  return p.testPath.string() + " vs " + p.referencePath.string();
}

std::string sizeText(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

}  // namespace

bool sameOrigin(const FrameOrigin& a, const FrameOrigin& b) {
  const CameraSpec &p = a.camera.spec(), &q = b.camera.spec();
  return p.position == q.position && p.lookAt == q.lookAt && p.up == q.up &&
         p.fovyDegrees == q.fovyDegrees && p.nearPlane == q.nearPlane &&
         p.farPlane == q.farPlane && a.camera.width() == b.camera.width() &&
         a.camera.height() == b.camera.height() && a.sceneTriangles == b.sceneTriangles;
}

FramePair readFramePair(const std::filesystem::path& test, const std::filesystem::path& reference) {
  FramePair p{test, reference, readFrameExr(test), readReferenceExr(reference), std::nullopt};
  const std::optional<FrameOrigin> testOrigin = readFrameOrigin(test);
  p.origin = readFrameOrigin(reference);
  require(p.test.width == p.reference.width && p.test.height == p.reference.height, bothNames(p),
          "image sizes differ (" + sizeText(p.test.width, p.test.height) + " vs reference " +
              sizeText(p.reference.width, p.reference.height) + ")");
  // Frames of two views (or two scenes) share pixel positions but not what they show.
  require(!testOrigin || !p.origin || sameOrigin(*testOrigin, *p.origin), bothNames(p),
          "the frames' headers name different cameras or scenes (lzb.camera.*, "
          "lzb.scene.triangles)");
  return p;
}

nlohmann::json compareFrames(const FramePair& pair, const VisibilityWitness* witness) {
  try {
    return toJson(compare(pair.test, pair.reference, witness));
  } catch (const InputError& e) {
    // compare() knows no file names: add them.
    throw InputError(bothNames(pair) + ": " + e.what());
  }
}

nlohmann::json compareFiles(const std::filesystem::path& test,
                            const std::filesystem::path& reference) {
  return compareFrames(readFramePair(test, reference));
}

}  // namespace lzb
