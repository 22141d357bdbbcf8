#pragma once
// Text mesh files read as assimp 5.2 reads them, only where that is certain: lines of a file read
// from a byte offset, split into tokens at spaces and tabs, each number one whole token read by
// assimp's own parsers (fast_atof.h, which rounds some spellings otherwise than strtod:
// "123.456e2" reads 12345.6006 as a float there, 12345.5996 by strtof).
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace lzb {

// A file read line by line from a byte offset, never whole.
class TextLines {
 public:
  // Throws InputError naming `where` if it cannot be read.
  TextLines(const std::filesystem::path& path, const std::string& where, uint64_t offset);
  ~TextLines();
  TextLines(const TextLines&) = delete;
  TextLines& operator=(const TextLines&) = delete;

  // The next line with its "\n" (none on a last line without one); false at the end.
  bool next(std::string_view& line);
  // The file offset of the next line.
  uint64_t offset() const { return offset_; }

 private:
  std::FILE* file_ = nullptr;
  char* buffer_ = nullptr;  // getline's
  size_t capacity_ = 0;
  uint64_t offset_ = 0;
};

// `line` without its line end ("\n" or "\r\n").
std::string_view withoutLineEnd(std::string_view line);

// The next token of `rest` (split at spaces and tabs, as assimp's SkipSpaces); false when none.
bool nextToken(std::string_view& rest, std::string_view& token);

// `token` read whole by assimp's fast_atoreal_move as a float (ai_real) or a double; nullopt
// where it does not read to its end (or is no number at all).
std::optional<double> assimpReal(std::string_view token, bool asDouble);

// `token` as assimp's strtoul10 (or strtol10, signed) reads it, when it is all digits (after a
// sign, signed) and its value at most `limit`; nullopt otherwise (other characters, overflow).
std::optional<int64_t> assimpInteger(std::string_view token, bool isSigned, uint64_t limit);

}  // namespace lzb
