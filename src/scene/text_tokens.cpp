#include "src/scene/text_tokens.hpp"

#include <assimp/defs.h>
#include <assimp/fast_atof.h>

#include <cstdlib>
#include <string>

#include "src/core/error.hpp"

namespace lzb {

namespace {

// What fast_atof.h throws where assimp throws DeadlyImportError (whose constructor the shared
// library does not export).
struct NotANumber {
  template <class... T>
  explicit NotANumber(T&&...) {}
};

template <class Real>
std::optional<double> realToken(std::string_view token) {
  // fast_atoreal_move reads up to the first character that is no part of a number; a copy ends
  // the token with a NUL so that it cannot read past it.
  char copy[64];
  if (token.empty() || token.size() >= sizeof copy) return std::nullopt;
  token.copy(copy, token.size());
  copy[token.size()] = '\0';
  Real v = 0;
  try {
    if (Assimp::fast_atoreal_move<Real, NotANumber>(copy, v) != copy + token.size())
      return std::nullopt;
  } catch (const NotANumber&) {
    return std::nullopt;
  }
  return double(v);
}

}  // namespace

TextLines::TextLines(const std::filesystem::path& path, const std::string& where, uint64_t offset)
    : offset_(offset) {
  file_ = std::fopen(path.c_str(), "rb");
  require(file_ != nullptr, where, "cannot be read (permission?)");
  std::fseek(file_, long(offset), SEEK_SET);
}

TextLines::~TextLines() {
  std::fclose(file_);
  std::free(buffer_);
}

bool TextLines::next(std::string_view& line) {
  const ssize_t n = ::getline(&buffer_, &capacity_, file_);
  if (n <= 0) return false;
  offset_ += uint64_t(n);
  line = std::string_view(buffer_, size_t(n));
  return true;
}

std::string_view withoutLineEnd(std::string_view line) {
  if (!line.empty() && line.back() == '\n') line.remove_suffix(1);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return line;
}

bool nextToken(std::string_view& rest, std::string_view& token) {
  const size_t begin = rest.find_first_not_of(" \t");
  if (begin == std::string_view::npos) {
    rest = {};
    return false;
  }
  const size_t end = std::min(rest.find_first_of(" \t", begin), rest.size());
  token = rest.substr(begin, end - begin);
  rest.remove_prefix(end);
  return true;
}

std::optional<double> assimpReal(std::string_view token, bool asDouble) {
  return asDouble ? realToken<double>(token) : realToken<ai_real>(token);
}

std::optional<int64_t> assimpInteger(std::string_view token, bool isSigned, uint64_t limit) {
  const bool negative = isSigned && !token.empty() && token[0] == '-';
  if (isSigned && !token.empty() && (token[0] == '-' || token[0] == '+')) token.remove_prefix(1);
  if (token.empty() || token.size() > 10) return std::nullopt;
  uint64_t v = 0;
  for (const char c : token) {
    if (c < '0' || c > '9') return std::nullopt;
    v = v * 10 + uint64_t(c - '0');
  }
  if (v > limit) return std::nullopt;
  return negative ? -int64_t(v) : int64_t(v);
}

}  // namespace lzb
