// `lumaslam run --viewer` in a real browser (issue 18): headless Chromium loads the page while
// the run is paused and stepped from the test; its screenshots must show the frame picture and
// a drawn 3D map, and the status text must follow the frames. The trajectory must be the one
// the same sequential run writes without the viewer.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "test_cli.h"

// After Eigen: glibc's <resolv.h>, which httplib.h includes, defines a macro `_res`.
#include <httplib.h>

extern char** environ;

namespace {

using lumaslam::test::readRunSummary;
using lumaslam::test::readTextFile;
using lumaslam::test::runCli;
using lumaslam::test::TempDir;

// A child process with stdout + stderr in `log`; killed and reaped if still running at the end.
class Child {
 public:
  Child(std::vector<std::string> args, const std::filesystem::path& log) {
    std::vector<char*> argv;
    for (auto& arg : args) argv.push_back(arg.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    if (posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), environ) != 0) pid_ = 0;
    posix_spawn_file_actions_destroy(&actions);
  }
  ~Child() {
    if (pid_ <= 0) return;
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  bool started() const { return pid_ > 0; }
  int wait() {  // exit code, -1 when killed by a signal
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = 0;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

 private:
  pid_t pid_ = 0;
};

struct PageCapture {
  cv::Mat screenshot;
  std::string dom;
  std::string log;  // Chromium's stderr (console messages)
};

constexpr int kPageWidth = 1300;
constexpr int kPageHeight = 900;

// Headless Chromium (Debian chromium, scripts/install-deps.sh) with SwiftShader for WebGL. The
// screenshot and the DOM are taken at the load event: the page is served with the status and
// the map of that moment (/map.js), which its script draws at once; the event stream, which
// stays open, only brings later changes.
PageCapture capturePage(const std::string& url, const std::filesystem::path& dir,
                        const std::string& name) {
  const auto png = dir / (name + ".png");
  const auto dom = dir / (name + ".html");
  const auto log = dir / (name + ".log");
  const std::string chromium =
      "timeout 120 chromium --headless=new --no-sandbox --use-angle=swiftshader "
      "--enable-unsafe-swiftshader --hide-scrollbars --enable-logging=stderr --window-size=" +
      std::to_string(kPageWidth) + "," + std::to_string(kPageHeight);
  std::system(
      (chromium + " --screenshot=" + png.string() + " " + url + " >/dev/null 2>" + log.string())
          .c_str());
  std::system(
      (chromium + " --dump-dom " + url + " >" + dom.string() + " 2>>" + log.string()).c_str());
  return {cv::imread(png.string(), cv::IMREAD_COLOR), readTextFile(dom), readTextFile(log)};
}

// Pixels that differ from the page's dark panel background in a region of the screenshot.
int drawnPixels(const cv::Mat& screenshot, const cv::Rect& region) {
  cv::Mat gray;
  cv::cvtColor(screenshot(region), gray, cv::COLOR_BGR2GRAY);
  cv::Mat drawn;
  cv::threshold(gray, drawn, 40, 255, cv::THRESH_BINARY);
  return cv::countNonZero(drawn);
}

std::string statusText(const std::string& dom) {
  std::smatch match;
  static const std::regex status(R"(<span id="status">([^<]*)</span>)");
  return std::regex_search(dom, match, status) ? match[1].str() : std::string();
}

// Layout (web/index.html, 1300 px wide): header ~36 px; the raw frame top left, the map bottom
// left.
const cv::Rect kRawFrame(10, 60, 620, 330);
const cv::Rect kMapArea(10, 460, 620, 330);
constexpr int kMapDrawn = 300;  // drawn pixels that say the map is there

// Up to 3 page loads (no time asserted) until the page shows `expected` and the map; one is
// enough unless the browser fails.
PageCapture capturePageShowing(const std::string& url, const std::filesystem::path& dir,
                               const std::string& name, const std::string& expected) {
  PageCapture capture;
  for (int attempt = 0; attempt < 3; ++attempt) {
    capture = capturePage(url, dir, name);
    const bool map_drawn =
        !capture.screenshot.empty() && drawnPixels(capture.screenshot, kMapArea) > kMapDrawn;
    if (map_drawn && statusText(capture.dom).find(expected) != std::string::npos) break;
  }
  return capture;
}

class CliViewer : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto synth =
        runCli("synth " + data_.string() + " --preset xyz-rgbd --frames 60 --seed 2");
    ASSERT_EQ(synth.exit_code, 0) << synth.output;
  }

  // The port the run printed ("viewer: http://127.0.0.1:PORT/"), 0 until it has.
  int printedPort(const std::filesystem::path& log) {
    std::smatch match;
    const std::string text = readTextFile(log);
    static const std::regex line(R"(viewer: http://127\.0\.0\.1:(\d+)/)");
    return std::regex_search(text, match, line) ? std::stoi(match[1].str()) : 0;
  }

  nlohmann::json status(httplib::Client& client) {
    const auto response = client.Get("/status.json");
    return response && response->status == 200 ? nlohmann::json::parse(response->body)
                                               : nlohmann::json{};
  }

