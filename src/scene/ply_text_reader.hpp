#pragma once
// The data of an ASCII PLY read line by line for streaming (ply_stream.hpp), only where it is
// certain that the loader (assimp 5.2) reads the same values: one element a line, ended by "\n"
// or "\r\n", no blank lines, values separated by spaces or tabs, each value one token that
// assimp's own number parsers read to its end and, for integers, within 32 bits
// (text_tokens.hpp). Anything else throws NotStreamed, and the file is left to the loader.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "src/scene/mesh_stream.hpp"
#include "src/scene/ply_header.hpp"
#include "src/scene/text_tokens.hpp"

namespace lzb {

class PlyTextReader {
 public:
  static constexpr bool kBinary = false;

  // Reads `path` from `offset` (the start of a line). Throws InputError naming `where` if it
  // cannot be read.
  PlyTextReader(const std::filesystem::path& path, const std::string& where, uint64_t offset)
      : where_(where), lines_(path, where, offset) {}

  // Starts element instance `index` of `count`: its line, the previous one read to its end.
  void at(const std::string* element, uint64_t index, uint64_t count);
  // The next value of the line as assimp converts it (the value union, widened to double).
  double scalar(PlyType t);
  void skip(PlyType t, uint64_t n);
  // The file offset of the next line (before the first at(): the offset it was opened at).
  uint64_t offset() const { return lines_.offset(); }
  // After the last element: its line read to its end and nothing but line ends after it.
  void finish();

 private:
  void endLine();

  std::string where_;
  TextLines lines_;
  bool started_ = false;
  std::string_view rest_;  // what is left of the current line
};

}  // namespace lzb
