#include <algorithm>
#include <exception>
#include <iostream>
#include <map>
#include <sstream>

#include <cstdio>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "cli_checks.h"
#include "command_registry.h"
#ifdef LUMASLAM_SERIAL_LIBRARIES
#include "lumaslam/core/serial_libraries.h"
#endif

namespace lumaslam::cli {

namespace {
std::vector<Command>& registry() {
  static std::vector<Command> instance;
  return instance;
}
}  // namespace

bool registerCommand(std::string name, std::string description, Setup setup) {
  registry().push_back({std::move(name), std::move(description), std::move(setup)});
  return true;
}

const std::vector<Command>& commands() {
  return registry();
}

}  // namespace lumaslam::cli

int main(int argc, char** argv) {
  using namespace lumaslam::cli;
#ifdef LUMASLAM_SERIAL_LIBRARIES  // ThreadSanitizer builds: OpenCV and TBB run single-threaded
  const lumaslam::core::SerialLibraries serial_libraries;
#endif
  CLI::App app{"lumaslam: visual SLAM that keeps localizing in bad light and busy scenes"};
  app.require_subcommand(1);
  std::string log_level = "info";
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error or off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "off"}));

  auto sorted = commands();
  std::sort(sorted.begin(), sorted.end(),
            [](const Command& a, const Command& b) { return a.name < b.name; });
  std::map<CLI::App*, std::pair<std::string, Runner>> runners;
  for (const auto& command : sorted) {
    CLI::App* sub = app.add_subcommand(command.name, command.description);
    runners[sub] = {command.name, command.setup(*sub)};
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    std::ostringstream errors;  // an option's value may be a 1 MB word: shortened
    const int code = app.exit(e, std::cout, errors);
    std::fputs(shortenLongWords(errors.str()).c_str(), stderr);
    return code;
  }
  // Logs go to stderr so that stdout carries only results (tables, JSON).
  spdlog::set_default_logger(spdlog::stderr_color_mt("lumaslam"));
  spdlog::set_level(spdlog::level::from_str(log_level));
  spdlog::set_pattern("[%H:%M:%S.%e] [%^%l%$] %v");

  for (auto& [sub, entry] : runners) {
    if (!sub->parsed()) continue;
    try {
      const int code = entry.second();
      // Results printed to stdout (tables, JSON) count as output too: `eval > /dev/full` must
      // not exit 0.
      if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
        std::fprintf(stderr, "lumaslam %s: error: writing to stdout failed\n", entry.first.c_str());
        return code == 0 ? 1 : code;
      }
      return code;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "lumaslam %s: error: %s\n", entry.first.c_str(),
                   shortenLongWords(e.what()).c_str());
      return 1;
    }
  }
  return 1;
}
