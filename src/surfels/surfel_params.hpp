#pragma once
// The surfel method's parameters (--method surfels): how objects are surfelized, which grids
// exist, how surfels are drawn, the switch to polygons and the time budget.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "src/surfels/collector.hpp"
#include "src/surfels/surfelize.hpp"

namespace lzb::surfels {

struct SurfelParams {
  Surfelizer surfelize = Surfelizer::kRaster;                        // --surfelize raster | shots
  CollectorQuality quality = CollectorQuality::kHigh;                                  // --surfel-quality low | high
  std::vector<int> grids = {1, 2, 4, 8, 16, 32, 64, 128, 256, 512};  // --surfel-grids (auto)
  int sprite = 1;             // --splat: the largest sprite, d x d pixels
  bool disc = false;          // --sprite-shape square | disc
  double cellFraction = 0.5;  // --surfel-cell
  bool split = true;          // --collisions split | average
  bool dropBackfaces = true;  // --backfaces drop | keep
  double budgetMs = 0.0;      // --budget-ms (0: no budget)
  double budgetRate = 0.0;    // --budget-rate, surfels per ms (0: measured)
  bool buildAtSetup = false;  // --surfel-build setup | lazy

  // Throws InputError naming the option for out-of-range values.
  void validate() const;
  nlohmann::json toJson() const;
  // The side of the square of pixel centres around its point that a d-pixel sprite always
  // covers: d for squares, d / sqrt(2) for discs (the square inscribed in the disc).
  double coverSide(int d) const;
};

// The option strings as the command line gives them.
struct SurfelOptionText {
  std::string surfelize = "raster", quality = "high", grids = "auto", shape = "square",
              collisions = "split", backfaces = "drop", budgetRate = "auto", build = "lazy";
  int splat = 1;
  double cell = 0.5, budgetMs = 0.0;
};

// Parses and validates; throws InputError naming the option.
SurfelParams parseSurfelOptions(const SurfelOptionText& text);

}  // namespace lzb::surfels
