#pragma once
// The program's --method values: every registered method (src/core/method.hpp), made once (and
// anew for each render of a batch).
#include <memory>
#include <string>
#include <vector>

#include "src/core/method.hpp"

namespace lzb {

const std::vector<std::unique_ptr<Method>>& methods();
// Makes every method anew, its options at their defaults (a batch's next render parses into them).
// References from methodNamed() die with it.
void resetMethods();
// The method called `name`; throws InputError naming `field` (with the known names) otherwise.
Method& methodNamed(const std::string& name, const std::string& field);
// The exact method called `name` (a --reference); throws InputError naming `field` otherwise.
Method& exactMethodNamed(const std::string& name, const std::string& field);
// "a | b | c" over the method names (exact ones only when asked), for --help.
std::string methodNames(bool exactOnly = false);

}  // namespace lzb
