#include "src/core/whole_file.hpp"

#include <fstream>
#include <sstream>

#include "src/core/error.hpp"

namespace lzb {

std::string readWholeFile(const std::filesystem::path& path, const std::string& unreadable) {
  std::ifstream in(path, std::ios::binary);
  require(bool(in), path.string(), unreadable);
  std::ostringstream text;
  text << in.rdbuf();
  return std::move(text).str();
}

}  // namespace lzb
