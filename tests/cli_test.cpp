// The lzb program end to end: exact references agree, reports are complete, bad input is refused.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <string>
#include <utility>

#include "src/image/frame_io.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/files.hpp"
#include "tests/support/meshes.hpp"

namespace lzb::test {
namespace {

namespace fs = std::filesystem;

// A built-in scene as it is, with "<data>/" naming the real-mesh folder; a mesh file from that
// folder; or "" when a mesh it needs is missing.
std::string sceneSpec(const std::string& scene) {
  const std::string data = "<data>/";
  if (scene.rfind("builtin:", 0) == 0) {
    const size_t at = scene.find(data);
    if (at == std::string::npos) return scene;
    const size_t end = scene.find('&', at);
    const std::string file = scene.substr(at + data.size(), end - at - data.size());
    if (!fs::exists(dataDir() / file)) return "";
    return scene.substr(0, at) + dataDir().string() + "/" + scene.substr(at + data.size());
  }
  const fs::path file = dataDir() / scene;
  return fs::exists(file) ? file.string() : "";
}

// The instanced armadillo field: 1024 scanned armadillos, about 100 triangles of 0.002 px^2 per
// pixel at 320x240, most of them visible in a pixel without touching any of its 17 samples.
const std::string kSubpixelField = "builtin:replicated?mesh=<data>/armadillo.off&k=32&levels=1";

// Renders SCENE with METHOD against the REFERENCE method and returns frame 0's accuracy.
nlohmann::json accuracyOf(const std::string& scene, const std::string& method,
                          const std::string& reference, const std::string& name,
                          const std::string& extra = "") {
  const fs::path out = freshDir(name);
  const RunResult r = runLzb("render '" + scene + "' --method " + method + " --reference " +
                             reference + " --quiet --out " + out.string() + " " + extra);
  EXPECT_EQ(r.status, 0) << r.output;
  if (r.status != 0) return nullptr;
  EXPECT_NE(r.output.find("correct (covered pixels) >= "), std::string::npos) << r.output;
  const nlohmann::json report = readJson(out / "report.json");
  EXPECT_TRUE(fs::exists(out / "frame_0000.png"));
  EXPECT_TRUE(fs::exists(out / "frame_0000.exr"));
  const nlohmann::json& frame = report["frames"][0];
  EXPECT_GT(frame["covered_pixels"].get<double>(), 0.0) << scene;
  EXPECT_EQ(report["summary"]["min_correct_rate_covered"], frame["accuracy"]["correct_rate_covered"]);
  EXPECT_EQ(frame["accuracy"]["witness"], "rays");
  EXPECT_EQ(report["witness"]["rule"], "rays");
  EXPECT_TRUE(frame["accuracy_seconds"].is_number());
  return frame["accuracy"];
}

struct ExactCase {
  std::string name, scene, extra;
  std::string method = "zbuffer", reference = "raycast";
  double exactIdRate = 0.99;  // the least share of covered pixels with the reference's centre ID
};
void PrintTo(const ExactCase& c, std::ostream* os) {
  *os << c.scene << " " << c.method << " vs " << c.reference;
}

class ExactReferencesAgree : public ::testing::TestWithParam<ExactCase> {};

// One exact method against the other: >= 99.5 % of covered pixels show a triangle visible in the
// pixel (one of the reference's 17 samples, or proven by the ray witness), >= 99 % the
// reference's centre triangle.
TEST_P(ExactReferencesAgree, OnAtLeast995PermilleOfCoveredPixels) {
  const ExactCase& c = GetParam();
  const std::string scene = sceneSpec(c.scene);
  if (scene.empty()) GTEST_SKIP() << c.scene << ": mesh missing, run scripts/fetch-test-meshes.sh";
  const nlohmann::json acc = accuracyOf(scene, c.method, c.reference, "exact_" + c.name, c.extra);
  ASSERT_FALSE(acc.is_null());
  EXPECT_EQ(acc["reference_samples_per_pixel"], 17);
  EXPECT_GE(acc["correct_rate_covered"].get<double>(), 0.995) << acc.dump();
  EXPECT_GE(acc["exact_id_rate_covered"].get<double>(), c.exactIdRate) << acc.dump();
  RecordProperty("correct_rate_covered", std::to_string(acc["correct_rate_covered"].get<double>()));
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
                      ExactCase{"dragon", "ChineseDragon-10kv.off", ""},
                      // llvmpipe snaps vertices to 1/256 pixel, Embree does not: on triangles of
                      // 0.002 px^2, 2.2 % of the pixel centres show different triangles.
                      ExactCase{"field", kSubpixelField, "--width 320 --height 240", "zbuffer",
                                "raycast", 0.97},
                      ExactCase{"field_reversed", kSubpixelField, "--width 320 --height 240",
                                "raycast", "zbuffer", 0.97}),
    [](const auto& info) { return info.param.name; });

// The randomized z-buffer at d = 1 (one-pixel splats) on sub-pixel geometry: the 17 samples alone
// give 18 %, the witnessed figure of the report >= 95 %.
TEST(RzbOnTheSubpixelField, ShowsAVisibleTriangleOnAtLeast95PercentOfCoveredPixels) {
  const std::string scene = sceneSpec(kSubpixelField);
  if (scene.empty()) GTEST_SKIP() << "armadillo.off missing, run scripts/fetch-test-meshes.sh";
  const nlohmann::json acc = accuracyOf(scene, "rzb", "raycast", "rzb_field",
                                        "--splat 1 --width 320 --height 240");
  ASSERT_FALSE(acc.is_null());
  EXPECT_GE(acc["correct_rate_covered"].get<double>(), 0.95) << acc.dump();
  // Most of it is proven by rays: the 17 samples alone would fail the bar by far.
  const double seventeen = acc["correct_covered_pixels"].get<double>() - acc["witnessed_pixels"].get<double>();
  EXPECT_LT(seventeen / acc["covered_pixels"].get<double>(), 0.5) << acc.dump();
  RecordProperty("correct_rate_covered", std::to_string(acc["correct_rate_covered"].get<double>()));
}

TEST(Render, ReportHasParametersStagesCountsAndMemory) {
  const fs::path out = freshDir("report");
  const RunResult r =
      runLzb("render builtin:sphereflake --frames 3 --width 96 --height 64 --quiet --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("frame time"), std::string::npos) << r.output;
  const nlohmann::json rep = readJson(out / "report.json");
  EXPECT_EQ(rep["method"], "hybrid");  // the default
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

// --bvh compact: Embree's leaves index the vertices; the same images (IDs, colours, depths on
// this scene) with fewer bytes counted, for raycast and for the hybrid's Embree scene.
TEST(Render, CompactBvhGivesTheSameImagesWithFewerBytes) {
  for (const char* method : {"raycast", "hybrid"}) {
    std::map<std::string, nlohmann::json> setup;
    for (const char* bvh : {"fast", "compact"}) {
      const fs::path out = freshDir(std::string("bvh_") + method + "_" + bvh);
      const RunResult r =
          runLzb("render builtin:sphereflake --frames 2 --width 96 --height 64 --method " +
                 std::string(method) + " --bvh " + bvh + " --quiet --out " + out.string());
      ASSERT_EQ(r.status, 0) << r.output;
      const nlohmann::json rep = readJson(out / "report.json");
      EXPECT_EQ(rep["parameters"]["bvh"], bvh);
      setup[bvh] = rep["setup"]["counts"];
    }
    EXPECT_LT(setup["compact"]["embree_bytes"].get<double>(),
              0.8 * setup["fast"]["embree_bytes"].get<double>())
        << method;
    for (const char* f : {"frame_0000.png", "frame_0001.png", "frame_0000.exr", "frame_0001.exr"})
      EXPECT_EQ(fileBytes(workDir() / (std::string("bvh_") + method + "_fast") / f),
                fileBytes(workDir() / (std::string("bvh_") + method + "_compact") / f))
          << method << " " << f;
  }
}

// The report says whose Embree scene the witness traces: the raycast reference's, else its own
// (built at set-up, within setup_seconds).
TEST(Render, ReportsWhereTheWitnessRaysAreTraced) {
  for (const auto& [reference, embree] : {std::pair{"raycast", "the raycast reference's"},
                                          std::pair{"zbuffer", "built for the witness"}}) {
    const fs::path out = freshDir(std::string("witness_") + reference);
    const RunResult r = runLzb("render builtin:sphereflake --width 64 --height 48 --reference " +
                               std::string(reference) + " --quiet --out " + out.string());
    ASSERT_EQ(r.status, 0) << r.output;
    const nlohmann::json rep = readJson(out / "report.json");
    EXPECT_EQ(rep["witness"]["rule"], "rays");
    EXPECT_EQ(rep["witness"]["embree_scene"], embree);
    const double build = rep["witness"]["build_seconds"].get<double>();
    EXPECT_EQ(build > 0.0, std::string(reference) == "zbuffer") << build;
    EXPECT_LE(build, rep["setup_seconds"].get<double>());
  }
}

// Renders SCENE at 64x48 with `args` into a fresh folder and returns frame 0's EXR.
fs::path renderSmall(const std::string& name, const std::string& scene, const std::string& args) {
  const fs::path out = freshDir(name);
  const RunResult r = runLzb("render '" + scene + "' --width 64 --height 48 --threads 2 --quiet --out " +
                             out.string() + " " + args);
  EXPECT_EQ(r.status, 0) << r.output;
  return out / "frame_0000.exr";
}

fs::path renderSphereflake(const std::string& name, const std::string& args) {
  return renderSmall(name, "builtin:sphereflake", args);
}

// `lzb compare --scene` gives exactly the report's figures; without --scene, the 17-sample rule.
struct ComparePair {
  std::string name, scene, method, reference;
};
void PrintTo(const ComparePair& c, std::ostream* os) {
  *os << c.scene << " " << c.method << " vs " << c.reference;
}

class CompareFiles : public ::testing::TestWithParam<ComparePair> {};

TEST_P(CompareFiles, WithTheSceneGiveTheReportsAccuracyAndWithoutItTheSeventeenSampleRule) {
  const ComparePair& c = GetParam();
  const fs::path ref = renderSmall("compare_ref_" + c.name, c.scene,
                                   "--method " + c.reference + " --subsamples");
  const fs::path test = renderSmall("compare_test_" + c.name, c.scene,
                                    "--method " + c.method + " --reference " + c.reference);
  const nlohmann::json report = readJson(test.parent_path() / "report.json")["frames"][0]["accuracy"];
  const RunResult withScene =
      runLzb("compare " + test.string() + " " + ref.string() + " --scene '" + c.scene + "' --threads 2");
  ASSERT_EQ(withScene.status, 0) << withScene.output;
  // The same reference rendered twice (exact methods are deterministic), the same rays.
  EXPECT_EQ(nlohmann::json::parse(withScene.output), report);
  EXPECT_EQ(report["witness"], "rays");
  EXPECT_GT(report["witnessed_pixels"].get<double>(), 0.0) << report.dump();

  const RunResult plain = runLzb("compare " + test.string() + " " + ref.string());
  ASSERT_EQ(plain.status, 0) << plain.output;
  const nlohmann::json lower = nlohmann::json::parse(plain.output);
  EXPECT_EQ(lower["witness"], "none");
  EXPECT_EQ(lower["witnessed_pixels"], 0);
  EXPECT_EQ(lower["correct_covered_pixels"].get<size_t>() + report["witnessed_pixels"].get<size_t>(),
            report["correct_covered_pixels"].get<size_t>());
  EXPECT_LT(lower["correct_rate_covered"].get<double>(), report["correct_rate_covered"].get<double>());
  EXPECT_EQ(lower["exact_covered_pixels"], report["exact_covered_pixels"]);
  EXPECT_EQ(lower["rmse_aa"], report["rmse_aa"]);
}

INSTANTIATE_TEST_SUITE_P(
    Pairs, CompareFiles,
    ::testing::Values(ComparePair{"rzb_forest", "builtin:forest?levels=1", "rzb", "raycast"},
                      ComparePair{"raycast_city", "builtin:city", "raycast", "zbuffer"}),
    [](const auto& info) { return info.param.name; });

TEST(Compare, AReferenceAgainstItselfIsCorrectEverywhere) {
  const fs::path ref = renderSphereflake("compare_self", "--method raycast --subsamples");
  const RunResult r = runLzb("compare " + ref.string() + " " + ref.string());
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json s = nlohmann::json::parse(r.output);
  EXPECT_DOUBLE_EQ(s["correct_rate_covered"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(s["exact_id_rate_covered"].get<double>(), 1.0);
  EXPECT_EQ(s["missing_pixels"], 0);
  EXPECT_EQ(s["wrong_pixels"], 0);
  // Centre colours against the box filter: edges differ.
  EXPECT_GT(s["rmse_aa"].get<double>(), 0.0);
}

TEST(Compare, AReferenceWithoutSubsamplesIsRefused) {
  const fs::path plain = renderSphereflake("compare_plain", "");
  const RunResult r = runLzb("compare " + plain.string() + " " + plain.string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find(plain.string()), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--subsamples"), std::string::npos) << r.output;
}

TEST(Compare, WithTheSceneAReferenceWithoutCameraIsRefusedNamingIt) {
  const fs::path test = renderSphereflake("compare_nocam_test", "--method raycast --subsamples");
  // A reference as another tool (or an older lzb) writes it: sub-samples, no header camera.
  const fs::path ref = freshDir("compare_nocam_ref") / "frame_0000.exr";
  writeExr(readFrameExr(test), readReferenceExr(test), ref);
  const RunResult r = runLzb("compare " + test.string() + " " + ref.string() + " --scene builtin:sphereflake");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find(ref.string()), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("camera"), std::string::npos) << r.output;
  // Without --scene it is a reference like any other.
  EXPECT_EQ(runLzb("compare " + test.string() + " " + ref.string()).status, 0);
}

TEST(Compare, AnotherSceneIsRefusedNamingTheOption) {
  const fs::path ref = renderSphereflake("compare_other_scene", "--method raycast --subsamples");
  const RunResult r = runLzb("compare " + ref.string() + " " + ref.string() + " --scene builtin:city");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--scene"), std::string::npos) << r.output;
}

TEST(Compare, FramesOfDifferentCamerasAreRefusedNamingBoth) {
  const fs::path out = freshDir("compare_two_views");
  const RunResult r = runLzb("render builtin:sphereflake --method raycast --subsamples --frames 2 "
                             "--width 64 --height 48 --quiet --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.output;
  const fs::path a = out / "frame_0000.exr", b = out / "frame_0001.exr";
  const RunResult c = runLzb("compare " + a.string() + " " + b.string());
  EXPECT_EQ(c.status, 2) << c.output;
  EXPECT_NE(c.output.find(a.string()), std::string::npos) << c.output;
  EXPECT_NE(c.output.find(b.string()), std::string::npos) << c.output;
}

// lzb culls per leaf and per visible instance: the 2.2 * 10^12-triangle chessboard passes its
// limits at the first frame, where it stops with exit 2 naming the methods that draw the board,
// and the output folder it made is gone (it used to run out of memory instead).
TEST(Render, LzbRefusesASceneTooInstancedToCullAndLeavesNoFolder) {
  const fs::path out = freshDir("too_instanced") / "out";
  const RunResult r = runLzb("render 'builtin:chessboard?n=1048576' --method lzb --frames 2 --quiet --out " +
                             out.string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("too instanced"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("hybrid"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST(Batch, RendersEachLineAsItsOwnRenderWithNoOptionCarriedOver) {
  const fs::path dir = freshDir("batch");
  const std::string render = "'builtin:sphereflake?depth=1' --method rzb --frames 1 --width 32 "
                             "--height 24 --threads 1 --quiet --out ";
  std::ofstream(dir / "jobs.txt") << "# two renders\n" << render << "'" << (dir / "a").string()
                                  << "' --splat 3\n\n" << render << (dir / "b").string() << "\n";
  const RunResult batch = runLzb("batch " + (dir / "jobs.txt").string() + " --quiet");
  ASSERT_EQ(batch.status, 0) << batch.output;
  const RunResult alone = runLzb("render " + render + (dir / "c").string());
  ASSERT_EQ(alone.status, 0) << alone.output;
  EXPECT_EQ(readJson(dir / "a" / "report.json")["method_parameters"]["splat"], 3);
  // The second line left --splat alone: the default again, not the first line's 3.
  EXPECT_EQ(readJson(dir / "b" / "report.json")["method_parameters"]["splat"], 1);
  EXPECT_EQ(fileBytes(dir / "b" / "frame_0000.exr"), fileBytes(dir / "c" / "frame_0000.exr"));
  EXPECT_NE(fileBytes(dir / "a" / "frame_0000.exr"), fileBytes(dir / "c" / "frame_0000.exr"));
}

TEST(Batch, ABadLineIsRefusedNamingItsLineBeforeAnyRender) {
  const fs::path dir = freshDir("batch_bad");
  const fs::path jobs = dir / "jobs.txt";
  std::ofstream(jobs) << "builtin:sphereflake --frames 1 --width 32 --height 24 --out "
                      << (dir / "a").string() << "\n\nbuiltin:sphereflake --frames 0 --out "
                      << (dir / "b").string() << "\n";
  const RunResult r = runLzb("batch " + jobs.string() + " --quiet");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find(jobs.string() + ":3"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("frames"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "a"));
  EXPECT_FALSE(fs::exists(dir / "b"));
  const RunResult missing = runLzb("batch " + (dir / "none.txt").string());
  EXPECT_EQ(missing.status, 2) << missing.output;
  EXPECT_NE(missing.output.find("none.txt"), std::string::npos) << missing.output;
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
  // The model holds at least 3 indices and a colour a unique triangle (16 bytes) besides vertices.
  EXPECT_GE(info["memory"]["scene_bytes_per_triangle"].get<double>(), 16.0);
  EXPECT_DOUBLE_EQ(info["memory"]["scene_bytes_per_triangle"].get<double>(),
                   info["memory"]["scene_bytes"].get<double>() /
                       info["triangles_unique"].get<double>());
}

TEST(Info, EstimatesEachRanksPeakForItsShare) {
  const std::string scene = "info 'builtin:city?blocks=3' --json --quiet --method raycast ";
  const nlohmann::json whole = nlohmann::json::parse(runLzb(scene + "--ranks 2").output);
  const RunResult r = runLzb(scene + "--ranks 3 --distribute data --regions 7");
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json cut = nlohmann::json::parse(r.output);
  const auto& ranks = cut["estimate"]["ranks"];
  ASSERT_EQ(ranks.size(), 3u);
  double held = 0.0;
  for (const auto& rank : ranks) {
    held += rank["triangles"].get<double>();
    EXPECT_LT(rank["peak_bytes"].get<double>(),
              whole["estimate"]["ranks"][0]["peak_bytes"].get<double>());
  }
  EXPECT_EQ(held, cut["triangles_unique"].get<double>()) << "the shares make the scene";
  EXPECT_EQ(whole["estimate"]["ranks"][1]["triangles"], whole["triangles_unique"]);
  // The method's bytes a triangle: the slope of every rank's estimate.
  const double slope = whole["estimate"]["bytes_per_triangle"].get<double>();
  EXPECT_GT(slope, 0.0);
  EXPECT_DOUBLE_EQ(
      ranks[0]["peak_bytes"].get<double>() - ranks[1]["peak_bytes"].get<double>(),
      slope * (ranks[0]["triangles"].get<double>() - ranks[1]["triangles"].get<double>()));
  EXPECT_EQ(runLzb(scene + "--distribute auto").status, 2);
}

// A binary PLY of triangles is read in slices under data: each rank's estimate holds its slice's
// load, which falls as ranks are added, and its peak is never below it.
TEST(Info, EstimatesTheLoadOfASliceReadFilePerRank) {
  const fs::path dir = freshDir("info_sliced");
  const std::string ply = (dir / "city.ply").string();
  ASSERT_EQ(runLzb("export 'builtin:city?blocks=2' " + ply + " --quiet").status, 0);
  const auto estimate = [&](int ranks) {
    const RunResult r = runLzb("info " + ply + " --json --quiet --method raycast --distribute data " +
                               "--ranks " + std::to_string(ranks));
    EXPECT_EQ(r.status, 0) << r.output;
    const nlohmann::json info = nlohmann::json::parse(r.output);
    EXPECT_NE(info["streamed"].get<std::string>().find("read in slices"), std::string::npos);
    return info["estimate"]["ranks"];
  };
  const nlohmann::json one = estimate(1), four = estimate(4);
  ASSERT_TRUE(one[0].contains("load_peak_bytes"));
  EXPECT_LT(four[0]["load_peak_bytes"].get<double>(), one[0]["load_peak_bytes"].get<double>());
  for (const auto& rank : four)
    EXPECT_GE(rank["peak_bytes"].get<double>(), rank["load_peak_bytes"].get<double>());
}

TEST(Limits, MeasuresCopyScatterAndKeyRates) {
  const RunResult r = runLzb("limits --seconds 0.1 --width 64 --height 48 --threads 1");
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(r.output);
  EXPECT_GT(j["memcpy_bytes_per_s"].get<double>(), 1e8);
  EXPECT_GT(j["atomic_min_scatter_per_s"].get<double>(), 1e5);
  EXPECT_GT(j["key_writes_per_s"].get<double>(), 1e6);
  const RunResult bad = runLzb("limits --seconds 0");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.output.find("--seconds"), std::string::npos) << bad.output;
}

TEST(Export, WritesTheExpandedSceneAsAMeshThatRendersTheSame) {
  const fs::path dir = freshDir("export");
  const RunResult r = runLzb("export 'builtin:sphereflake?depth=1' " + (dir / "flake.ply").string() + " --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  // The PLY loads back with every triangle (instances expanded) and renders the same IDs.
  const RunResult info = runLzb("info " + (dir / "flake.ply").string() + " --json --quiet");
  ASSERT_EQ(info.status, 0) << info.output;
  const RunResult orig = runLzb("info 'builtin:sphereflake?depth=1' --json --quiet");
  EXPECT_EQ(nlohmann::json::parse(info.output)["triangles_expanded"],
            nlohmann::json::parse(orig.output)["triangles_expanded"]);
  // Each placed sphere's vertices written once, shared by its faces (a closed sphere holds about
  // half a vertex a triangle), not three a face.
  std::ifstream header(dir / "flake.ply", std::ios::binary);
  uint64_t vertices = 0, faces = 0;
  for (std::string line; std::getline(header, line) && line != "end_header";) {
    if (line.rfind("element vertex ", 0) == 0) vertices = std::stoull(line.substr(15));
    if (line.rfind("element face ", 0) == 0) faces = std::stoull(line.substr(13));
  }
  EXPECT_GT(faces, 0u);
  EXPECT_LT(vertices, faces);
  const RunResult big = runLzb("export 'builtin:chessboard?n=1048576' " + (dir / "big.ply").string() +
                               " --quiet");
  EXPECT_EQ(big.status, 2) << big.output;
  EXPECT_NE(big.output.find("--max-triangles"), std::string::npos) << big.output;
  EXPECT_FALSE(fs::exists(dir / "big.ply"));
}

// Bad input: a clear message naming what is wrong, exit status 2, and no output written.
struct BadCase {
  std::string name, args, mustMention;
  std::string shellPrefix = "";  // e.g. a ulimit for the run
};
void PrintTo(const BadCase& c, std::ostream* os) { *os << c.shellPrefix << c.args; }

// A chain of `n` TOML nodes over one sphere, c0 -> c1 -> ... -> one.
std::string chainToml(int n) {
  std::string s = "root = \"c0\"\n[[generators]]\nname = \"one\"\nspec = \"sphereflake?depth=0\"\n";
  for (int k = 0; k < n; ++k)
    s += "[[nodes]]\nname = \"c" + std::to_string(k) + "\"\ninstances = [{ node = \"" +
         (k + 1 < n ? "c" + std::to_string(k + 1) : std::string("one")) + "\" }]\n";
  return s;
}

// Each level instances the one below 10 times: 10^30 triangles at the root.
std::string hugeToml() {
  std::string s = "root = \"l29\"\n[[generators]]\nname = \"one\"\nspec = \"sphereflake?depth=0\"\n";
  for (int k = 0; k < 30; ++k) {
    s += "[[nodes]]\nname = \"l" + std::to_string(k) + "\"\ninstances = [";
    for (int i = 0; i < 10; ++i)
      s += std::string(i ? ", " : "") + "{ node = \"" + (k ? "l" + std::to_string(k - 1) : "one") + "\" }";
    s += "]\n";
  }
  return s;
}

// The input files the cases name (written only when a case names them).
const std::vector<std::pair<std::string, std::function<std::string()>>>& badFiles() {
  static const std::vector<std::pair<std::string, std::function<std::string()>>> files = {
      {"malformed.obj", [] { return "v 0 0 0\nv 1 0 0\nf 1 2 9\nthis is not obj\n"; }},
      {"truncated.ply",
       [] {
         return "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                "end_header\n0 0 0\n1 0";
       }},
      {"nan.off", [] { return "OFF\n3 1 0\nnan 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"; }},
      {"degenerate.off", [] { return "OFF\n3 1 0\n0 0 0\n1 1 1\n2 2 2\n3 0 1 2\n"; }},
      {"face.off", [] { return "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n18446744073709551615 0 1 2\n"; }},
      {"empty.obj", [] { return "# nothing\n"; }},
      {"bad.toml", [] { return "[camera]\nposition = [0, 0, 5]\nnear = -1\n[[mesh]]\nname = 3\n"; }},
      {"tall.toml",
       [] {
         return "root = \"flake\"\n[image]\nwidth = 64\nheight = 5000\n[[generators]]\n"
                "name = \"flake\"\nspec = \"sphereflake?depth=1\"\n";
       }},
      {"vast.toml",
       [] {
         return "root = \"flake\"\n[image]\nwidth = 16384\nheight = 16384\n[[generators]]\n"
                "name = \"flake\"\nspec = \"sphereflake?depth=1\"\n";
       }},
      {"chain.toml", [] { return chainToml(100000); }},
      {"self.toml",
       [] {
         return "root = \"me\"\n[[generators]]\nname = \"one\"\nspec = \"sphereflake?depth=0\"\n"
                "[[nodes]]\nname = \"me\"\ninstances = [{ node = \"one\" }, { node = \"me\" }]\n";
       }},
      {"huge.toml", hugeToml},
  };
  return files;
}

class BadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadInput, ExitsWithStatus2AndWritesNothing) {
  const BadCase& c = GetParam();
#ifdef LZB_SANITIZE
  if (c.shellPrefix.find("ulimit -v") != std::string::npos)
    GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space: ulimit -v cannot apply";
#endif
  const fs::path dir = freshDir("bad_" + c.name);
  std::string args = c.args;
  for (const auto& [name, text] : badFiles())
    if (args.find("DIR/" + name) != std::string::npos) std::ofstream(dir / name) << text();
  for (size_t p; (p = args.find("DIR")) != std::string::npos;) args.replace(p, 3, dir.string());
  const fs::path out = dir / "out";
  if (args.find("--out") == std::string::npos) args += " --out " + out.string();
  const RunResult r = runLzb(args + " --quiet", c.shellPrefix);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find(c.mustMention), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("error"), std::string::npos) << r.output;
  // Not even the folder: --out is created only after the scene and every option passed.
  EXPECT_FALSE(fs::exists(out)) << "output left in " << out;
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
        BadCase{"unwritable_out", "render builtin:sphereflake --out /proc/lzb-cannot-write",
                "--out"},
        BadCase{"reference_unknown", "render builtin:sphereflake --reference magic", "--reference"},
        BadCase{"reference_inexact", "render builtin:sphereflake --reference rzb", "--reference"},
        BadCase{"reference_lzb", "render builtin:sphereflake --reference lzb", "--reference"},
        BadCase{"reference_too_wide", "render builtin:sphereflake --reference zbuffer --width 4097",
                "--reference"},
        BadCase{"reference_too_tall_in_file", "render DIR/tall.toml --reference raycast",
                "--reference"},
        BadCase{"subsamples_inexact", "render builtin:sphereflake --method rzb --subsamples",
                "--subsamples"},
        BadCase{"distribute_unknown", "render builtin:sphereflake --distribute halves",
                "--distribute"},
        BadCase{"bvh_unknown", "render builtin:sphereflake --bvh small", "--bvh"},
        BadCase{
            "distribute_data_store",
            "render builtin:sphereflake --method sampletree --tree /etc/passwd --distribute data",
            "--distribute data"},
        BadCase{"regions_huge",
                "render builtin:sphereflake --method zbuffer --distribute data --regions 70000",
                "--regions"},
        BadCase{"fallback_render_unknown",
                "render builtin:sphereflake --method rzb --fallback-render opengl",
                "--fallback-render"},
        BadCase{"subsamples_too_tall", "render builtin:sphereflake --subsamples --height 4100",
                "--subsamples"},
        BadCase{"surfel_grids", "render builtin:sphereflake --method surfels --surfel-grids 64,96",
                "--surfel-grids"},
        BadCase{"surfel_grids_low",
                "render builtin:sphereflake --method surfels --surfel-quality low --surfel-grids "
                "64,512",
                "--surfel-grids"},
        BadCase{"surfel_sprite", "render builtin:sphereflake --method surfels --splat 0",
                "--splat"},
        BadCase{"surfel_cell", "render builtin:sphereflake --method surfels --surfel-cell -1",
                "--surfel-cell"},
        BadCase{"surfel_budget", "render builtin:sphereflake --method surfels --budget-ms -5",
                "--budget-ms"},
        BadCase{"surfel_rate", "render builtin:sphereflake --method surfels --budget-rate fast",
                "--budget-rate"},
        BadCase{"surfelize", "render builtin:sphereflake --method surfels --surfelize voxels",
                "--surfelize"},
        BadCase{"quality", "render builtin:city --method rzb --quality best", "--quality"},
        BadCase{"sweep_quality", "sweep builtin:city --method rzb --quality 1 --param splat=1,2",
                "--quality"},
        BadCase{"sqrt5_amin_zero", "render 'builtin:displaced?tess=8' --method sqrt5 --amin 0",
                "--amin"},
        BadCase{"sqrt5_amin_text", "render 'builtin:displaced?tess=8' --method sqrt5 --amin big",
                "--amin"},
        BadCase{"sqrt5_amin_huge", "render 'builtin:displaced?tess=8' --method sqrt5 --amin 1e300",
                "--amin"},
        BadCase{"sqrt5_levels",
                "render 'builtin:displaced?tess=8' --method sqrt5 --sqrt5-levels 99",
                "--sqrt5-levels"},
        BadCase{"sqrt5_horizon", "render 'builtin:terrain?tess=8' --method sqrt5 --horizon maybe",
                "--horizon"},
        BadCase{"displaced_tess", "render 'builtin:displaced?tess=100000' --method sqrt5", "tess"},
        // The scene graph: 100,000 chained nodes, a node instancing itself, 10^30 triangles.
        BadCase{"chain_100000", "render DIR/chain.toml", "deeper than 64 levels"},
        BadCase{"self_instance", "render DIR/self.toml", "instancing cycle: me -> me"},
        BadCase{"expands_to_1e30", "render DIR/huge.toml", "more than 2^62 triangles"},
        // Counts in headers that used to wrap.
        BadCase{"off_face_size_2_64", "render DIR/face.off", "face.off"},
        // Resources, checked before anything is allocated.
        BadCase{"cache_mb_not_an_integer",
                "render builtin:sphereflake --method rzb --cache-mb 1e300",
                "--cache-mb: must be 0 (no cache) or a budget in MiB up to 2^40, got 1e+300"},
        BadCase{"oversample_1e300", "render builtin:sphereflake --method rzb --oversample 1e300",
                "--oversample: must be in (0, 1000], got 1e+300"},
        BadCase{"cache_mb_beyond_memory", "render builtin:sphereflake --method rzb --cache-mb 1e9",
                "--cache-mb: a sample cache needs 1000000000 MiB"},
        BadCase{"frame_beyond_ulimit", "render builtin:sphereflake --width 16384 --height 16384",
                "--width/--height: a 16384x16384 frame needs 4096 MiB", "ulimit -v 3000000; "},
        BadCase{"frame_of_scene_file_beyond_ulimit", "render DIR/vast.toml",
                "image size: a 16384x16384", "ulimit -v 3000000; "},
        BadCase{"reference_beyond_ulimit",
                "render builtin:sphereflake --reference raycast --width 2048 --height 2048",
                "with its --reference needs", "ulimit -v 1000000; "}),
    [](const auto& info) { return info.param.name; });

}  // namespace
}  // namespace lzb::test
