#pragma once
// Runs the built `lumaslam` binary with arguments; captures stdout + stderr and the exit code.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "test_paths.h"

namespace lumaslam::test {

struct CliResult {
  int exit_code = -1;
  std::string output;
};

// Runs a command line in sh, stdout + stderr captured.
inline CliResult runShell(const std::string& command_line) {
  const std::string command = command_line + " 2>&1";
  CliResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer{};
  while (fgets(buffer.data(), buffer.size(), pipe)) result.output += buffer.data();
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

// `shell_setup` runs first in the same shell, e.g. "ulimit -f 1; ".
inline CliResult runCli(const std::string& arguments, const std::string& shell_setup = "") {
  return runShell(shell_setup + cliPath().string() + " " + arguments);
}

// A whole text file ("" when it cannot be read).
inline std::string readTextFile(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The data rows of the markdown tables in `text` ("| a | b |" lines after a "|---|" line), each
// as its trimmed cells; header and separator lines are left out.
inline std::vector<std::vector<std::string>> markdownRows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream lines(text);
  bool in_table = false;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("|", 0) != 0) {
      in_table = false;
      continue;
    }
    if (line.rfind("|---", 0) == 0) {
      in_table = true;
      continue;
    }
    if (!in_table) continue;
    std::vector<std::string> cells;
    std::istringstream row(line.substr(1));
    for (std::string cell; std::getline(row, cell, '|');) {
      const auto first = cell.find_first_not_of(' ');
      const auto last = cell.find_last_not_of(' ');
      cells.push_back(first == std::string::npos ? "" : cell.substr(first, last - first + 1));
    }
    rows.push_back(cells);
  }
  return rows;
}

// The summary.json that `lumaslam run` writes into `out` (empty json when there is none).
inline nlohmann::json readRunSummary(const std::filesystem::path& out) {
  std::ifstream file(out / "summary.json");
  if (!file) return {};
  return nlohmann::json::parse(file);
}

}  // namespace lumaslam::test
