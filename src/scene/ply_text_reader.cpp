#include "src/scene/ply_text_reader.hpp"

#include <assimp/defs.h>
#include <assimp/fast_atof.h>

#include <cstring>
#include <limits>
#include <optional>

#include "src/core/error.hpp"

namespace lzb {

namespace {

bool isSpace(char c) { return c == ' ' || c == '\t'; }

// A whole token of decimal digits, optionally signed, within `limit`, as strtoul10 / strtol10
// read it; nullopt where assimp's reading could differ (another character, an overflow).
std::optional<double> integerToken(const char* b, const char* e, bool isSigned, uint64_t limit) {
  const bool negative = isSigned && *b == '-';
  if (isSigned && (*b == '-' || *b == '+')) ++b;
  if (b == e || e - b > 10) return std::nullopt;
  uint64_t v = 0;
  for (const char* c = b; c < e; ++c) {
    if (*c < '0' || *c > '9') return std::nullopt;
    v = v * 10 + uint64_t(*c - '0');
  }
  if (v > limit) return std::nullopt;
  return negative ? -double(v) : double(v);
}

// What fast_atof.h throws where assimp throws DeadlyImportError (whose constructor the shared
// library does not export).
struct NotANumber {
  template <class... T>
  explicit NotANumber(T&&...) {}
};

// A whole token read by assimp's fast_atoreal_move as type Real (it throws on what is no number).
template <class Real>
std::optional<double> realToken(const char* b, const char* e) {
  Real v = 0;
  try {
    if (Assimp::fast_atoreal_move<Real, NotANumber>(b, v) != e) return std::nullopt;
  } catch (const NotANumber&) {
    return std::nullopt;
  }
  return double(v);
}

}  // namespace

PlyTextReader::PlyTextReader(const std::filesystem::path& path, const std::string& where,
                             uint64_t offset)
    : where_(where), next_(offset) {
  file_ = std::fopen(path.c_str(), "rb");
  require(file_ != nullptr, where_, "cannot be read (permission?)");
  std::fseek(file_, long(offset), SEEK_SET);
}

PlyTextReader::~PlyTextReader() {
  std::fclose(file_);
  std::free(line_);
}

void PlyTextReader::at(const std::string* element, uint64_t index, uint64_t count) {
  if (pos_) endLine();
  element_ = element, index_ = index, count_ = count;
  const ssize_t n = ::getline(&line_, &capacity_, file_);
  require(n > 0, where_, [&] {
    return "truncated: PLY data ends inside element '" + *element_ + "' " +
           std::to_string(index_) + " of " + std::to_string(count_);
  });
  next_ += uint64_t(n);
  end_ = line_ + n;
  if (end_[-1] != '\n') throw NotStreamed{"a last line without a line end"};
  --end_;
  if (end_ > line_ && end_[-1] == '\r') --end_;
  // assimp ends a line at any of these, and skips a blank line after "\n" but not after "\r\n".
  for (const char* c = line_; c < end_; ++c)
    if (*c == '\0' || *c == '\r' || *c == '\f')
      throw NotStreamed{"a NUL, carriage return or form feed inside a data line"};
  pos_ = line_;
  const char* b;
  const char* e;
  if (!token(b, e)) throw NotStreamed{"a blank line among the data"};
  pos_ = line_;
}

bool PlyTextReader::token(const char*& begin, const char*& end) {
  while (pos_ < end_ && isSpace(*pos_)) ++pos_;
  if (pos_ == end_) return false;
  begin = pos_;
  while (pos_ < end_ && !isSpace(*pos_)) ++pos_;
  end = pos_;
  return true;
}

double PlyTextReader::scalar(PlyType t) {
  const char* b;
  const char* e;
  if (!token(b, e)) throw NotStreamed{"a line with fewer values than its element"};
  std::optional<double> v;
  switch (t) {
    case PlyType::Int8:
    case PlyType::Int16:
    case PlyType::Int32:
      v = integerToken(b, e, true, uint64_t(std::numeric_limits<int32_t>::max()));
      break;
    case PlyType::UInt8:
    case PlyType::UInt16:
    case PlyType::UInt32:
      v = integerToken(b, e, false, uint64_t(std::numeric_limits<uint32_t>::max()));
      break;
    case PlyType::Float32:
      v = realToken<ai_real>(b, e);  // assimp reads a float property as ai_real
      break;
    case PlyType::Float64:
      v = realToken<double>(b, e);
      break;
  }
  if (!v) throw NotStreamed{"a value that is not one plain number ('" + std::string(b, e) + "')"};
  return *v;
}

void PlyTextReader::skip(PlyType t, uint64_t n) {
  for (uint64_t i = 0; i < n; ++i) scalar(t);
}

void PlyTextReader::endLine() {
  const char* b;
  const char* e;
  if (token(b, e)) throw NotStreamed{"a line with more values than its element"};
}

void PlyTextReader::finish() {
  if (pos_) endLine();
  for (ssize_t n; (n = ::getline(&line_, &capacity_, file_)) > 0;)
    if (std::strspn(line_, "\r\n") != size_t(n)) throw NotStreamed{"data after the last element"};
}

}  // namespace lzb
