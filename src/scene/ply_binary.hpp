#pragma once
// What the streaming PLY reader (ply_stream.hpp) and the slice reader (ply_slices.hpp) share: the
// header read from the file's start with the layout of its mesh (or why the loader must read it),
// buffered reads of binary data in the file's byte order, and colours as the loader normalises
// them.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "src/core/error.hpp"
#include "src/scene/ply_header.hpp"

namespace lzb {

constexpr size_t kPlyReadBuffer = 1 << 20;
constexpr uint64_t kPlyMaxCount = 0xffffffffu;  // assimp counts elements in 32 bits

// Buffered reads of a PLY file's binary data, in its byte order; a read past the end is an
// InputError naming the element being read.
class PlyReader {
 public:
  static constexpr bool kBinary = true;

  // Reads from `offset`, never past `end` (a slice's end; by default the file's): a read
  // beyond it is the data ending.
  PlyReader(const std::filesystem::path& path, const std::string& where, uint64_t offset, bool big,
            uint64_t end = ~uint64_t(0))
      : where_(where), big_(big), buffer_(kPlyReadBuffer) {
    file_ = std::fopen(path.c_str(), "rb");
    require(file_ != nullptr, where_, "cannot be read (permission?)");
    std::fseek(file_, 0, SEEK_END);
    size_ = std::min(uint64_t(std::ftell(file_)), end);
    seek(offset);
  }
  ~PlyReader() { std::fclose(file_); }
  PlyReader(const PlyReader&) = delete;
  PlyReader& operator=(const PlyReader&) = delete;

  // What is being read, for the message when the data ends.
  void at(const std::string* element, uint64_t index, uint64_t count) {
    element_ = element, index_ = index, count_ = count;
  }
  uint64_t offset() const { return start_ + pos_; }
  // Bytes read from the file so far (what a rank reading a slice is held to).
  uint64_t bytesRead() const { return read_; }
  uint64_t size() const { return size_; }

  double scalar(PlyType t) {
    unsigned char b[8];
    const int n = plyTypeBytes(t);
    bytes(b, size_t(n));
    if (big_) std::reverse(b, b + n);
    switch (t) {
      case PlyType::Int8:
        return double(int8_t(b[0]));
      case PlyType::UInt8:
        return double(b[0]);
      case PlyType::Int16:
        return double(as<int16_t>(b));
      case PlyType::UInt16:
        return double(as<uint16_t>(b));
      case PlyType::Int32:
        return double(as<int32_t>(b));
      case PlyType::UInt32:
        return double(as<uint32_t>(b));
      case PlyType::Float32:
        return double(as<float>(b));
      case PlyType::Float64:
        return as<double>(b);
    }
    return 0.0;
  }
  void skip(PlyType t, uint64_t n) { skip(n * uint64_t(plyTypeBytes(t))); }
  void finish() {}  // what follows the elements is not read
  void skip(uint64_t n) {
    if (n <= len_ - pos_) {
      pos_ += size_t(n);
      return;
    }
    require(n <= size_ - offset(), where_, [this] { return truncated(); });
    seek(offset() + n);
  }
  std::string truncated() const {
    return "truncated: PLY binary data ends inside element '" + *element_ + "' " +
           std::to_string(index_) + " of " + std::to_string(count_);
  }

 private:
  template <class T>
  static T as(const unsigned char* b) {
    T v;
    std::memcpy(&v, b, sizeof(T));
    return v;
  }
  void seek(uint64_t to) {
    std::fseek(file_, long(to), SEEK_SET);
    start_ = to, pos_ = 0, len_ = 0;
  }
  void bytes(unsigned char* out, size_t n) {
    if (n > len_ - pos_) refill();
    require(n <= len_ - pos_, where_, [this] { return truncated(); });
    std::memcpy(out, buffer_.data() + pos_, n);
    pos_ += n;
  }
  void refill() {
    std::memmove(buffer_.data(), buffer_.data() + pos_, len_ - pos_);
    start_ += pos_, len_ -= pos_, pos_ = 0;
    const uint64_t left = size_ - std::min(size_, start_ + len_);
    const size_t want = size_t(std::min<uint64_t>(buffer_.size() - len_, left));
    const size_t got = std::fread(buffer_.data() + len_, 1, want, file_);
    len_ += got, read_ += got;
  }

  std::string where_;
  bool big_;
  std::FILE* file_ = nullptr;
  uint64_t size_ = 0, start_ = 0;  // start_: file offset of buffer_[0]
  std::vector<unsigned char> buffer_;
  size_t pos_ = 0, len_ = 0;
  const std::string* element_ = nullptr;
  uint64_t index_ = 0, count_ = 0;
  uint64_t read_ = 0;
};

// Which elements and properties hold the mesh (indices into the header's lists; -1: none).
struct PlyMeshLayout {
  size_t vertex = 0, face = 0;
  int x = -1, y = -1, z = -1, rgba[4] = {-1, -1, -1, -1};
  int indices = -1;
};

// The layout of the mesh `h` holds, or why the file is left to the loader (a header assimp 5.2
// reads otherwise, triangle strips, not one vertex and one face element, faces before the
// vertices, no x, y and z, no integer vertex index list...). Throws InputError naming `where` for
// an unknown format or more elements than the loader reads.
std::string plyMeshLayout(const PlyHeader& h, PlyMeshLayout& l, const std::string& where);

// A colour component as assimp 5.2 normalises it (PLYImporter::NormalizeColorValue).
float normalisedColour(double v, PlyType t);

// A PLY file's header as the mesh readers take it: parsed, with its layout.
struct PlyHead {
  PlyHeader header;
  PlyMeshLayout layout;
  uint64_t bytesRead = 0;  // of the file, to find the header's end
};
// Reads the header from the start of `path` (at most the 1 MiB assimp reads it in) and its
// layout. Sets `why` (and returns what was read) when the loader must read the file instead;
// throws InputError naming `where` for a header the loader refuses.
PlyHead readPlyHead(const std::filesystem::path& path, const std::string& where, std::string& why);

}  // namespace lzb
