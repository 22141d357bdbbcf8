// The lzb program end to end: exact references agree, reports are complete, bad input is refused.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "tests/cli_runner.hpp"

namespace lzb::test {
namespace {

namespace fs = std::filesystem;

// Renders SCENE with zbuffer against the raycast reference and returns frame 0's accuracy.
nlohmann::json zbufferVsRaycast(const std::string& scene, const std::string& name,
                                const std::string& extra = "") {
  const fs::path out = freshDir(name);
  const RunResult r = runLzb("render '" + scene + "' --method zbuffer --reference raycast --quiet --out " +
                             out.string() + " " + extra);
  EXPECT_EQ(r.status, 0) << r.output;
  if (r.status != 0) return nullptr;
  const nlohmann::json report = readJson(out / "report.json");
  EXPECT_TRUE(fs::exists(out / "frame_0000.png"));
  EXPECT_TRUE(fs::exists(out / "frame_0000.exr"));
  const nlohmann::json& frame = report["frames"][0];
  EXPECT_GT(frame["covered_pixels"].get<double>(), 0.0) << scene;
  return frame["accuracy"];
}

struct ExactCase {
  std::string name, scene, extra;
};
void PrintTo(const ExactCase& c, std::ostream* os) { *os << c.scene; }

class ExactReferencesAgree : public ::testing::TestWithParam<ExactCase> {};

TEST_P(ExactReferencesAgree, OnAtLeast995PermilleOfPixels) {
  const ExactCase& c = GetParam();
  std::string scene = c.scene;
  if (scene.rfind("builtin:", 0) != 0) {
    scene = (dataDir() / scene).string();
    if (!fs::exists(scene)) GTEST_SKIP() << scene << " missing: run scripts/fetch-test-meshes.sh";
  }
  const nlohmann::json acc = zbufferVsRaycast(scene, "exact_" + c.name, c.extra);
  ASSERT_FALSE(acc.is_null());
  EXPECT_GE(acc["correct_pixel_rate"].get<double>(), 0.995) << acc.dump();
  EXPECT_GE(acc["exact_id_rate"].get<double>(), 0.99) << acc.dump();
  RecordProperty("correct_pixel_rate", std::to_string(acc["correct_pixel_rate"].get<double>()));
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, ExactReferencesAgree,
    ::testing::Values(ExactCase{"city", "builtin:city", ""},
                      ExactCase{"sphereflake", "builtin:sphereflake", ""},
                      ExactCase{"chessboard", "builtin:chessboard?n=256", ""},
                      ExactCase{"forest", "builtin:forest?levels=1", ""},
                      ExactCase{"bunny", "bunny00.off", ""},
                      ExactCase{"armadillo", "armadillo.off", ""},
                      ExactCase{"elephant", "elephant.off", ""},
                      ExactCase{"fandisk", "fandisk.off", ""},
                      ExactCase{"dragon", "ChineseDragon-10kv.off", ""}),
    [](const auto& info) { return info.param.name; });

TEST(Render, ReportHasParametersStagesCountsAndMemory) {
  const fs::path out = freshDir("report");
  const RunResult r =
      runLzb("render builtin:sphereflake --frames 3 --width 96 --height 64 --quiet --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("frame time"), std::string::npos) << r.output;
  const nlohmann::json rep = readJson(out / "report.json");
  EXPECT_EQ(rep["method"], "zbuffer");
  EXPECT_EQ(rep["width"], 96);
  EXPECT_EQ(rep["height"], 64);
  EXPECT_EQ(rep["ranks"], 1);
  EXPECT_GE(rep["threads"].get<int>(), 1);
  EXPECT_GT(rep["scene"]["triangles_unique"].get<double>(), 0.0);
  EXPECT_GE(rep["scene"]["triangles_expanded"].get<double>(), rep["scene"]["triangles_unique"].get<double>());
  ASSERT_EQ(rep["frames"].size(), 3u);
  for (const auto& f : rep["frames"]) {
    EXPECT_GT(f["seconds"].get<double>(), 0.0);
    EXPECT_FALSE(f["stages"].empty());
    EXPECT_GT(f["peak_memory_bytes"].get<double>(), 0.0);
    EXPECT_EQ(f["ranks"].size(), 1u);
  }
  // The camera circles: frames differ.
  EXPECT_NE(rep["frames"][0]["camera"]["position"], rep["frames"][1]["camera"]["position"]);
  for (int f = 0; f < 3; ++f) EXPECT_TRUE(fs::exists(out / ("frame_000" + std::to_string(f) + ".exr")));
}

TEST(Compare, PrintsMetricsOfTwoImages) {
  const fs::path a = freshDir("compare_a"), b = freshDir("compare_b");
  ASSERT_EQ(runLzb("render builtin:sphereflake --width 64 --height 48 --quiet --out " + a.string()).status, 0);
  ASSERT_EQ(runLzb("render builtin:sphereflake --method raycast --width 64 --height 48 --quiet --out " +
                   b.string()).status, 0);
  const RunResult same = runLzb("compare " + (a / "frame_0000.exr").string() + " " +
                                (a / "frame_0000.exr").string());
  ASSERT_EQ(same.status, 0) << same.output;
  const nlohmann::json s = nlohmann::json::parse(same.output);
  EXPECT_DOUBLE_EQ(s["correct_pixel_rate"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(s["rmse"].get<double>(), 0.0);
  const RunResult diff = runLzb("compare " + (a / "frame_0000.exr").string() + " " +
                                (b / "frame_0000.exr").string());
  ASSERT_EQ(diff.status, 0) << diff.output;
  EXPECT_GT(nlohmann::json::parse(diff.output)["correct_pixel_rate"].get<double>(), 0.99);
}

TEST(Info, CountsInstancedTrianglesAndBuildsOctrees) {
  const RunResult r = runLzb("info 'builtin:chessboard?n=1048576' --json --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json info = nlohmann::json::parse(r.output);
  EXPECT_GE(info["triangles_expanded"].get<double>(), 1e12);
  EXPECT_LT(info["triangles_unique"].get<double>(), 1e5);
  ASSERT_FALSE(info["octrees"].empty());
  EXPECT_GT(info["octrees"][0]["leaves"].get<double>(), 0.0);
  EXPECT_GT(info["memory"]["scene_bytes"].get<double>(), 0.0);
}

// Bad input: a clear message naming what is wrong, exit status 2, and no output written.
struct BadCase {
  std::string name, args, mustMention;
};
void PrintTo(const BadCase& c, std::ostream* os) { *os << c.args; }

class BadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadInput, ExitsWithStatus2AndWritesNothing) {
  const BadCase& c = GetParam();
  const fs::path dir = freshDir("bad_" + c.name);
  // Input files the cases refer to.
  std::ofstream(dir / "malformed.obj") << "v 0 0 0\nv 1 0 0\nf 1 2 9\nthis is not obj\n";
  std::ofstream(dir / "truncated.ply") << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                          "property float y\nproperty float z\nelement face 1\n"
                                          "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0";
  std::ofstream(dir / "nan.off") << "OFF\n3 1 0\nnan 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  std::ofstream(dir / "degenerate.off") << "OFF\n3 1 0\n0 0 0\n1 1 1\n2 2 2\n3 0 1 2\n";
  std::ofstream(dir / "empty.obj") << "# nothing\n";
  std::ofstream(dir / "bad.toml") << "[camera]\nposition = [0, 0, 5]\nnear = -1\n[[mesh]]\nname = 3\n";
  std::string args = c.args;
  for (size_t p; (p = args.find("DIR")) != std::string::npos;) args.replace(p, 3, dir.string());
  const fs::path out = dir / "out";
  if (args.find("--out") == std::string::npos) args += " --out " + out.string();
  const RunResult r = runLzb(args + " --quiet");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find(c.mustMention), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("error"), std::string::npos) << r.output;
  if (fs::exists(out)) {
    EXPECT_TRUE(fs::is_empty(out)) << "partial output left in " << out;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BadInput,
    ::testing::Values(
        BadCase{"missing_file", "render DIR/nope.ply", "nope.ply"},
        BadCase{"malformed", "render DIR/malformed.obj", "malformed.obj"},
        BadCase{"truncated", "render DIR/truncated.ply", "truncated.ply"},
        BadCase{"only_nan", "render DIR/nan.off", "nan.off"},
        BadCase{"only_degenerate", "render DIR/degenerate.off", "degenerate.off"},
        BadCase{"empty", "render DIR/empty.obj", "empty.obj"},
        BadCase{"bad_toml", "render DIR/bad.toml", "bad.toml"},
        BadCase{"unknown_builtin", "render builtin:teapot", "teapot"},
        BadCase{"unknown_method", "render builtin:sphereflake --method magic", "--method"},
        BadCase{"unknown_option", "render builtin:sphereflake --frobnicate 3", "frobnicate"},
        BadCase{"width_zero", "render builtin:sphereflake --width 0", "width"},
        BadCase{"width_huge", "render builtin:sphereflake --width 100000", "width"},
        BadCase{"near_negative", "render builtin:sphereflake --near -1", "near"},
        BadCase{"near_beyond_far", "render builtin:sphereflake --near 10 --far 5", "far"},
        BadCase{"frames_zero", "render builtin:sphereflake --frames 0", "frames"},
        BadCase{"unwritable_out", "render builtin:sphereflake --out /proc/lzb-cannot-write", "--out"}),
    [](const auto& info) { return info.param.name; });

}  // namespace
}  // namespace lzb::test
