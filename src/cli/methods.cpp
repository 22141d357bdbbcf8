#include "src/cli/methods.hpp"

#include "src/core/error.hpp"

namespace lzb {

namespace {

std::vector<std::unique_ptr<Method>>& registry() {
  static std::vector<std::unique_ptr<Method>> all = makeRegisteredMethods();
  return all;
}

}  // namespace

const std::vector<std::unique_ptr<Method>>& methods() {
  return registry();
}

void resetMethods() {
  registry() = makeRegisteredMethods();
}

std::string methodNames(bool exactOnly) {
  std::string names;
  for (const auto& m : methods())
    if (!exactOnly || m->exact()) names += (names.empty() ? "" : " | ") + m->name();
  return names;
}

Method& methodNamed(const std::string& name, const std::string& field) {
  for (const auto& m : methods())
    if (m->name() == name) return *m;
  throw InputError(field + ": unknown method '" + name + "' (known: " + methodNames() + ")");
}

Method& exactMethodNamed(const std::string& name, const std::string& field) {
  Method& m = methodNamed(name, field);
  require(m.exact(), field,
          "'" + name + "' is not an exact method (exact: " + methodNames(true) + ")");
  return m;
}

}  // namespace lzb
