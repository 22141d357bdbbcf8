// Every registered method (src/core/method.hpp) against the contracts all of them keep: the same
// frames for 1 and 2 threads; the shares of 2 and 3 ranks, composited by the one (depth, ID)
// rule, give the 1-rank frames; the report carries the common fields. Parameterised over
// makeRegisteredMethods(), so a method is covered as soon as it registers.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "src/core/method.hpp"
#include "src/core/shading.hpp"
#include "src/core/system.hpp"
#include "src/scene/load.hpp"
#include "tests/support/cameras.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/render.hpp"

namespace lzb::test {
namespace {

std::vector<std::string> registeredNames() {
  std::vector<std::string> names;
  for (const auto& m : makeRegisteredMethods()) names.push_back(m->name());
  return names;
}

// A fresh renderer of `method` with its default options.
std::unique_ptr<Renderer> makeRenderer(const std::string& method, const Scene& scene, int threads) {
  for (auto& m : makeRegisteredMethods())
    if (m->name() == method) {
      m->validate();
      RenderOptions o;
      o.method = method;
      o.threads = threads;
      o.quiet = true;
      return m->create(scene, o);
    }
  ADD_FAILURE() << "no method " << method;
  return nullptr;
}

constexpr int kFrames = 2;  // consecutive frames: state kept between frames (plane reuse, caches)

// Frame f of 8 on the default path, small.
Camera frameCamera(const Scene& scene, int f) {
  return pathFrame(scene, f, 8, 96, 72);
}

// The frames one renderer gives as share `share` (depth and ID; colour too when it is not a
// function of the IDs).
std::vector<Framebuffer> renderFrames(Renderer& r, const Scene& scene, WorkShare share) {
  std::vector<Framebuffer> out;
  for (int f = 0; f < kFrames; ++f) {
    out.push_back(renderFrame(r, frameCamera(scene, f), nullptr, share, f));
  }
  return out;
}

// Colour from the IDs, as the frame driver gives it at the root after compositing.
void shadeFrames(const Renderer& r, const Scene& scene, std::vector<Framebuffer>& frames) {
  if (!r.colourFromIds()) return;
  for (int f = 0; f < kFrames; ++f) shadeFromIds(scene, frameCamera(scene, f), frames[size_t(f)]);
}

void expectSameFrame(const Framebuffer& a, const Framebuffer& b, const std::string& what) {
  EXPECT_EQ(a.id, b.id) << what;
  EXPECT_EQ(a.depth, b.depth) << what;
  EXPECT_EQ(a.color, b.color) << what;
}

const std::vector<std::string>& scenes() {
  // A flat scene of many nodes and a deeply instanced one.
  static const std::vector<std::string> s = {"builtin:city?blocks=3", "builtin:sphereflake?depth=2"};
  return s;
}

class MethodConformance : public ::testing::TestWithParam<std::string> {};

TEST_P(MethodConformance, SameFramesForOneAndTwoThreads) {
  for (const std::string& name : scenes()) {
    const Scene scene = loadScene(name, true);
    auto one = makeRenderer(GetParam(), scene, 1);
    auto two = makeRenderer(GetParam(), scene, 2);
    auto a = renderFrames(*one, scene, {}), b = renderFrames(*two, scene, {});
    shadeFrames(*one, scene, a);
    shadeFrames(*two, scene, b);
    for (int f = 0; f < kFrames; ++f) {
      EXPECT_GT(a[size_t(f)].coveredCount(), 0u) << name;
      expectSameFrame(a[size_t(f)], b[size_t(f)], name + " frame " + std::to_string(f));
    }
  }
}

TEST_P(MethodConformance, CompositedSharesOfTwoAndThreeRanksEqualOneRank) {
  for (const std::string& name : scenes()) {
    const Scene scene = loadScene(name, true);
    auto alone = makeRenderer(GetParam(), scene, 2);
    auto single = renderFrames(*alone, scene, {});
    shadeFrames(*alone, scene, single);
    for (int size : {2, 3}) {
      std::vector<Framebuffer> composite;
      for (int rank = 0; rank < size; ++rank) {
        // One renderer per rank, as every rank of a run has its own.
        auto renderer = makeRenderer(GetParam(), scene, 1);
        const auto part = renderFrames(*renderer, scene, {rank, size});
        for (int f = 0; f < kFrames; ++f) {
          if (rank == 0) composite.push_back(part[size_t(f)]);
          else compositeNearer(composite[size_t(f)], part[size_t(f)]);
        }
        if (rank == size - 1) shadeFrames(*renderer, scene, composite);
      }
      for (int f = 0; f < kFrames; ++f)
        expectSameFrame(composite[size_t(f)], single[size_t(f)],
                        name + " frame " + std::to_string(f) + " on " + std::to_string(size) + " ranks");
    }
  }
}

TEST_P(MethodConformance, ReportCarriesTheCommonFields) {
  const std::filesystem::path out = freshDir("conformance_" + GetParam());
  const RunResult r = runLzb("render 'builtin:city?blocks=2' --method " + GetParam() +
                             " --reference raycast --frames 2 --width 64 --height 48 --threads 1 "
                             "--quiet --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json rep = readJson(out / "report.json");
  EXPECT_EQ(rep["method"], GetParam());
  EXPECT_TRUE(rep["method_parameters"].is_object());
  EXPECT_FALSE(rep["decomposition"].get<std::string>().empty());
  EXPECT_EQ(rep["ranks"], 1);
  EXPECT_EQ(rep["threads"], 1);
  EXPECT_EQ(rep["width"], 64);
  EXPECT_EQ(rep["height"], 48);
  EXPECT_TRUE(rep["setup"]["stages"].is_object());
  EXPECT_TRUE(rep["setup"]["counts"].is_object());
  // What the rank's peak cost a triangle it holds (the scene's, replicated).
  const nlohmann::json& rank = rep["setup"]["ranks"][0];
  EXPECT_DOUBLE_EQ(rank["peak_bytes_per_unique_triangle"].get<double>(),
                   rank["peak_memory_bytes"].get<double>() /
                       rank["counts"]["held_unique_triangles"].get<double>());
  EXPECT_GT(rep["summary"]["median_frame_seconds"].get<double>(), 0.0);
  ASSERT_EQ(rep["frames"].size(), 2u);
  for (const auto& f : rep["frames"]) {
    EXPECT_GT(f["seconds"].get<double>(), 0.0);
    EXPECT_FALSE(f["stages"].empty());
    EXPECT_TRUE(f["stages"].contains("composite"));
    EXPECT_TRUE(f["counts"].is_object());
    EXPECT_GT(f["peak_memory_bytes"].get<double>(), 0.0);
    EXPECT_TRUE(f["bytes_sent"].is_number());
    EXPECT_GT(f["covered_pixels"].get<double>(), 0.0);
    ASSERT_EQ(f["ranks"].size(), 1u);
    EXPECT_TRUE(f["ranks"][0]["stages"].is_object());
    EXPECT_TRUE(f["accuracy"].is_object());
    EXPECT_TRUE(f["reference_seconds"].is_number());
    EXPECT_TRUE(f["camera"].is_object());
  }
  EXPECT_TRUE(std::filesystem::exists(out / "frame_0001.png"));
  EXPECT_TRUE(std::filesystem::exists(out / "frame_0001.exr"));
}

// The method_parameters of `lzb render` on a small frame with `options` (which hold
// --quality `quality`, or none when it is empty).
nlohmann::json methodParameters(const std::string& method, const std::string& options,
                                const std::string& quality, const std::string& name) {
  const auto out = freshDir("preset_" + method + "_" + name);
  const RunResult r = runLzb("render 'builtin:city?blocks=2' --method " + method +
                             " --width 48 --height 36 --quiet " + options + " --out " + out.string());
  EXPECT_EQ(r.status, 0) << options << "\n" << r.output;
  const nlohmann::json rep = readJson(out / "report.json");
  EXPECT_EQ(rep["parameters"]["quality"],
            quality.empty() ? nlohmann::json(nullptr) : nlohmann::json(quality));
  return rep["method_parameters"];
}

// The preset's options as a command line.
std::string asOptions(const std::vector<PresetOption>& preset) {
  std::string s;
  for (const PresetOption& o : preset) s += " '--" + o.name + "=" + o.value + "'";
  return s;
}

// --quality q sets exactly the options the method's preset names (the render runs with them and
// reports them as if typed), options typed on the command line win over the preset, and a
// method with a trade to make has presets that differ.
TEST_P(MethodConformance, QualityPresetsSetTheirOptionsAndTypedOptionsWin) {
  std::unique_ptr<Method> method;
  for (auto& m : makeRegisteredMethods())
    if (m->name() == GetParam()) method = std::move(m);
  ASSERT_TRUE(method);
  const Quality levels[] = {Quality::kFast, Quality::kBalanced, Quality::kExact};
  const char* names[] = {"fast", "balanced", "exact"};
  std::vector<nlohmann::json> got;
  for (int k = 0; k < 3; ++k) {
    const std::vector<PresetOption> preset = method->preset(levels[k]);
    got.push_back(methodParameters(GetParam(), std::string("--quality ") + names[k], names[k], names[k]));
    EXPECT_EQ(got.back(), methodParameters(GetParam(), asOptions(preset), "",
                                           std::string(names[k]) + "_typed"));
  }
  const std::vector<PresetOption> fast = method->preset(Quality::kFast);
  const std::vector<PresetOption> exact = method->preset(Quality::kExact);
  EXPECT_EQ(fast.empty(), method->exact() || GetParam() == "lzb");
  if (fast.empty()) return;
  EXPECT_NE(got[0], got[2]) << "fast and exact presets give the same options";
  EXPECT_EQ(methodParameters(GetParam(), "--quality fast" + asOptions(exact), "fast",
                             "fast_then_exact"),
            got[2]);
}

INSTANTIATE_TEST_SUITE_P(Registered, MethodConformance, ::testing::ValuesIn(registeredNames()),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace lzb::test
