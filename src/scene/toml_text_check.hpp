#pragma once
// toml++ 3.3.0 (Debian 12) reaches __builtin_unreachable, undefined behaviour, when it asks
// whether a character of U+00A1-U+0499, U+2C5E-U+2FFF, U+3001-U+3057 or U+FB26-U+FEFE is
// whitespace (marzer/tomlplusplus#190 and #295, found again by tests/fuzz). It asks outside
// strings, after backslashes in multi-line strings, and wherever a malformed token runs on over
// quotes, so no reading of the text short of toml++'s own tells where it will ask: this check
// refuses those characters anywhere in a scene file, before toml++ reads it. In a string they
// can be written as escapes ("\u00E9"), which toml++ decodes without asking.
#include <string>
#include <string_view>

namespace lzb {

// Throws InputError "<file>:<line>:<column>: ..." at the first such character.
void checkTomlText(std::string_view text, const std::string& file);

}  // namespace lzb
