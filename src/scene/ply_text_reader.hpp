#pragma once
// The data of an ASCII PLY read line by line for streaming (ply_stream.hpp), only where it is
// certain that the loader (assimp 5.2) reads the same values: one element a line, ended by "\n"
// or "\r\n", no blank lines, values separated by spaces or tabs, each value one token that
// assimp's own number parsers (fast_atof.h) read to its end and, for integers, within the type.
// Anything else throws NotStreamed, and the file is left to the loader.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "src/scene/ply_header.hpp"

namespace lzb {

// Why a file is left to the loader: read on, this reader might not give the loader's triangles.
struct NotStreamed {
  std::string why;
};

class PlyTextReader {
 public:
  static constexpr bool kBinary = false;

  // Reads `path` from `offset` (the start of a line). Throws InputError naming `where` if it
  // cannot be opened.
  PlyTextReader(const std::filesystem::path& path, const std::string& where, uint64_t offset);
  ~PlyTextReader();
  PlyTextReader(const PlyTextReader&) = delete;
  PlyTextReader& operator=(const PlyTextReader&) = delete;

  // Starts element instance `index` of `count`: its line, the previous one read to its end.
  void at(const std::string* element, uint64_t index, uint64_t count);
  // The next value of the line as assimp converts it (the value union, widened to double).
  double scalar(PlyType t);
  void skip(PlyType t, uint64_t n);
  // The file offset of the next line (before the first at(): the offset it was opened at).
  uint64_t offset() const { return next_; }
  // After the last element: its line read to its end and nothing but line ends after it.
  void finish();

 private:
  void endLine();
  bool token(const char*& begin, const char*& end);

  std::string where_;
  std::FILE* file_ = nullptr;
  char* line_ = nullptr;  // getline's buffer
  size_t capacity_ = 0;
  const char* pos_ = nullptr;   // within the current line; nullptr before the first
  const char* end_ = nullptr;   // the line's end (its "\n" or "\r\n" cut off)
  uint64_t next_ = 0;
  const std::string* element_ = nullptr;
  uint64_t index_ = 0, count_ = 0;
};

}  // namespace lzb
