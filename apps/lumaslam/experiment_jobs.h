#pragma once
// `lumaslam experiment PLAN --out DIR --emit parallel|slurm` (docs/experiments.md): the runs
// that are not complete as jobs for GNU parallel or a Slurm array, one `lumaslam run` command
// line each; the scheduler runs them, `lumaslam experiment collect DIR` tabulates.
#include <filesystem>
#include <string>
#include <vector>

#include "experiment_cells.h"

namespace lumaslam::cli {

// One `lumaslam run` command line per run that is not complete (external rows are no jobs).
std::vector<std::string> jobLines(const std::vector<ExperimentRun>& runs);

// Writes DIR/jobs.txt, one line per run that is not complete (empty when every run is);
// returns the number of lines.
int writeJobs(const std::vector<ExperimentRun>& runs, const std::filesystem::path& dir);

// Writes DIR/jobs.slurm, an array job whose task K runs line K of DIR/jobs.txt; with no jobs it
// removes an earlier one instead (an array of 0 tasks is not a Slurm job).
void writeSlurmScript(const std::filesystem::path& dir, int jobs);

}  // namespace lumaslam::cli
