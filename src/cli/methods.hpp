#pragma once
// The program's --method values: every registered method (src/core/method.hpp), made once.
#include <memory>
#include <string>
#include <vector>

#include "src/core/method.hpp"

namespace lzb {

const std::vector<std::unique_ptr<Method>>& methods();
// The method called `name`; throws InputError naming `field` (with the known names) otherwise.
Method& methodNamed(const std::string& name, const std::string& field);
// The exact method called `name` (a --reference); throws InputError naming `field` otherwise.
Method& exactMethodNamed(const std::string& name, const std::string& field);
// "a | b | c" over the method names (exact ones only when asked), for --help.
std::string methodNames(bool exactOnly = false);

}  // namespace lzb
