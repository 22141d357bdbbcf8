#include "tests/support/meshes.hpp"

#include <cstdlib>

namespace lzb::test {

std::filesystem::path dataDir() {
  return LZB_DATA_DIR;
}

std::string scannedMesh(const std::string& name) {
  const std::filesystem::path file = dataDir() / name;
  if (std::filesystem::exists(file)) return file.string();
  // ctest names the source tree (it may have moved since the build); a direct run uses the one
  // this library was built from.
  const char* env = std::getenv("LZB_SOURCE_DIR");
  const std::string source = env ? env : LZB_SOURCE_ROOT;
  const std::string cmd = "bash '" + source + "/scripts/fetch-test-meshes.sh' '" +
                          dataDir().string() + "' >/dev/null 2>&1";
  if (std::system(cmd.c_str()) != 0 || !std::filesystem::exists(file)) return "";
  return file.string();
}

}  // namespace lzb::test
