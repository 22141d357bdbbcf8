#include "src/scene/toml_text_check.hpp"

#include <cstdint>
#include <cstdio>

#include "src/core/error.hpp"

namespace lzb {

namespace {

// The code points toml++ 3.3's is_non_ascii_horizontal_whitespace() has no answer for.
bool unclassifiable(char32_t c) {
  return (c >= 0xA1 && c <= 0x499) || (c >= 0x2C5E && c <= 0x2FFF) || (c >= 0x3001 && c <= 0x3057) ||
         (c >= 0xFB26 && c <= 0xFEFE);
}

// The UTF-8 sequence at s[at] and its length; an invalid one reads as 0xFFFD of length 1
// (toml++ refuses invalid UTF-8 itself, before classifying anything).
char32_t decode(std::string_view s, size_t at, size_t& length) {
  const auto byte = [&](size_t i) { return static_cast<unsigned char>(s[i]); };
  const unsigned char lead = byte(at);
  length = lead < 0x80 ? 1 : lead >= 0xF0 ? 4 : lead >= 0xE0 ? 3 : lead >= 0xC0 ? 2 : 0;
  if (length == 0 || at + length > s.size()) {
    length = 1;
    return 0xFFFD;
  }
  char32_t c = length == 1 ? lead : lead & (0x7F >> length);
  for (size_t i = 1; i < length; ++i) {
    if ((byte(at + i) & 0xC0) != 0x80) {
      length = 1;
      return 0xFFFD;
    }
    c = (c << 6) | (byte(at + i) & 0x3F);
  }
  return c;
}

}  // namespace

void checkTomlText(std::string_view text, const std::string& file) {
  int line = 1, column = 1;
  for (size_t at = 0, length = 1; at < text.size(); at += length) {
    const char32_t c = decode(text, at, length);
    if (unclassifiable(c)) {
      char code[16];
      std::snprintf(code, sizeof code, "U+%04X", unsigned(c));
      throw InputError(file + ":" + std::to_string(line) + ":" + std::to_string(column) +
                       ": the TOML reader (toml++ 3.3) cannot read the character " + code +
                       " safely; in a string, write it as the escape \\u" + (code + 2));
    }
    if (c == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
}

}  // namespace lzb
