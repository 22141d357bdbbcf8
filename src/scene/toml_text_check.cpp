#include "src/scene/toml_text_check.hpp"

#include "src/core/error.hpp"

namespace lzb {

namespace {

bool isAscii(char c) { return static_cast<unsigned char>(c) < 0x80; }
bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

class TomlScanner {
 public:
  TomlScanner(std::string_view text, const std::string& file) : s_(text), file_(file) {
    if (s_.substr(0, 3) == "\xEF\xBB\xBF") at_ = 3;  // a UTF-8 byte order mark, which toml++ skips
  }

  void run() {
    while (at_ < s_.size()) {
      const char c = s_[at_];
      if (c == '#') {
        skipPast("\n");
      } else if (startsWith("\"\"\"")) {
        advance(3);
        multiLineBasic();
      } else if (startsWith("'''")) {
        advance(3);
        skipPast("'''");
      } else if (c == '"') {
        advance(1);
        singleLine('"', true);
      } else if (c == '\'') {
        advance(1);
        singleLine('\'', false);
      } else {
        if (!isAscii(c)) refuse("a non-ASCII character outside a string or comment");
        advance(1);
      }
    }
  }

 private:
  bool startsWith(std::string_view p) const { return s_.substr(at_, p.size()) == p; }

  // Moves n bytes on, counting lines and columns (in characters, as toml++ reports them).
  void advance(size_t n) {
    for (; n > 0 && at_ < s_.size(); --n, ++at_) {
      const char c = s_[at_];
      if (c == '\n') {
        ++line_;
        column_ = 1;
      } else if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) {
        ++column_;
      }
    }
  }

  void skipPast(std::string_view end) {
    while (at_ < s_.size() && !startsWith(end)) advance(1);
    advance(end.size());
  }

  // A one-line string; toml++ reports an unterminated one itself.
  void singleLine(char quote, bool escapes) {
    while (at_ < s_.size() && s_[at_] != quote && s_[at_] != '\n')
      advance(escapes && s_[at_] == '\\' ? 2 : 1);
    advance(1);
  }

  void multiLineBasic() {
    while (at_ < s_.size() && !startsWith("\"\"\"")) {
      if (s_[at_] != '\\') {
        advance(1);
        continue;
      }
      advance(1);
      if (at_ >= s_.size()) return;
      if (!isAscii(s_[at_])) refuse("a non-ASCII character after a backslash");
      if (!isSpace(s_[at_])) {
        advance(1);
        continue;
      }
      // A line-ending backslash: toml++ tests each character it skips, and the first after.
      while (at_ < s_.size() && isSpace(s_[at_])) advance(1);
      if (at_ < s_.size() && !isAscii(s_[at_]))
        refuse("a non-ASCII character first after a line-ending backslash");
    }
    advance(3);
    for (int k = 0; k < 2 && at_ < s_.size() && s_[at_] == '"'; ++k) advance(1);  // `x"`
  }

  [[noreturn]] void refuse(const std::string& what) const {
    throw InputError(file_ + ":" + std::to_string(line_) + ":" + std::to_string(column_) + ": " +
                     what + " (the TOML reader, toml++ 3.3, cannot read it safely)");
  }

  std::string_view s_;
  const std::string& file_;
  size_t at_ = 0;
  int line_ = 1, column_ = 1;
};

}  // namespace

void checkTomlText(std::string_view text, const std::string& file) { TomlScanner(text, file).run(); }

}  // namespace lzb
