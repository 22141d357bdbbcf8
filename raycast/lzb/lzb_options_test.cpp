#include "raycast/lzb/lzb_options.hpp"

#include <gtest/gtest.h>

#include <string>

#include "src/core/error.hpp"

namespace lzb::localz {
namespace {

// The message of the InputError that f throws ("" when none).
template <typename F>
std::string inputError(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(LzbOptions, ParsesEveryStageModeAndWalk) {
  EXPECT_EQ(parseLzbStage("naive", "--lzb-stage"), LzbStage::kNaive);
  EXPECT_EQ(parseLzbStage("lazy", "--lzb-stage"), LzbStage::kLazy);
  EXPECT_EQ(parseLzbStage("selective", "--lzb-stage"), LzbStage::kSelective);
  EXPECT_EQ(parseLzbStage("oor", "--lzb-stage"), LzbStage::kOor);
  EXPECT_EQ(parseLzbStage("final", "--lzb-stage"), LzbStage::kFinal);
  EXPECT_EQ(parseOccluderMode("dynamic", "--occluder-mode"), OccluderMode::kDynamic);
  EXPECT_EQ(parseOctreeWalk("topdown", "--lzb-walk"), OctreeWalk::kTopDown);
  EXPECT_EQ(parseZBufferKind("native", "--pvl-render"), ZBufferKind::kNative);
  EXPECT_EQ(parseZBufferKind("gl", "--pvl-render"), ZBufferKind::kGl);
  EXPECT_EQ(toString(ZBufferKind::kGl), "gl");
  EXPECT_EQ(LzbOptions{}.pvlRender, ZBufferKind::kNative);
  EXPECT_EQ(LzbOptions{}.nearRender, ZBufferKind::kNative);
  const std::string bad = inputError([] { parseZBufferKind("vulkan", "--pvl-render"); });
  EXPECT_NE(bad.find("--pvl-render"), std::string::npos) << bad;
  EXPECT_NE(bad.find("native, gl"), std::string::npos) << bad;
  for (LzbStage s :
       {LzbStage::kNaive, LzbStage::kLazy, LzbStage::kSelective, LzbStage::kOor, LzbStage::kFinal})
    EXPECT_EQ(parseLzbStage(toString(s), "x"), s);
}

TEST(LzbOptions, UnknownNamesNameTheOptionAndTheChoices) {
  const std::string m = inputError([] { parseLzbStage("fast", "--lzb-stage"); });
  EXPECT_NE(m.find("--lzb-stage"), std::string::npos) << m;
  EXPECT_NE(m.find("'fast'"), std::string::npos) << m;
  EXPECT_NE(m.find("naive, lazy, selective, oor, final"), std::string::npos) << m;
  EXPECT_NE(inputError([] { parseOccluderMode("random", "--occluder-mode"); }), "");
  EXPECT_NE(inputError([] { parseOctreeWalk("bfs", "--lzb-walk"); }), "");
}

TEST(LzbOptions, PlaneIsAutoCostOrAFractionStrictlyInside01) {
  LzbOptions o;
  EXPECT_TRUE(o.dynamicPlane() && o.costPlane);  // the default: the cost plane (README.md)
  parsePlane("auto", "--plane", o);
  EXPECT_TRUE(o.dynamicPlane());
  EXPECT_FALSE(o.costPlane);
  parsePlane("cost", "--plane", o);
  EXPECT_TRUE(o.dynamicPlane() && o.costPlane);
  parsePlane("0.2", "--plane", o);
  EXPECT_DOUBLE_EQ(o.planeFraction, 0.2);
  EXPECT_FALSE(o.dynamicPlane() || o.costPlane);
  for (const char* bad : {"0", "1", "1.5", "-0.1", "nan", "inf", "0.2x", "", "automatic"}) {
    const std::string m = inputError([&] { parsePlane(bad, "--plane", o); });
    EXPECT_NE(m.find("--plane"), std::string::npos) << bad;
    EXPECT_NE(m.find("(0, 1)"), std::string::npos) << bad;
  }
}

TEST(LzbOptions, ValidateRejectsOutOfRangeValues) {
  EXPECT_EQ(inputError([] { validate(LzbOptions{}); }), "");
  LzbOptions k;
  k.occluders = -1;
  EXPECT_NE(inputError([&] { validate(k); }).find("--occluders"), std::string::npos);
  LzbOptions zero;
  zero.occluders = 0;  // allowed: no occluder tested, every traversed leaf recorded
  EXPECT_EQ(inputError([&] { validate(zero); }), "");
  LzbOptions plane;
  plane.planeFraction = 1.0;
  EXPECT_NE(inputError([&] { validate(plane); }).find("--plane"), std::string::npos);
  LzbOptions grid;
  grid.planeGrid = 0;
  EXPECT_NE(inputError([&] { validate(grid); }).find("--plane-grid"), std::string::npos);
  LzbOptions reuse;
  reuse.planeReuse = -2;
  EXPECT_NE(inputError([&] { validate(reuse); }).find("--plane-reuse"), std::string::npos);
  LzbOptions leaf;
  leaf.leafEntries = 0;
  EXPECT_NE(inputError([&] { validate(leaf); }).find("--lzb-leaf"), std::string::npos);
}

TEST(LzbOptions, StagesBuildOnEachOther) {
  LzbOptions o;
  o.stage = LzbStage::kNaive;
  EXPECT_FALSE(o.usesPvl());
  o.stage = LzbStage::kLazy;
  EXPECT_TRUE(o.usesPvl());
  EXPECT_FALSE(o.usesOccluders());
  EXPECT_EQ(o.octreeWalk(), OctreeWalk::kTopDown);
  o.stage = LzbStage::kSelective;
  EXPECT_TRUE(o.usesOccluders());
  EXPECT_FALSE(o.usesOor());
  o.stage = LzbStage::kOor;
  EXPECT_TRUE(o.usesOor());
  EXPECT_EQ(o.octreeWalk(), OctreeWalk::kTopDown);
  o.stage = LzbStage::kFinal;
  EXPECT_TRUE(o.usesOor() && o.usesOccluders());
  EXPECT_EQ(o.octreeWalk(), OctreeWalk::kCoherent);
  o.walkOverride = true;
  o.walk = OctreeWalk::kTopDown;
  EXPECT_EQ(o.octreeWalk(), OctreeWalk::kTopDown);
}

}  // namespace
}  // namespace lzb::localz
