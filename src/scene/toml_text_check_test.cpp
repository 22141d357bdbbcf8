// The characters toml++ 3.3 cannot classify are refused wherever they stand; the rest passes.
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

TEST(TomlTextCheck, OtherCharactersPass) {
  // U+00A0, U+3000 and U+FEFF (the byte order mark) toml++ classifies; U+0500, U+4E2D, U+1F600
  // lie outside its gaps; invalid UTF-8 is toml++'s own to refuse; escapes are plain ASCII.
  for (const char* ok : {"a = \"\xC2\xA0\"\n", "# \xE3\x80\x80\n", "\xEF\xBB\xBF" "a = 1\n",
                         "a = \"\xD4\x80\"\n", "a = '\xE4\xB8\xAD'\n", "# \xF0\x9F\x98\x80\n",
                         "a = \"\xC3\"\n", "a = \"\\u00E9\"\n"})
    EXPECT_EQ(refusal(ok), "") << ok;
}

TEST(TomlTextCheck, RefusesWhatToml33ReadsWithUndefinedBehaviour) {
  // The fuzzer's first input: a byte order mark, a key, then U+FEFB.
  EXPECT_EQ(refusal("\xEF\xBB\xBFo\xEF\xBB\xBB"),
            "s.toml:1:3: the TOML reader (toml++ 3.3) cannot read the character U+FEFB safely; in "
            "a string, write it as the escape \\uFEFB");
  // Its second: a number running on over quotes into U+FEF7 (no string was ever open).
  EXPECT_NE(refusal("x = [0.3\"\"\"\xEF\xBB\xB7o]\n").find("1:12: the TOML reader"),
            std::string::npos);
  // Each gap at both ends, in a string, a comment and a key.
  for (const char* bad : {"a = \"\xC2\xA1\"", "# \xD2\x99", "\xE2\xB1\x9E = 1", "a = '\xE2\xBF\xBF'",
                          "a = \"\"\"\\\n\xE3\x80\x81\"\"\"", "# \xE3\x81\x97", "\xEF\xAC\xA6",
                          "a = \"\xEF\xBB\xBE\""})
    EXPECT_NE(refusal(bad).find("cannot read the character U+"), std::string::npos) << bad;
  EXPECT_NE(refusal("a = 1\nb = \"caf\xC3\xA9\"\n").find("s.toml:2:9: "), std::string::npos);
}

}  // namespace
}  // namespace lzb
