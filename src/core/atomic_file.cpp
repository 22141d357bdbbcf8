#include "src/core/atomic_file.hpp"

#include <unistd.h>

#include <fstream>

#include "src/core/error.hpp"

namespace lzb {

void writeAtomically(const std::filesystem::path& path,
                     const std::function<void(const std::filesystem::path&)>& write) {
  std::filesystem::path tmp = path;
  tmp.replace_filename("." + path.stem().string() + ".tmp" + std::to_string(getpid()) +
                       path.extension().string());
  try {
    write(tmp);
    std::filesystem::rename(tmp, path);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw;
  }
}

void writeTextAtomically(const std::filesystem::path& path, const std::string& text) {
  writeAtomically(path, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw InputError(path.string() + ": cannot write");
  });
}

}  // namespace lzb
