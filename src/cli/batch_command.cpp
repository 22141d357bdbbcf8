#include "src/cli/batch_command.hpp"

#include <sstream>

#include "mpi/failure.hpp"
#include "src/cli/methods.hpp"
#include "src/cli/quality.hpp"
#include "src/cli/render_setup.hpp"
#include "src/core/error.hpp"
#include "src/core/progress.hpp"
#include "src/core/whole_file.hpp"

namespace lzb {

void addBatchOptions(CLI::App& c, BatchArgs& a) {
  c.add_option("file", a.file,
               "a text file, one render a line: the arguments of `lzb render` (SCENE and its "
               "options; '#' starts a comment line; '...' or \"...\" keep blanks in a word)")
      ->required();
  c.add_flag("--quiet,-q", a.quiet, "no progress line of the batch's own (each job has --quiet)");
}

namespace {

std::string at(const std::string& name, int line) {
  return name + ":" + std::to_string(line);
}

// The words of one line; a quote runs to the next same quote.
std::vector<std::string> splitWords(const std::string& line, const std::string& where) {
  std::vector<std::string> words;
  std::string word;
  bool inWord = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '\'' || c == '"') {
      const size_t end = line.find(c, i + 1);
      if (end == std::string::npos) throw InputError(where + ": unterminated " + c + " quote");
      word += line.substr(i + 1, end - i - 1);
      inWord = true;
      i = end;
    } else if (c == ' ' || c == '\t' || c == '\r') {
      if (inWord) words.push_back(word);
      word.clear();
      inWord = false;
    } else {
      word += c;
      inWord = true;
    }
  }
  if (inWord) words.push_back(word);
  return words;
}

}  // namespace

std::vector<BatchJob> splitBatch(const std::string& text, const std::string& name) {
  std::vector<BatchJob> jobs;
  std::istringstream lines(text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    jobs.push_back({number, line, splitWords(line, at(name, number))});
  }
  return jobs;
}

RenderArgs parseBatchJob(const BatchJob& job, const std::string& name) {
  const std::string where = at(name, job.line);
  for (const std::string& w : job.words)
    if (w.rfind("--node-server", 0) == 0)
      throw InputError(where + ": --node-server needs MPI_THREAD_MULTIPLE from the job's start; "
                               "run it with `lzb render`, not in a batch");
  resetMethods();  // options left alone on this line keep their defaults, not an earlier job's
  RenderArgs args;
  CLI::App command;
  addRenderOptions(command, args);
  std::vector<std::string> argv(job.words.rbegin(), job.words.rend());  // CLI11: last first
  try {
    command.parse(argv);
    applyQuality(command, args);
    validateRenderArgs(args);
  } catch (const CLI::ParseError& e) {
    throw InputError(where + ": " + e.what());
  } catch (const InputError& e) {
    throw InputError(where + ": " + e.what());
  }
  return args;
}

int runBatch(const BatchArgs& a, const mpi::Group& g) {
  std::vector<BatchJob> jobs;
  // Every line is parsed and its --out checked before any job runs, so a bad line writes nothing.
  mpi::agree(g, [&] {
    jobs = splitBatch(readWholeFile(a.file, "cannot read the batch file"), a.file);
    require(!jobs.empty(), a.file, "holds no render line");
    for (const BatchJob& job : jobs) {
      const RenderArgs args = parseBatchJob(job, a.file);
      if (g.root()) checkOutput(args.out);
    }
  });
  Progress progress("batch of " + std::to_string(jobs.size()) + " renders", jobs.size(),
                    g.root() && !a.quiet);
  for (const BatchJob& job : jobs) {
    const RenderArgs args = parseBatchJob(job, a.file);
    const int status = runRender(args, g, "lzb render " + job.text);
    if (status != 0) return status;
    progress.add();
  }
  return 0;
}

}  // namespace lzb
