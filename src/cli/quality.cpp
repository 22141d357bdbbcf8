#include "src/cli/quality.hpp"

#include <string>
#include <vector>

#include "src/cli/methods.hpp"
#include "src/core/error.hpp"

namespace lzb {

Quality parseQuality(const std::string& text) {
  if (text == "fast") return Quality::kFast;
  if (text == "balanced") return Quality::kBalanced;
  if (text == "exact") return Quality::kExact;
  throw InputError("--quality: expected fast, balanced or exact, got '" + text + "'");
}

void applyQuality(const CLI::App& command, RenderArgs& args) {
  if (args.quality.empty()) return;
  const Quality q = parseQuality(args.quality);
  std::vector<std::string> options;
  for (const PresetOption& o : methodNamed(args.method, "--method").preset(q)) {
    const CLI::Option* given = command.get_option_no_throw("--" + o.name);
    if (!given || given->count() == 0) options.push_back("--" + o.name + "=" + o.value);
  }
  if (!options.empty()) parseRenderOverrides(args, options, "--quality " + args.quality);
}

}  // namespace lzb
