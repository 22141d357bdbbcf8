#pragma once
// toml++ 3.3.0 (Debian 12) reaches __builtin_unreachable, undefined behaviour, when it asks
// whether some non-ASCII characters are whitespace (marzer/tomlplusplus#190 and #295, found again
// by tests/fuzz): wherever one stands outside a string or comment, after a backslash in a
// multi-line basic string, and first after a line-ending backslash. TOML allows non-ASCII text
// only in strings and comments, and the escapes take none, so this check refuses those
// characters before toml++ reads the file, losing no valid scene but a multi-line string whose
// continued line starts with a non-ASCII character.
#include <string>
#include <string_view>

namespace lzb {

// Throws InputError "<file>:<line>:<column>: ..." at the first character toml++ cannot read safely.
void checkTomlText(std::string_view text, const std::string& file);

}  // namespace lzb
