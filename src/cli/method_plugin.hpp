#pragma once
// How a rendering method plugs into the CLI: its own options on `lzb render`, their validation,
// their record in report.json, and its renderer factory. Each method folder defines one function
// returning its MethodPlugin (the option values live in storage the plugin owns).
#include <functional>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "src/core/renderer.hpp"

namespace lzb {

struct MethodPlugin {
  std::string name;                              // the --method value
  std::string summary;                           // one line for --help
  std::function<void(CLI::App&)> addOptions;     // may add nothing
  std::function<void()> validate;                // throws InputError naming the option
  std::function<nlohmann::json()> parameters;    // the method's option values, for the report
  std::function<std::unique_ptr<Renderer>(const Scene&, const RenderOptions&)> create;
};

}  // namespace lzb
