// The sqrt5 options: defaults, the splat rule, and bad values as InputErrors naming the option
// (exit status 2 in lzb, tests/cli_test.cpp).
#include <gtest/gtest.h>

#include "src/core/error.hpp"
#include "src/sqrt5/sqrt5_params.hpp"

namespace lzb::sqrt5 {
namespace {

void expectRefused(const Sqrt5OptionText& t, const std::string& option) {
  try {
    parseSqrt5Options(t);
    ADD_FAILURE() << "accepted; expected an error naming " << option;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(option), std::string::npos) << e.what();
  }
}

TEST(Sqrt5Options, DefaultsAndSplatRule) {
  const Sqrt5Params p = parseSqrt5Options({});
  EXPECT_EQ(p.amin, 0.5);
  EXPECT_EQ(p.levels, 12);
  EXPECT_TRUE(p.horizon);
  EXPECT_EQ(p.splat(), 1);  // spacing below 0.71 px: every pixel holds a sample
  Sqrt5Params q;
  q.amin = 2.0;
  EXPECT_EQ(q.splat(), 2);
  q.amin = 2.1;
  EXPECT_EQ(q.splat(), 3);
  q.amin = 64.0;
  EXPECT_EQ(q.splat(), 12);
}

TEST(Sqrt5Options, BadValuesNameTheirOption) {
  for (const char* bad : {"0", "-1", "nan", "inf", "100", "x", "", "0.5px"}) {
    Sqrt5OptionText t;
    t.amin = bad;
    expectRefused(t, "--amin");
  }
  Sqrt5OptionText t;
  t.levels = -1;
  expectRefused(t, "--sqrt5-levels");
  t.levels = kMaxLevels + 1;
  expectRefused(t, "--sqrt5-levels");
  t = {};
  t.horizon = "yes";
  expectRefused(t, "--horizon");
  t = {};
  t.cacheMb = -1;
  expectRefused(t, "--sqrt5-cache-mb");
  t.cacheMb = 1.5;
  expectRefused(t, "--sqrt5-cache-mb");
  t.cacheMb = 1e300;
  expectRefused(t, "--sqrt5-cache-mb");
}

}  // namespace
}  // namespace lzb::sqrt5