  // Steps the paused run to frame `index` (frames are numbered from 0; each step lets one
  // through), then polls until the viewer shows it (no time asserted).
  bool stepTo(httplib::Client& client, std::size_t index) {
    const auto now = status(client);
    const std::size_t done = now.contains("frame") ? now["frame"].get<std::size_t>() + 1 : 0;
    for (std::size_t step = done; step <= index; ++step) {
      if (!client.Post("/control?action=step", "", "text/plain")) return false;
    }
    for (int attempt = 0; attempt < 3000; ++attempt) {
      const auto shown = status(client);
      if (shown.contains("frame") && shown["frame"].get<std::size_t>() == index) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
  }

  TempDir dir_{"cli_viewer"};
  std::filesystem::path data_ = dir_.path() / "data";
};

TEST_F(CliViewer, TheBrowserShowsTheFrameTheMapAndTheStatusAsTheRunAdvances) {
  const auto out = dir_.path() / "out";
  const auto log = dir_.path() / "run.log";
  Child run({lumaslam::test::cliPath().string(), "run", "--dataset", "tum:" + data_.string(),
             "--sequential", "--out", out.string(), "--viewer", "0", "--viewer-paused"},
            log);
  ASSERT_TRUE(run.started());
  int port = 0;
  for (int attempt = 0; attempt < 3000 && port == 0; ++attempt) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    port = printedPort(log);
  }
  ASSERT_GT(port, 0) << readTextFile(log);
  httplib::Client client("127.0.0.1", port);
  const std::string url = "http://127.0.0.1:" + std::to_string(port) + "/";

  ASSERT_TRUE(stepTo(client, 10));
  const auto early = capturePageShowing(url, dir_.path(), "early", "frame 10 ");
  ASSERT_FALSE(early.screenshot.empty()) << early.log;
  ASSERT_TRUE(stepTo(client, 40));
  const auto late = capturePageShowing(url, dir_.path(), "late", "frame 40 ");
  ASSERT_FALSE(late.screenshot.empty()) << late.log;

  EXPECT_GT(drawnPixels(early.screenshot, kRawFrame), 20000) << "no frame picture";
  EXPECT_GT(drawnPixels(late.screenshot, kMapArea), kMapDrawn) << "the 3D map stays blank";
  cv::Mat difference;
  cv::absdiff(early.screenshot(kRawFrame), late.screenshot(kRawFrame), difference);
  EXPECT_GT(cv::mean(difference)[0] + cv::mean(difference)[1] + cv::mean(difference)[2], 1.0)
      << "the frame picture did not change between frame 10 and frame 40";
  const std::string early_status = statusText(early.dom);
  const std::string late_status = statusText(late.dom);
  EXPECT_NE(early_status.find("frame 10 "), std::string::npos) << early_status;
  EXPECT_NE(late_status.find("frame 40 "), std::string::npos) << late_status;
  EXPECT_NE(late_status.find("keyframes"), std::string::npos) << late_status;
  EXPECT_EQ(late.log.find("Uncaught"), std::string::npos) << late.log;

  ASSERT_TRUE(client.Post("/control?action=resume", "", "text/plain"));
  ASSERT_EQ(run.wait(), 0) << readTextFile(log);
  const auto summary = readRunSummary(out);
  EXPECT_EQ(summary["viewer"]["frames_published"], summary["frames"]);
  // The tracking thread's cost is reported (docs/viewer.md has the measured numbers).
  EXPECT_GE(summary["viewer"]["handover_ms"]["median"].get<double>(), 0.0);
  EXPECT_GE(summary["viewer"]["handover_cpu_ms"]["median"].get<double>(), 0.0);
  // Where the kernel reports it, the time the thread waited for a core; what is left of the
  // wall time is neither work nor waiting, so it cannot be negative (0.05 ms for the two
  // clocks' rounding).
  const bool kernel_reports_waits = std::filesystem::exists("/proc/thread-self/schedstat");
  ASSERT_EQ(summary["viewer"].contains("handover_runqueue_ms"), kernel_reports_waits)
      << summary["viewer"].dump();
  if (kernel_reports_waits) {
    EXPECT_GE(summary["viewer"]["handover_runqueue_ms"]["median"].get<double>(), 0.0);
    EXPECT_GE(summary["viewer"]["handover_other_ms"]["median"].get<double>(), -0.05);
    EXPECT_LE(summary["viewer"]["handover_runqueue_ms"]["max"].get<double>(),
              summary["viewer"]["handover_ms"]["max"].get<double>() + 0.05);
  }

  const auto plain_out = dir_.path() / "plain";
  const auto plain =
      runCli("run --dataset tum:" + data_.string() + " --sequential --out " + plain_out.string());
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_EQ(readTextFile(out / "trajectory.txt"), readTextFile(plain_out / "trajectory.txt"))
      << "the viewer changed the result";
}

TEST_F(CliViewer, ViewerFlagsWithoutTheViewerAreRefused) {
  const auto result = runCli("run --dataset tum:" + data_.string() + " --viewer-paused --out " +
                             (dir_.path() / "x").string());
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("need --viewer"), std::string::npos) << result.output;
}

}  // namespace
