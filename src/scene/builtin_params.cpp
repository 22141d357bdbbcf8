#include "src/scene/builtin_params.hpp"

#include <charconv>
#include <sstream>

#include "src/core/error.hpp"

namespace lzb {

BuiltinParams::BuiltinParams(const std::string& spec) : spec_(spec) {
  const size_t q = spec.find('?');
  name_ = spec.substr(0, q);
  require(!name_.empty(), "builtin:" + spec, "missing generator name");
  if (q == std::string::npos) return;
  const std::string query = spec.substr(q + 1);
  size_t at = 0;
  while (at <= query.size()) {
    const size_t amp = std::min(query.find('&', at), query.size());
    const std::string item = query.substr(at, amp - at);
    at = amp + 1;
    if (item.empty()) continue;  // tolerate "a=1&&b=2" and a trailing '&'
    const size_t eq = item.find('=');
    require(eq != std::string::npos && eq > 0, "builtin:" + spec,
            "parameter '" + item + "' is not key=value");
    const std::string key = item.substr(0, eq);
    require(values_.emplace(key, item.substr(eq + 1)).second, where(key), "given twice");
  }
}

std::string BuiltinParams::where(const std::string& key) const {
  return "builtin:" + spec_ + ": " + key;
}

int64_t BuiltinParams::integer(const std::string& key, int64_t def, int64_t lo, int64_t hi) {
  asked_.insert(key);
  const auto it = values_.find(key);
  if (it == values_.end()) return def;
  const std::string& v = it->second;
  int64_t x = 0;
  const auto r = std::from_chars(v.data(), v.data() + v.size(), x);
  const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  require(!v.empty() && r.ec != std::errc::invalid_argument && r.ptr == v.data() + v.size(),
          where(key), "must be an integer in " + range + ", got '" + v + "'");
  require(r.ec == std::errc() && x >= lo && x <= hi, where(key),
          "must be in " + range + ", got " + v);
  return x;
}

double BuiltinParams::number(const std::string& key, double def, double lo, double hi) {
  asked_.insert(key);
  const auto it = values_.find(key);
  if (it == values_.end()) return def;
  std::ostringstream range;
  range << "[" << lo << ", " << hi << "]";
  const double x = parseNumber(it->second, where(key), "a number in " + range.str());
  require(x >= lo && x <= hi, where(key), "must be in " + range.str() + ", got " + it->second);
  return x;
}

uint64_t BuiltinParams::seed(const std::string& key, uint64_t def) {
  asked_.insert(key);
  const auto it = values_.find(key);
  if (it == values_.end()) return def;
  const std::string& v = it->second;
  uint64_t x = 0;
  const auto r = std::from_chars(v.data(), v.data() + v.size(), x);
  require(!v.empty() && r.ec == std::errc() && r.ptr == v.data() + v.size(), where(key),
          "must be an unsigned 64-bit integer, got '" + v + "'");
  return x;
}

std::string BuiltinParams::text(const std::string& key, const std::string& def) {
  asked_.insert(key);
  const auto it = values_.find(key);
  if (it == values_.end()) return def;
  require(!it->second.empty(), where(key), "must not be empty");
  return it->second;
}

void BuiltinParams::finish() const {
  for (const auto& [key, value] : values_)
    if (!asked_.count(key)) {
      std::string known;
      for (const std::string& k : asked_) known += (known.empty() ? "" : ", ") + k;
      throw InputError(where(key) + ": unknown parameter of '" + name_ + "' (known: " + known +
                       ")");
    }
}

}  // namespace lzb
