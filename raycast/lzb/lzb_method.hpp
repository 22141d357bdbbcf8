#pragma once
// --method lzb: the local z-buffering method's options, validation, report parameters and
// factory (the method contract of src/core/method.hpp).
#include <memory>
#include <string>

#include "src/core/method.hpp"

namespace lzb::localz {

std::unique_ptr<Method> makeLzbMethod();
// --tile-deal, shared by the methods that cast lzb's far rays (lzb, hybrid).
void addTileDealOption(CLI::App& c, std::string& value);

}  // namespace lzb::localz
