#include "src/image/compare.hpp"

#include "src/core/error.hpp"
#include "src/image/frame_io.hpp"
#include "src/image/metrics.hpp"

namespace lzb {

nlohmann::json compareFiles(const std::filesystem::path& test,
                            const std::filesystem::path& reference) {
  const Framebuffer a = readFrameExr(test);
  const ReferenceFrame b = readReferenceExr(reference);
  try {
    return toJson(compare(a, b));
  } catch (const InputError& e) {
    // compare() knows no file names: add them.
    throw InputError(test.string() + " vs " + reference.string() + ": " + e.what());
  }
}

}  // namespace lzb
