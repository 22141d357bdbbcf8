#include "src/cli/report_command.hpp"

#include <cstdio>
#include <filesystem>

#include "src/cli/render_job.hpp"
#include "src/cli/report.hpp"

namespace lzb {

void addReportOptions(CLI::App& c, ReportArgs& a) {
  c.add_option("dir", a.dir, "the --out folder of a `lzb render` run")->required();
}

int runReport(const ReportArgs& a, const mpi::Group& g) {
  if (!g.root()) return 0;
  Report report(readJobHead(a.dir), a.dir);
  const std::vector<nlohmann::json> frames = recordedFrames(a.dir);
  report.setFrames(frames);
  report.setTotal(-1.0);  // not a run: the frames' own figures only
  report.write(std::filesystem::path(a.dir) / "report.json");
  if (frames.empty()) {
    std::printf("lzb: %s: the record holds no finished frame yet\n", a.dir.c_str());
    return 0;
  }
  report.printSummary(stdout);
  return 0;
}

}  // namespace lzb
