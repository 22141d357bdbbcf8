// `lzb sweep` end to end: the CSV's rows and accuracy, the plot or the message that it was
// skipped, and bad --param values refused with exit status 2 and nothing written.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/cli_runner.hpp"

namespace lzb::test {
namespace {

namespace fs = std::filesystem;

const std::string kTiny = "'builtin:city?blocks=3' --width 80 --height 60 --frames 2 --threads 2";

struct Csv {
  std::string comment;                                   // the first line
  std::vector<std::map<std::string, std::string>> rows;  // by header name
};

std::vector<std::string> fields(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  for (std::string f; std::getline(in, f, ',');) out.push_back(f);
  return out;
}

Csv readCsv(const fs::path& file) {
  Csv csv;
  std::ifstream in(file);
  std::getline(in, csv.comment);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = fields(line);
  while (std::getline(in, line)) {
    const std::vector<std::string> values = fields(line);
    std::map<std::string, std::string> row;
    for (size_t i = 0; i < header.size() && i < values.size(); ++i) row[header[i]] = values[i];
    csv.rows.push_back(row);
  }
  return csv;
}

bool gnuplotOnPath() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

// Runs a sweep into a fresh folder and reads its CSV.
Csv sweep(const std::string& name, const std::string& args) {
  const fs::path out = freshDir(name) / "out";
  const RunResult r = runLzb("sweep " + kTiny + " " + args + " --quiet --out " + out.string());
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(out / "sweep.csv")) << r.output;
  if (gnuplotOnPath()) {
    EXPECT_TRUE(fs::exists(out / "sweep.png")) << r.output;
  } else {
    EXPECT_FALSE(fs::exists(out / "sweep.png"));
    EXPECT_NE(r.output.find("plot: skipped"), std::string::npos) << r.output;
  }
  return readCsv(out / "sweep.csv");
}

double number(const std::map<std::string, std::string>& row, const std::string& column) {
  const auto it = row.find(column);
  EXPECT_NE(it, row.end()) << column;
  return it == row.end() ? -1.0 : std::stod(it->second);
}

TEST(Sweep, TwoValuesGiveTwoRowsWithRatesInZeroOne) {
  const Csv csv = sweep("two_values", "--method rzb --param splat=1,2");
  EXPECT_EQ(csv.comment.rfind("# ", 0), 0u) << csv.comment;
  EXPECT_NE(csv.comment.find("sweep"), std::string::npos) << csv.comment;
  ASSERT_EQ(csv.rows.size(), 2u);
  EXPECT_EQ(csv.rows[0].at("splat"), "1");
  EXPECT_EQ(csv.rows[1].at("splat"), "2");
  for (const auto& row : csv.rows) {
    EXPECT_EQ(number(row, "frames"), 2.0);
    EXPECT_GT(number(row, "median_frame_s"), 0.0);
    for (const char* c : {"correct_rate_covered_min", "correct_rate_covered_median"}) {
      EXPECT_GE(number(row, c), 0.0) << c;
      EXPECT_LE(number(row, c), 1.0) << c;
    }
    EXPECT_LE(number(row, "correct_rate_covered_min"), number(row, "correct_rate_covered_median"));
    EXPECT_GT(number(row, "samples_drawn"), 0.0);  // the method's counts come along
  }
}

TEST(Sweep, EveryCombinationOfTwoParameters) {
  const Csv csv = sweep("grid", "--method rzb --param splat=1,2 --param eps=1.5,2");
  ASSERT_EQ(csv.rows.size(), 4u);
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"1", "1.5"}, {"1", "2"}, {"2", "1.5"}, {"2", "2"}};
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(csv.rows[i].at("splat"), expected[i].first);
    EXPECT_EQ(csv.rows[i].at("eps"), expected[i].second);
  }
}

