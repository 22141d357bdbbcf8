#include "src/cli/compare_command.hpp"

#include <cstdio>

#include "src/image/compare.hpp"

namespace lzb {

void addCompareOptions(CLI::App& c, CompareArgs& a) {
  c.add_option("image", a.test, "EXR written by lzb render (the image to judge)")->required();
  c.add_option("reference", a.reference,
               "EXR of the exact reference, rendered with `lzb render --subsamples`")
      ->required();
}

int runCompare(const CompareArgs& a, const mpi::Group& g) {
  const nlohmann::json result = compareFiles(a.test, a.reference);
  if (g.root()) std::printf("%s\n", result.dump(2).c_str());
  return 0;
}

}  // namespace lzb
