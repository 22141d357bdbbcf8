#pragma once
// The benchmarks' switches (tests named *Bench*, run only with LZB_BENCH=1, they print figures)
// and their settings from the environment.
#include <cstdlib>
#include <string>

namespace lzb::test {

inline bool benchEnabled() {
  const char* v = std::getenv("LZB_BENCH");
  return v && *v && *v != '0';
}

// The variable's value, or fallback when unset or empty.
inline std::string envString(const char* name, const std::string& fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::string(v) : fallback;
}

inline int envInt(const char* name, int fallback) {
  return std::atoi(envString(name, std::to_string(fallback)).c_str());
}

}  // namespace lzb::test
