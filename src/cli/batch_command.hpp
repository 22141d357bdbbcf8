#pragma once
// `lzb batch FILE`: many renders in one job. Each line of FILE holds the arguments of one
// `lzb render` (what follows `lzb render` on a command line; '#' starts a comment line); the jobs
// run in order on every rank of this one MPI job, so a batch pays the launch, MPI's start and the
// program's start once instead of once per render. Every line is parsed before any job runs: a bad
// line is refused with `FILE:LINE: ...` and exit status 2, and nothing is written.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "mpi/group.hpp"
#include "src/cli/render_command.hpp"

namespace lzb {

struct BatchArgs {
  std::string file;
  bool quiet = false;  // no progress line of the batch's own
};

// One render of a batch: where it stands in the file, and its arguments.
struct BatchJob {
  int line = 0;
  std::string text;  // the line as written
  std::vector<std::string> words;
};

void addBatchOptions(CLI::App& command, BatchArgs& args);
// The jobs of a batch file's text (`name` in messages); throws InputError `name:LINE: ...` for an
// unterminated quote. Words are split at blanks; '...' and "..." keep blanks inside a word.
std::vector<BatchJob> splitBatch(const std::string& text, const std::string& name);
// A job's render arguments, parsed as `lzb render` parses them (--quality applied) with every
// method's options at their defaults first, so no value carries over from an earlier job.
// Throws InputError naming the file and line.
RenderArgs parseBatchJob(const BatchJob& job, const std::string& name);
// Returns the process exit status. Throws InputError for bad input (on every rank alike).
int runBatch(const BatchArgs& args, const mpi::Group& g);

}  // namespace lzb