// An exact method judged against itself is right at every covered pixel, whatever is swept.
TEST(Sweep, ExactMethodAgainstItselfIsAllCorrect) {
  const Csv csv = sweep("exact_self", "--method raycast --reference raycast --param composite=tiles,reduce");
  ASSERT_EQ(csv.rows.size(), 2u);
  for (const auto& row : csv.rows) {
    EXPECT_EQ(number(row, "correct_rate_covered_min"), 1.0);
    EXPECT_EQ(number(row, "exact_id_rate_covered_median"), 1.0);
  }
}

// Against the other exact method: on this scene every covered pixel is correct (measured: 99.7 %
// show zbuffer's centre ID, the 17 samples and the witness settle the rest). Not so everywhere:
// cli_test's ExactReferencesAgree holds other scenes to 99.5 %.
TEST(Sweep, ExactMethodAgainstTheOtherExactReference) {
  const Csv csv = sweep("exact_other", "--method raycast --reference zbuffer --param seed=1,2");
  ASSERT_EQ(csv.rows.size(), 2u);
  for (const auto& row : csv.rows) EXPECT_EQ(number(row, "correct_rate_covered_min"), 1.0);
  // An exact method draws no random numbers: the seed leaves its image, and accuracy, alone.
  EXPECT_EQ(csv.rows[0].at("correct_rate_covered_min"), csv.rows[1].at("correct_rate_covered_min"));
}

struct BadSweep {
  std::string name, args, mustMention;
};
void PrintTo(const BadSweep& c, std::ostream* os) { *os << c.args; }

class BadSweepInput : public ::testing::TestWithParam<BadSweep> {};

TEST_P(BadSweepInput, ExitsWithStatus2AndWritesNothing) {
  const BadSweep& c = GetParam();
  const fs::path out = freshDir("bad_" + c.name) / "out";
  const RunResult r = runLzb("sweep " + kTiny + " " + c.args + " --quiet --out " + out.string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find(c.mustMention), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("error"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out)) << "output left in " << out;
}

// 4 parameters of 11 values: 14,641 combinations.
std::string tooMany() {
  std::string s = "--method rzb";
  for (const char* name : {"splat", "oversample", "area-ratio", "cache-mb"}) {
    s += std::string(" --param ") + name + "=";
    for (int v = 1; v <= 11; ++v) s += (v > 1 ? "," : "") + std::to_string(v + 1);
  }
  return s;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BadSweepInput,
    ::testing::Values(
        BadSweep{"unknown_method", "--method nosuch --param splat=1,2", "unknown method 'nosuch'"},
        BadSweep{"unknown_name", "--method rzb --param nosuch=1,2", "--param nosuch"},
        BadSweep{"other_methods_option", "--method rzb --param plane=0.5", "--param plane"},
        BadSweep{"frames_not_sweepable", "--method rzb --param frames=1,2", "--param frames"},
        BadSweep{"no_equals", "--method rzb --param splat", "--param splat"},
        BadSweep{"empty_list", "--method rzb --param splat=", "--param splat="},
        BadSweep{"empty_value", "--method rzb --param splat=1,,2", "--param splat=1,,2"},
        BadSweep{"repeated_value", "--method rzb --param splat=1,1", "listed twice"},
        BadSweep{"repeated_name", "--method rzb --param splat=1 --param splat=2", "swept twice"},
        BadSweep{"also_plain", "--method rzb --splat 2 --param splat=1,2", "also given as --splat"},
        BadSweep{"not_a_number", "--method rzb --param splat=1,two", "--param splat=two"},
        BadSweep{"refused_by_validate", "--method rzb --param eps=1.5,0.5", "--param eps=0.5: --eps"},
        BadSweep{"refused_combination", "--method rzb --reconstruct pixel --param splat=1,2",
                 "--param splat=2: --reconstruct"},
        BadSweep{"no_param", "--method rzb", "--param"},
        BadSweep{"too_many", tooMany(), "more than 10000 combinations"},
        BadSweep{"inexact_reference", "--method rzb --reference rzb --param splat=1,2", "--reference"}),
    [](const auto& info) { return info.param.name; });

}  // namespace
}  // namespace lzb::test
