#pragma once
// Each cmd_*.cpp registers one subcommand at static-initialisation time:
//
//   const bool registered = lumaslam::cli::registerCommand(
//       "eval", "Compare a trajectory with ground truth",
//       [](CLI::App& cmd) -> lumaslam::cli::Runner {
//         auto options = std::make_shared<EvalOptions>();
//         cmd.add_option("EST", options->estimate)->required();
//         return [options] { return runEval(*options); };  // returns the exit code
//       });
//
// main() parses, runs the chosen command and turns a thrown lumaslam::Error (or any
// std::exception) into one "lumaslam CMD: error: ..." line and exit code 1.
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace lumaslam::cli {

using Runner = std::function<int()>;
using Setup = std::function<Runner(CLI::App&)>;

struct Command {
  std::string name;
  std::string description;
  Setup setup;
};

bool registerCommand(std::string name, std::string description, Setup setup);
const std::vector<Command>& commands();

}  // namespace lumaslam::cli
