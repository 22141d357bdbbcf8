#pragma once
// A scratch file of the external construction: bytes appended and read back by offset, removed
// when the object goes (also when the build fails).
#include <cstddef>
#include <cstdint>
#include <filesystem>

namespace lzb::sampletree {

class ScratchFile {
 public:
  explicit ScratchFile(std::filesystem::path path);
  ~ScratchFile();
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

  // Appends n bytes; returns the offset they start at.
  uint64_t append(const void* data, size_t n);
  void read(uint64_t offset, size_t n, void* out) const;
  uint64_t size() const { return end_; }

 private:
  std::filesystem::path path_;
  int fd_ = -1;
  uint64_t end_ = 0;
};

}  // namespace lzb::sampletree
