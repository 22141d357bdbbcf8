// The non-ASCII characters toml++ 3.3 cannot classify safely are refused; the rest passes.
#include "src/scene/toml_text_check.hpp"

#include <gtest/gtest.h>

#include <string>

#include "src/core/error.hpp"

namespace lzb {
namespace {

// The message checkTomlText throws for `text`, "" when it passes.
std::string refusal(const std::string& text) {
  try {
    checkTomlText(text, "s.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(TomlTextCheck, NonAsciiInStringsAndCommentsPasses) {
  for (const char* ok : {"a = \"\xC3\xA9\"\n", "a = '\xC3\xA9'\n", "# \xC3\xA9\n", "\"\xC3\xA9\" = 1\n",
                         "a = \"\"\"x\n\xC3\xA9\"\"\"\n", "a = '''\\\n\xC3\xA9'''\n",
                         "a = \"\"\"\\\n  x\xC3\xA9\"\"\"\n", "a = \"\\\"\xC3\xA9\"\n",
                         "a = \"\"\"x\"\"\"\"\" # \xC3\xA9\n", "\xEF\xBB\xBF" "a = 1\n"})
    EXPECT_EQ(refusal(ok), "") << ok;
}

TEST(TomlTextCheck, RefusesWhatToml33ReadsWithUndefinedBehaviour) {
  // The fuzzer's input: a byte order mark, a key, then U+FEFB.
  EXPECT_EQ(refusal("\xEF\xBB\xBFo\xEF\xBB\xBB"),
            "s.toml:1:2: a non-ASCII character outside a string or comment (the TOML reader, "
            "toml++ 3.3, cannot read it safely)");
  EXPECT_NE(refusal("a = 1\nb\xC3\xA9 = 2\n").find("s.toml:2:2: a non-ASCII character outside"),
            std::string::npos);
  EXPECT_NE(refusal("a = \"x\" \xC2\xA7\n").find("1:9"), std::string::npos);
  // marzer/tomlplusplus#190: the first character after a line-ending backslash.
  EXPECT_NE(refusal("s = \"\"\"\\\n\xC2\xA7\"\"\"\n").find("first after a line-ending backslash"),
            std::string::npos);
  EXPECT_NE(refusal("s = \"\"\"\\  \n\n  \xC2\xA7\"\"\"\n").find("s.toml:3:3:"), std::string::npos);
  EXPECT_NE(refusal("s = \"\"\"\\\xC2\xA7\"\"\"\n").find("after a backslash"), std::string::npos);
}

}  // namespace
}  // namespace lzb
