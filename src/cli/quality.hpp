#pragma once
// --quality fast|balanced|exact: the chosen method's preset (Method::preset) applied to the
// render options the command line left alone.
#include <CLI/CLI.hpp>

#include "src/cli/render_command.hpp"
#include "src/core/method.hpp"

namespace lzb {

// "fast", "balanced" or "exact"; throws InputError naming --quality.
Quality parseQuality(const std::string& text);

// Parses, as `lzb render --NAME=VALUE` would, each option of the preset that `command` (the
// parsed render or sweep command) did not get. No-op without --quality. Throws InputError.
void applyQuality(const CLI::App& command, RenderArgs& args);

}  // namespace lzb
