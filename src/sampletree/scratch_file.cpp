#include "src/sampletree/scratch_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace lzb::sampletree {

namespace {

// Scratch-file failures (a full disk) are the machine's, not the input's: a runtime_error.
[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what) {
  throw std::runtime_error(path.string() + ": " + what + ": " + std::strerror(errno));
}

}  // namespace

ScratchFile::ScratchFile(std::filesystem::path path) : path_(std::move(path)) {
  fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd_ < 0) fail(path_, "cannot create the scratch file");
}

ScratchFile::~ScratchFile() {
  ::close(fd_);
  std::error_code ec;
  std::filesystem::remove(path_, ec);
}

uint64_t ScratchFile::append(const void* data, size_t n) {
  const uint64_t at = reserve(n);
  write(at, data, n);
  return at;
}

uint64_t ScratchFile::reserve(size_t n) {
  const uint64_t at = end_;
  end_ += n;
  return at;
}

void ScratchFile::write(uint64_t offset, const void* data, size_t n) const {
  const auto* p = static_cast<const char*>(data);
  for (size_t done = 0; done < n;) {
    const ssize_t k = ::pwrite(fd_, p + done, n - done, off_t(offset + done));
    if (k <= 0) fail(path_, "write failed");
    done += size_t(k);
  }
}

void ScratchFile::read(uint64_t offset, size_t n, void* out) const {
  auto* p = static_cast<char*>(out);
  for (size_t done = 0; done < n;) {
    const ssize_t k = ::pread(fd_, p + done, n - done, off_t(offset + done));
    if (k <= 0) fail(path_, "read failed");
    done += size_t(k);
  }
}

}  // namespace lzb::sampletree
