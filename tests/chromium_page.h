#pragma once
// Opens a page in headless Chromium (tests of the self-contained HTML reports).
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "test_cli.h"

namespace lumaslam::test {

// Headless Chromium on `page`: the DOM it built and what it logged (console messages are
// logged as ":CONSOLE" lines at --enable-logging=stderr).
struct BrowserResult {
  int exit_code = -1;
  std::string dom;
  std::vector<std::string> console;
};

inline BrowserResult openInChromium(const std::filesystem::path& page,
                                    const std::filesystem::path& work) {
  const auto dom = work / "dom.html";
  const auto log = work / "chromium.log";
  const std::string command =
      "timeout 120 chromium --headless=new --no-sandbox --disable-gpu --enable-logging=stderr "
      "--v=0 --user-data-dir=" +
      (work / "profile").string() + " --dump-dom file://" + page.string() + " > " + dom.string() +
      " 2> " + log.string();
  BrowserResult result;
  const int status = std::system(command.c_str());
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.dom = readTextFile(dom);
  std::istringstream lines(readTextFile(log));
  for (std::string line; std::getline(lines, line);) {
    if (line.find(":CONSOLE") != std::string::npos || line.find("Uncaught") != std::string::npos) {
      result.console.push_back(line);
    }
  }
  return result;
}

inline bool haveChromium() {
  return std::filesystem::exists("/usr/bin/chromium");
}

}  // namespace lumaslam::test
