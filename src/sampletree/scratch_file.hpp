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
  // Sets n bytes aside at the end for a later write (from any thread); returns their offset.
  uint64_t reserve(size_t n);
  // Writes n bytes at offset (inside what was appended or reserved).
  void write(uint64_t offset, const void* data, size_t n) const;
  void read(uint64_t offset, size_t n, void* out) const;
  uint64_t size() const { return end_; }

 private:
  std::filesystem::path path_;
  int fd_ = -1;
  uint64_t end_ = 0;
};

}  // namespace lzb::sampletree
