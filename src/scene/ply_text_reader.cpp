#include "src/scene/ply_text_reader.hpp"

#include <limits>
#include <optional>

#include "src/core/error.hpp"

namespace lzb {

void PlyTextReader::at(const std::string* element, uint64_t index, uint64_t count) {
  if (started_) endLine();
  started_ = true;
  std::string_view line;
  require(lines_.next(line), where_, [&] {
    return "truncated: PLY data ends inside element '" + *element + "' " + std::to_string(index) +
           " of " + std::to_string(count);
  });
  if (line.back() != '\n') throw NotStreamed{"a last line without a line end"};
  line = withoutLineEnd(line);
  // assimp ends a line at any of these, and skips a blank line after "\n" but not after "\r\n".
  if (line.find_first_of(std::string_view("\0\r\f", 3)) != std::string_view::npos)
    throw NotStreamed{"a NUL, carriage return or form feed inside a data line"};
  if (line.find_first_not_of(" \t") == std::string_view::npos)
    throw NotStreamed{"a blank line among the data"};
  rest_ = line;
}

double PlyTextReader::scalar(PlyType t) {
  std::string_view token;
  if (!nextToken(rest_, token)) throw NotStreamed{"a line with fewer values than its element"};
  std::optional<int64_t> integer;
  std::optional<double> real;
  switch (t) {
    case PlyType::Int8:
    case PlyType::Int16:
    case PlyType::Int32:
      integer = assimpInteger(token, true, uint64_t(std::numeric_limits<int32_t>::max()));
      break;
    case PlyType::UInt8:
    case PlyType::UInt16:
    case PlyType::UInt32:
      integer = assimpInteger(token, false, uint64_t(std::numeric_limits<uint32_t>::max()));
      break;
    case PlyType::Float32:  // assimp reads a float property as ai_real
    case PlyType::Float64:
      real = assimpReal(token, t == PlyType::Float64);
      break;
  }
  if (integer) return double(*integer);
  if (real) return *real;
  throw NotStreamed{"a value that is not one plain number ('" + std::string(token) + "')"};
}

void PlyTextReader::skip(PlyType t, uint64_t n) {
  for (uint64_t i = 0; i < n; ++i) scalar(t);
}

void PlyTextReader::endLine() {
  std::string_view token;
  if (nextToken(rest_, token)) throw NotStreamed{"a line with more values than its element"};
}

void PlyTextReader::finish() {
  if (started_) endLine();
  for (std::string_view line; lines_.next(line);)
    if (line.find_first_not_of("\r\n") != std::string_view::npos)
      throw NotStreamed{"data after the last element"};
}

}  // namespace lzb
