#include "experiment_jobs.h"

#include <fmt/format.h>

#include "lumaslam/core/error.h"
#include "lumaslam/io/output_file.h"
#include "run_command_line.h"

namespace lumaslam::cli {

std::vector<std::string> jobLines(const std::vector<ExperimentRun>& runs) {
  std::vector<std::string> lines;
  for (const auto& run : runs) {
    if (run.external || isComplete(run.options.out)) continue;
    const std::string line = runCommandLine(run.options);
    if (line.find('\n') != std::string::npos) {
      fail("{}: a path or value with a line break cannot be one line of jobs.txt: {}",
           run.options.out.string(), line);
    }
    lines.push_back(line);
  }
  return lines;
}

int writeJobs(const std::vector<ExperimentRun>& runs, const std::filesystem::path& dir) {
  const auto lines = jobLines(runs);
  io::OutputFile out(dir / "jobs.txt");
  for (const auto& line : lines) out.stream() << line << '\n';
  out.commit();
  return static_cast<int>(lines.size());
}

void writeSlurmScript(const std::filesystem::path& dir, int jobs) {
  const auto file = dir / "jobs.slurm";
  if (jobs == 0) {
    std::filesystem::remove(file);
    return;
  }
  io::OutputFile out(file);
  // #SBATCH lines count only before the first command.
  out.stream() << fmt::format(
      "#!/bin/sh\n"
      "# lumaslam experiment: task K of the array runs line K of jobs.txt.\n"
      "# Submit with `sbatch {0}`, then `lumaslam experiment collect {1}`.\n"
      "#SBATCH --job-name=lumaslam-experiment\n"
      "#SBATCH --array=1-{2}\n"
      "#SBATCH --cpus-per-task=1\n"
      "sed -n \"${{SLURM_ARRAY_TASK_ID}}p\" {3} | sh\n",
      shellQuote(file.string()), shellQuote(dir.string()), jobs,
      shellQuote((dir / "jobs.txt").string()));
  out.commit();
}

}  // namespace lumaslam::cli
