#include "src/cli/sweep_params.hpp"

#include <algorithm>

#include "src/cli/render_setup.hpp"
#include "src/core/error.hpp"

namespace lzb {

namespace {

// Render options a sweep may vary: they change neither the frames nor their reference.
const std::vector<std::string> kSweepableRenderOptions = {"threads", "seed", "composite"};

std::vector<std::string> split(const std::string& list, char separator) {
  std::vector<std::string> parts;
  size_t start = 0;
  for (size_t at; (at = list.find(separator, start)) != std::string::npos; start = at + 1)
    parts.push_back(list.substr(start, at - start));
  parts.push_back(list.substr(start));
  return parts;
}

SweptParam parseParam(const std::string& text) {
  const std::string where = "--param " + text;
  const size_t eq = text.find('=');
  require(eq != std::string::npos && eq > 0, where, "expected NAME=V1,V2,... (e.g. splat=1,2,4)");
  SweptParam p{text.substr(0, eq), {}};
  const std::string list = text.substr(eq + 1);
  require(!list.empty(), where, "the value list is empty");
  p.values = split(list, list.find(';') != std::string::npos ? ';' : ',');
  for (size_t i = 0; i < p.values.size(); ++i) {
    require(!p.values[i].empty(), where, "value " + std::to_string(i + 1) + " is empty");
    require(std::count(p.values.begin(), p.values.end(), p.values[i]) == 1, where,
            "value '" + p.values[i] + "' is listed twice");
  }
  return p;
}

}  // namespace

uint64_t SweepGrid::count() const {
  uint64_t n = 1;
  for (const SweptParam& p : params) n *= p.values.size();  // bounded by parseSweepGrid
  return n;
}

std::vector<std::string> SweepGrid::values(uint64_t k) const {
  std::vector<std::string> v(params.size());
  for (size_t i = params.size(); i-- > 0;) {
    v[i] = params[i].values[k % params[i].values.size()];
    k /= params[i].values.size();
  }
  return v;
}

std::string SweepGrid::label(uint64_t k) const {
  const std::vector<std::string> v = values(k);
  std::string s;
  for (size_t i = 0; i < params.size(); ++i) s += (i ? " " : "") + params[i].name + "=" + v[i];
  return s;
}

SweepGrid parseSweepGrid(const std::vector<std::string>& texts) {
  require(!texts.empty(), "--param", "give at least one NAME=V1,V2,...");
  SweepGrid grid;
  uint64_t combinations = 1;
  for (const std::string& text : texts) {
    SweptParam p = parseParam(text);
    for (const SweptParam& q : grid.params)
      require(q.name != p.name, "--param " + text, "'" + p.name + "' is swept twice");
    combinations *= p.values.size();  // each factor <= the text's length: no overflow first
    require(combinations <= kMaxCombinations, "--param " + text,
            "more than " + std::to_string(kMaxCombinations) + " combinations in all");
    grid.params.push_back(std::move(p));
  }
  return grid;
}

std::vector<std::string> sweepableNames(Method& method) {
  CLI::App probe;
  method.addOptions(probe);
  std::vector<std::string> names;
  for (const CLI::Option* o : probe.get_options())
    for (const std::string& n : o->get_lnames())
      if (n != "help") names.push_back(n);
  names.insert(names.end(), kSweepableRenderOptions.begin(), kSweepableRenderOptions.end());
  return names;
}

void checkSweepNames(const SweepGrid& grid, Method& method, const CLI::App& command) {
  const std::vector<std::string> names = sweepableNames(method);
  std::string known;
  for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
  for (const SweptParam& p : grid.params) {
    const std::string where = "--param " + p.name;
    require(std::find(names.begin(), names.end(), p.name) != names.end(), where,
            "--method " + method.name() + " cannot sweep '" + p.name + "' (it can: " + known + ")");
    const CLI::Option* plain = command.get_option_no_throw("--" + p.name);
    require(!plain || plain->count() == 0, where, "also given as --" + p.name + "; give it once");
  }
}

RenderArgs applyCombination(const RenderArgs& base, const SweepGrid& grid, uint64_t k) {
  RenderArgs args = base;
  std::vector<std::string> options;
  const std::vector<std::string> values = grid.values(k);
  for (size_t i = 0; i < values.size(); ++i)
    options.push_back("--" + grid.params[i].name + "=" + values[i]);
  const std::string where = "--param " + grid.label(k);
  parseRenderOverrides(args, options, where);
  try {
    validateRenderArgs(args);
  } catch (const InputError& e) {
    throw InputError(where + ": " + e.what());
  }
  return args;
}

}  // namespace lzb
