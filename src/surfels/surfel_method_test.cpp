// The surfel options: defaults as documented, and out-of-range values as InputErrors naming the
// option (exit status 2 in lzb, tests/cli_test.cpp).
#include <gtest/gtest.h>

#include "src/core/error.hpp"
#include "src/surfels/surfel_params.hpp"

namespace lzb::surfels {
namespace {

void expectRefused(SurfelOptionText t, const std::string& option) {
  try {
    parseSurfelOptions(t);
    ADD_FAILURE() << "accepted; expected an error naming " << option;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(option), std::string::npos) << e.what();
  }
}

TEST(SurfelOptions, DefaultsAreTheDocumentedOnes) {
  const SurfelParams p = parseSurfelOptions({});
  EXPECT_EQ(p.quality, CollectorQuality::kHigh);
  EXPECT_EQ(p.grids, (std::vector<int>{1, 2, 4, 8, 16, 32, 64, 128, 256, 512}));
  EXPECT_EQ(p.sprite, 1);
  EXPECT_FALSE(p.disc);
  EXPECT_EQ(p.cellFraction, 0.5);
  EXPECT_TRUE(p.split);
  EXPECT_TRUE(p.dropBackfaces);
  EXPECT_EQ(p.budgetMs, 0.0);
  EXPECT_EQ(p.toJson()["budget_rate"], "auto");
  SurfelOptionText low;
  low.quality = "low";  // auto grids stop at half the low-quality lattice of 256
  EXPECT_EQ(parseSurfelOptions(low).grids, (std::vector<int>{1, 2, 4, 8, 16, 32, 64, 128}));
}

TEST(SurfelOptions, BadValuesNameTheirOption) {
  SurfelOptionText t;
  t.grids = "64,100";  // not a power of two
  expectRefused(t, "--surfel-grids");
  t.grids = "128,64";  // not ascending
  expectRefused(t, "--surfel-grids");
  t.grids = "";
  expectRefused(t, "--surfel-grids");
  t.grids = "64,512";
  t.quality = "low";  // 512 is beyond the low-quality lattice of 256
  expectRefused(t, "--surfel-grids");
  t = {};
  t.quality = "medium";
  expectRefused(t, "--surfel-quality");
  t = {};
  t.surfelize = "voxels";
  expectRefused(t, "--surfelize");
  t = {};
  t.splat = 0;
  expectRefused(t, "--splat");
  t = {};
  t.shape = "star";
  expectRefused(t, "--sprite-shape");
  t = {};
  t.cell = 0.0;
  expectRefused(t, "--surfel-cell");
  t = {};
  t.collisions = "keep";
  expectRefused(t, "--collisions");
  t = {};
  t.backfaces = "cull";
  expectRefused(t, "--backfaces");
  t = {};
  t.budgetMs = -1.0;
  expectRefused(t, "--budget-ms");
  t = {};
  t.budgetRate = "0";
  expectRefused(t, "--budget-rate");
  t.budgetRate = "fast";
  expectRefused(t, "--budget-rate");
  t = {};
  t.build = "eager";
  expectRefused(t, "--surfel-build");
}

}  // namespace
}  // namespace lzb::surfels
