#pragma once
// Errors that the user caused (bad file, bad option): the CLI prints them and exits with status 2.
#include <concepts>
#include <stdexcept>
#include <string>

namespace lzb {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws InputError("<where>: <what>") when cond is false.
inline void require(bool cond, const std::string& where, const std::string& what) {
  if (!cond) throw InputError(where + ": " + what);
}
// The same with the message built only when cond is false, for checks run on every element of a
// file (a message built eagerly on every read took half of a streamed PLY pass).
template <std::invocable Message>
inline void require(bool cond, const std::string& where, Message&& what) {
  if (!cond) throw InputError(where + ": " + std::string(what()));
}

// The finite number `text` is, whole; else an InputError naming `option` and what was expected.
double parseNumber(const std::string& text, const std::string& option, const std::string& expected);

}  // namespace lzb
