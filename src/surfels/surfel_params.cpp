#include "src/surfels/surfel_params.hpp"

#include <cmath>
#include <sstream>

#include "src/core/error.hpp"
#include "src/splat/splatter.hpp"

namespace lzb::surfels {

namespace {

// 1, 2, 4, ... up to half the lattice: positions keep a bit inside the finest cell.
std::vector<int> autoGrids(int lattice) {
  std::vector<int> grids;
  for (int g = 1; g <= lattice / 2; g *= 2) grids.push_back(g);
  return grids;
}

std::vector<int> parseGrids(const std::string& text, CollectorQuality quality) {
  const int lattice = int(CollectorLayout::of(quality).lattice());
  if (text == "auto") return autoGrids(lattice);
  const std::string expected = "auto or a comma-separated ascending list of powers of two in [1, " +
                               std::to_string(lattice) + "] (the " +
                               (quality == CollectorQuality::kLow ? "low" : "high") +
                               "-quality collector's lattice, --surfel-quality)";
  std::vector<int> grids;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    const double v = parseNumber(item, "--surfel-grids", expected);
    require(v >= 1.0 && v <= lattice && v == std::floor(v) && (int(v) & (int(v) - 1)) == 0,
            "--surfel-grids", "expected " + expected + ", got '" + item + "'");
    require(grids.empty() || int(v) > grids.back(), "--surfel-grids",
            "expected " + expected + ", got '" + text + "'");
    grids.push_back(int(v));
  }
  require(!grids.empty(), "--surfel-grids", "expected " + expected + ", got '" + text + "'");
  return grids;
}

}  // namespace

void SurfelParams::validate() const {
  validateSplat(sprite);
  require(cellFraction > 0.0 && cellFraction <= 4.0, "--surfel-cell", "must be in (0, 4]");
  require(budgetMs >= 0.0 && budgetMs <= 1e6, "--budget-ms", "must be in [0, 1e6] milliseconds");
  require(budgetRate >= 0.0 && std::isfinite(budgetRate), "--budget-rate",
          "must be 'auto' or a rate > 0 surfels per millisecond");
  require(!grids.empty(), "--surfel-grids", "must name at least one grid");
  for (size_t i = 0; i < grids.size(); ++i)
    require(grids[i] >= 1 && uint32_t(grids[i]) <= CollectorLayout::of(quality).lattice() &&
                (grids[i] & (grids[i] - 1)) == 0 && (i == 0 || grids[i] > grids[i - 1]),
            "--surfel-grids", "must be ascending powers of two within the collector's lattice");
}

double SurfelParams::coverSide(int d) const {
  return disc ? double(d) / std::sqrt(2.0) : double(d);
}

nlohmann::json SurfelParams::toJson() const {
  return {{"surfelize", surfelize == Surfelizer::kRaster ? "raster" : "shots"},
          {"quality", quality == CollectorQuality::kLow ? "low" : "high"},
          {"grids", grids},
          {"splat", sprite},
          {"sprite_shape", disc ? "disc" : "square"},
          {"surfel_cell", cellFraction},
          {"collisions", split ? "split" : "average"},
          {"backfaces", dropBackfaces ? "drop" : "keep"},
          {"budget_ms", budgetMs},
          {"budget_rate", budgetRate > 0.0 ? nlohmann::json(budgetRate) : nlohmann::json("auto")},
          {"surfel_build", buildAtSetup ? "setup" : "lazy"}};
}

SurfelParams parseSurfelOptions(const SurfelOptionText& t) {
  SurfelParams p;
  require(t.surfelize == "raster" || t.surfelize == "shots", "--surfelize",
          "expected raster or shots, got '" + t.surfelize + "'");
  p.surfelize = t.surfelize == "raster" ? Surfelizer::kRaster : Surfelizer::kShots;
  require(t.quality == "low" || t.quality == "high", "--surfel-quality",
          "expected low or high, got '" + t.quality + "'");
  p.quality = t.quality == "low" ? CollectorQuality::kLow : CollectorQuality::kHigh;
  p.grids = parseGrids(t.grids, p.quality);
  require(t.shape == "square" || t.shape == "disc", "--sprite-shape",
          "expected square or disc, got '" + t.shape + "'");
  p.disc = t.shape == "disc";
  require(t.collisions == "split" || t.collisions == "average", "--collisions",
          "expected split or average, got '" + t.collisions + "'");
  p.split = t.collisions == "split";
  require(t.backfaces == "drop" || t.backfaces == "keep", "--backfaces",
          "expected drop or keep, got '" + t.backfaces + "'");
  p.dropBackfaces = t.backfaces == "drop";
  if (t.budgetRate != "auto") {
    p.budgetRate =
        parseNumber(t.budgetRate, "--budget-rate", "'auto' or a rate > 0 surfels per ms");
    require(p.budgetRate > 0.0, "--budget-rate",
            "expected 'auto' or a rate > 0, got '" + t.budgetRate + "'");
  }
  require(t.build == "lazy" || t.build == "setup", "--surfel-build",
          "expected lazy or setup, got '" + t.build + "'");
  p.buildAtSetup = t.build == "setup";
  p.sprite = t.splat;
  p.cellFraction = t.cell;
  p.budgetMs = t.budgetMs;
  p.validate();
  return p;
}

}  // namespace lzb::surfels
