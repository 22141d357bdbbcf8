#pragma once
// The "NAME?key=value&key=value" part of a built-in generator spec.
#include <cstdint>
#include <map>
#include <set>
#include <string>

namespace lzb {

class BuiltinParams {
 public:
  // Throws InputError for an empty name, an empty or duplicate key, or a key without '='.
  explicit BuiltinParams(const std::string& spec);

  const std::string& name() const { return name_; }
  const std::string& spec() const { return spec_; }
  // Each getter returns the default when the key is absent and throws InputError naming the key
  // when the value does not parse or lies outside [lo, hi].
  int64_t integer(const std::string& key, int64_t def, int64_t lo, int64_t hi);
  double number(const std::string& key, double def, double lo, double hi);
  uint64_t seed(const std::string& key, uint64_t def);
  std::string text(const std::string& key, const std::string& def);
  // Throws InputError naming the first key no getter asked for.
  void finish() const;
  // "<spec>: <key>" for messages.
  std::string where(const std::string& key) const;

 private:
  std::string spec_, name_;
  std::map<std::string, std::string> values_;
  std::set<std::string> asked_;
};

}  // namespace lzb
