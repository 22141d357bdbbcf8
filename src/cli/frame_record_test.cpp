// The job's record: frame ranges, whole lines only (a torn last line is dropped and cut off), the
// fields that make two runs one job, and frames verified by their files' sizes.
#include "src/cli/frame_record.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "src/core/error.hpp"

namespace lzb {
namespace {

namespace fs = std::filesystem;

fs::path freshFolder(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("lzb_frame_record_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void writeText(const fs::path& file, const std::string& text) {
  std::ofstream(file, std::ios::binary) << text;
}

TEST(FrameRange, ParsesRangesWithinThePath) {
  EXPECT_EQ(parseFrameRange("", 6, "--frame-range").end, 6);
  const FrameRange r = parseFrameRange("3:5", 6, "--frame-range");
  EXPECT_EQ(r.begin, 3);
  EXPECT_EQ(r.end, 5);
  EXPECT_EQ(parseFrameRange("4:", 6, "--frame-range").end, 6);
  for (const char* bad : {"5:3", "3:3", "0:7", "-1:2", "a:b", "3", ":4", "1:2:3", "1: 2"})
    EXPECT_THROW(parseFrameRange(bad, 6, "--frame-range"), InputError) << bad;
}

TEST(FrameRecord, ATornLastLineIsLeftOutAndCutOff) {
  const fs::path file = freshFolder("torn") / kFramesFile;
  {
    FrameRecordWriter writer(file);
    writer.append({{"frame", 0}, {"seconds", 0.5}});
    writer.append({{"frame", 1}, {"seconds", 0.25}});
  }
  std::ofstream(file, std::ios::app) << R"({"frame": 2, "seco)";  // killed mid-append
  ASSERT_EQ(readFrameRecords(file).size(), 2u);
  trimTornLine(file);
  FrameRecordWriter(file).append({{"frame", 2}, {"seconds", 1.0}});
  const auto records = readFrameRecords(file);
  ASSERT_EQ(records.size(), 3u);
  EXPECT_EQ(records[2]["frame"], 2);
}

TEST(FrameRecord, ALineTornAtItsLastBraceIsStillTorn) {
  const fs::path file = freshFolder("brace") / kFramesFile;
  writeText(file, "{\"frame\": 0}\n{\"frame\": 1}");  // whole JSON, but its newline never came
  EXPECT_EQ(readFrameRecords(file).size(), 1u);
}

TEST(FrameRecord, ADamagedLineBeforeTheLastIsAnErrorNamingIt) {
  const fs::path file = freshFolder("damaged") / kFramesFile;
  writeText(file, "{\"frame\": 0}\nnot json\n{\"frame\": 2}\n");
  try {
    readFrameRecords(file);
    FAIL() << "a damaged record was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("frames.jsonl:2"), std::string::npos) << e.what();
  }
}

TEST(FrameRecord, TheLatestRecordOfEachFrameInFrameOrder) {
  const auto frames = latestPerFrame({{{"frame", 3}, {"seconds", 1}},
                                      {{"frame", 1}, {"seconds", 2}},
                                      {{"frame", 3}, {"seconds", 3}}});
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0]["frame"], 1);
  EXPECT_EQ(frames[1]["seconds"], 3);
}

nlohmann::json head() {
  return {
      {"scene", {{"source", "builtin:city"}, {"triangles_unique", 10}, {"triangles_expanded", 20}}},
      {"method", "hybrid"},
      {"method_exact", false},
      {"method_parameters", {{"plane", 0.5}}},
      {"width", 64},
      {"height", 48},
      {"distribution", "replicate"},
      {"ranks", 2},
      {"threads", 1},
      {"parameters",
       {{"seed", 1},
        {"quality", nullptr},
        {"frames", 6},
        {"reference", nullptr},
        {"subsamples", false},
        {"fov", 0},
        {"near", 0},
        {"far", 0},
        {"regions", 0},
        {"composite", "tiles"},
        {"frame_groups", 1}}}};
}

TEST(JobKey, RanksThreadsAndCompositeDoNotMakeAnotherJob) {
  nlohmann::json other = head();
  other["ranks"] = 3;
  other["threads"] = 2;
  other["parameters"]["composite"] = "bswap";
  other["parameters"]["frame_groups"] = 3;
  EXPECT_EQ(keyDifference(imageKey(head()), imageKey(other)), "");
}

TEST(JobKey, WhatChangesTheImagesIsNamed) {
  nlohmann::json other = head();
  other["parameters"]["seed"] = 2;
  EXPECT_EQ(keyDifference(imageKey(head()), imageKey(other)), "seed: was 1, now 2");
  other = head();
  other["method_parameters"]["plane"] = 0.25;
  EXPECT_NE(keyDifference(imageKey(head()), imageKey(other)).find("method_parameters"),
            std::string::npos);
  other = head();
  other["width"] = 65;
  EXPECT_EQ(keyDifference(imageKey(head()), imageKey(other)), "width: was 64, now 65");
  other = head();
  other["distribution"] = "data";
  EXPECT_NE(keyDifference(imageKey(head()), imageKey(other)), "");
  other["method_exact"] = true;  // exact methods give the replicated image under data too
  nlohmann::json exact = head();
  exact["method_exact"] = true;
  EXPECT_EQ(keyDifference(imageKey(exact), imageKey(other)), "");
}

TEST(FrameFiles, AFrameIsCompleteWhenItsFilesHaveTheRecordedSizes) {
  const fs::path dir = freshFolder("files");
  writeText(dir / "frame_0004.png", "png bytes");
  writeText(dir / "frame_0004.exr", "exr bytes, more");
  const nlohmann::json record = {{"frame", 4}, {"files", frameFiles(dir, 4)}};
  EXPECT_EQ(record["files"]["frame_0004.exr"], 15);
  EXPECT_TRUE(frameComplete(dir, record));
  writeText(dir / "frame_0004.exr", "exr");  // replaced by something else
  EXPECT_FALSE(frameComplete(dir, record));
  fs::remove(dir / "frame_0004.png");
  EXPECT_FALSE(frameComplete(dir, record));
  EXPECT_FALSE(frameComplete(dir, {{"frame", 4}}));  // a record without files proves nothing
}

TEST(FrameFiles, StaleTemporariesGoAndFramesStay) {
  const fs::path dir = freshFolder("stale");
  writeText(dir / ".frame_0002.tmp123.exr", "half");
  writeText(dir / "frame_0002.exr", "whole");
  removeStaleTemporaries(dir);
  EXPECT_FALSE(fs::exists(dir / ".frame_0002.tmp123.exr"));
  EXPECT_TRUE(fs::exists(dir / "frame_0002.exr"));
}

}  // namespace
}  // namespace lzb
