#pragma once
// `lzb report DIR`: rebuilds DIR/report.json from the job's record (job.json and frames.jsonl,
// src/cli/frame_record.hpp) without rendering: for a killed job, or after the frame-range tasks
// of one path have all written into DIR.
#include <CLI/CLI.hpp>
#include <string>

#include "mpi/group.hpp"

namespace lzb {

struct ReportArgs {
  std::string dir;
};

void addReportOptions(CLI::App& command, ReportArgs& args);
int runReport(const ReportArgs& args, const mpi::Group& g);

}  // namespace lzb
