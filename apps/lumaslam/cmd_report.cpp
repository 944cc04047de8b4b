#include <cstdio>
#include <filesystem>
#include <memory>

#include "command_registry.h"
#include "run_report.h"

namespace lumaslam::cli {
namespace {

struct ReportOptions {
  std::filesystem::path run_dir;
  std::filesystem::path out;  // empty: RUN_DIR/report.html
};

int runReport(const ReportOptions& options) {
  const auto out = options.out.empty() ? options.run_dir / "report.html" : options.out;
  writeReport(options.run_dir, out);
  std::printf("report in %s\n", out.string().c_str());
  return 0;
}

const bool registered = registerCommand(
    "report", "Write one self-contained HTML page showing what `lumaslam run` wrote",
    [](CLI::App& cmd) -> Runner {
      auto options = std::make_shared<ReportOptions>();
      cmd.add_option("RUN_DIR", options->run_dir,
                     "The --out folder of `lumaslam run` (or of `run --repeat`)")
          ->required();
      cmd.add_option("--out", options->out, "HTML file to write (default: RUN_DIR/report.html)");
      return [options] { return runReport(*options); };
    });

}  // namespace
}  // namespace lumaslam::cli
