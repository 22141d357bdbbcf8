#include "src/core/error.hpp"

#include <cmath>

namespace lzb {

double parseNumber(const std::string& text, const std::string& option, const std::string& expected) {
  size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  require(used == text.size() && used > 0 && std::isfinite(v), option,
          "expected " + expected + ", got '" + text + "'");
  return v;
}

}  // namespace lzb
