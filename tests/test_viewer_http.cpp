// The viewer's HTTP routes, in process: every route, bad requests, the frame pictures' drawing,
// the event stream, pause / step, and the hand-over that drops frames the encoder missed.

#include <atomic>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "error_of.h"
#include "lumaslam/viewer/frame_mailbox.h"
#include "lumaslam/viewer/viewer.h"

// After Eigen: glibc's <resolv.h>, which httplib.h includes, defines a macro `_res`.
#include <httplib.h>

namespace {

using lumaslam::test::errorOf;
using lumaslam::viewer::FrameMailbox;
using lumaslam::viewer::FrameView;
using lumaslam::viewer::Viewer;
using lumaslam::viewer::ViewerOptions;

FrameView testFrame(std::size_t index) {
  FrameView view;
  view.index = index;
  view.timestamp = 0.1 * static_cast<double>(index);
  view.state = "ok";
  view.step = "motion model";
  view.inliers = 200 + static_cast<int>(index);
  view.camera_centre = Eigen::Vector3d(0.01 * static_cast<double>(index), 0.0, 0.0);
  view.raw = cv::Mat(120, 160, CV_8UC3, cv::Scalar(0, 0, 0));
  view.features_image = cv::Mat(120, 160, CV_8UC1, cv::Scalar(128));
  view.kept = {{40.f, 40.f}};
  view.dropped = {{120.f, 40.f}};
  view.boxes = {cv::Rect2f(100.f, 70.f, 40.f, 30.f)};
  return view;
}

class ViewerHttp : public ::testing::Test {
 protected:
  ViewerHttp() {
    ViewerOptions options;
    options.port = 0;
    options.map_interval = std::chrono::milliseconds(20);
    viewer_ = std::make_unique<Viewer>(options, map_);
    client_ = std::make_unique<httplib::Client>("127.0.0.1", viewer_->port());
  }

  nlohmann::json status() {
    const auto response = client_->Get("/status.json");
    EXPECT_TRUE(response);
    return response ? nlohmann::json::parse(response->body) : nlohmann::json{};
  }

  // Polls (no time asserted) until the page's status shows frame `index`.
  bool waitForFrame(std::size_t index) {
    for (int attempt = 0; attempt < 1000; ++attempt) {
      const auto now = status();
      if (now.contains("frame") && now["frame"].get<std::size_t>() == index) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
  }

  std::shared_ptr<lumaslam::map::Map> map_ = std::make_shared<lumaslam::map::Map>();
  std::unique_ptr<Viewer> viewer_;
  std::unique_ptr<httplib::Client> client_;
};

TEST_F(ViewerHttp, ServesThePageItsScriptAndThreeJs) {
  const auto page = client_->Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->get_header_value("Content-Type").find("text/html"), std::string::npos);
  EXPECT_NE(page->body.find("id=\"map-view\""), std::string::npos);
  const auto script = client_->Get("/viewer.js");
  ASSERT_TRUE(script);
  EXPECT_EQ(script->status, 200);
  EXPECT_NE(script->body.find("EventSource('/events')"), std::string::npos);
  ASSERT_TRUE(viewer_->threeJsFound()) << "libjs-three is installed by scripts/install-deps.sh";
  for (const char* path : {"/three/three.min.js", "/three/OrbitControls.js"}) {
    const auto three = client_->Get(path);
    ASSERT_TRUE(three) << path;
    EXPECT_EQ(three->status, 200) << path;
    EXPECT_GT(three->body.size(), 1000u) << path;
  }
}

TEST_F(ViewerHttp, BeforeTheFirstFrameThereIsNoPictureAndTheStatusSaysRunning) {
  const auto picture = client_->Get("/frame.jpg");
  ASSERT_TRUE(picture);
  EXPECT_EQ(picture->status, 404);
  const auto now = status();
  EXPECT_EQ(now["status"], "running");
  EXPECT_FALSE(now.contains("frame"));
}

TEST_F(ViewerHttp, BadRequestsAreRefusedWithAReason) {
  const auto bad_view = client_->Get("/frame.jpg?view=depth");
  ASSERT_TRUE(bad_view);
  EXPECT_EQ(bad_view->status, 400);
  EXPECT_NE(bad_view->body.find("raw, enhanced or right"), std::string::npos);
  const auto bad_action = client_->Post("/control?action=jump", "", "text/plain");
  ASSERT_TRUE(bad_action);
  EXPECT_EQ(bad_action->status, 400);
  EXPECT_NE(bad_action->body.find("pause, resume or step"), std::string::npos);
  const auto no_action = client_->Post("/control", "", "text/plain");
  ASSERT_TRUE(no_action);
  EXPECT_EQ(no_action->status, 400);
  const auto get_control = client_->Get("/control");
  ASSERT_TRUE(get_control);
  EXPECT_EQ(get_control->status, 405);
  EXPECT_EQ(get_control->get_header_value("Allow"), "POST");
  const auto unknown = client_->Get("/nothing/here");
  ASSERT_TRUE(unknown);
  EXPECT_EQ(unknown->status, 404);
  EXPECT_NE(unknown->body.find("/nothing/here"), std::string::npos);
}

TEST_F(ViewerHttp, APublishedFrameIsDrawnWithItsKeypointsAndBoxes) {
  viewer_->publish(testFrame(7));
  ASSERT_TRUE(waitForFrame(7));
  const auto now = status();
  EXPECT_EQ(now["inliers"], 207);
  EXPECT_EQ(now["kept"], 1);
  EXPECT_EQ(now["dropped"], 1);
  EXPECT_EQ(now["boxes"].size(), 1u);

  const auto raw = client_->Get("/frame.jpg?view=raw");
  ASSERT_TRUE(raw);
  ASSERT_EQ(raw->status, 200);
  EXPECT_EQ(raw->get_header_value("Content-Type"), "image/jpeg");
  const cv::Mat picture =
      cv::imdecode(std::vector<uchar>(raw->body.begin(), raw->body.end()), cv::IMREAD_COLOR);
  ASSERT_EQ(picture.size(), cv::Size(160, 120));
  const auto bgr = [&](int x, int y) { return picture.at<cv::Vec3b>(y, x); };
  EXPECT_GT(bgr(42, 40)[1], 120) << "kept keypoint: green ring";
  EXPECT_GT(bgr(122, 40)[2], 120) << "dropped keypoint: red ring";
  EXPECT_LT(bgr(122, 40)[1], 100);
  EXPECT_GT(bgr(100, 85)[2], 120) << "box edge: yellow";
  EXPECT_GT(bgr(100, 85)[1], 120);
  EXPECT_LT(bgr(10, 100)[2], 30) << "untouched background stays black";

  const auto enhanced = client_->Get("/frame.jpg?view=enhanced");
  ASSERT_TRUE(enhanced);
  const cv::Mat gray = cv::imdecode(
      std::vector<uchar>(enhanced->body.begin(), enhanced->body.end()), cv::IMREAD_COLOR);
  ASSERT_FALSE(gray.empty());
  EXPECT_NEAR(gray.at<cv::Vec3b>(100, 10)[0], 128, 6) << "the features image, not the raw one";

  // The page and its map script carry the state of the moment they are served.
  const auto page = client_->Get("/");
  ASSERT_TRUE(page);
  EXPECT_NE(page->body.find("lumaslamInitialStatus = {"), std::string::npos);
  EXPECT_NE(page->body.find("\"frame\":7,"), std::string::npos);
  const auto map_script = client_->Get("/map.js");
  ASSERT_TRUE(map_script);
  EXPECT_EQ(map_script->body.rfind("window.lumaslamInitialMap = {\"map\":", 0), 0u)
      << map_script->body.substr(0, 80);
}

TEST_F(ViewerHttp, AStereoFrameServesItsRightImageWithoutTheLeftImagesMarks) {
  FrameView stereo = testFrame(8);
  stereo.right = cv::Mat(120, 160, CV_8UC1, cv::Scalar(200));
  viewer_->publish(std::move(stereo));
  ASSERT_TRUE(waitForFrame(8));
  EXPECT_EQ(status()["right"], true);
  const auto right = client_->Get("/frame.jpg?view=right");
  ASSERT_TRUE(right);
  ASSERT_EQ(right->status, 200);
  EXPECT_EQ(right->get_header_value("Content-Type"), "image/jpeg");
  const cv::Mat picture =
      cv::imdecode(std::vector<uchar>(right->body.begin(), right->body.end()), cv::IMREAD_COLOR);
  ASSERT_EQ(picture.size(), cv::Size(160, 120));
  for (const cv::Point at : {cv::Point(10, 100), cv::Point(42, 40), cv::Point(122, 40)}) {
    const cv::Vec3b bgr = picture.at<cv::Vec3b>(at);
    for (int channel = 0; channel < 3; ++channel) {
      EXPECT_NEAR(bgr[channel], 200, 8) << "the right image, unmarked, at " << at;
    }
  }

  viewer_->publish(testFrame(9));  // not stereo
  ASSERT_TRUE(waitForFrame(9));
  EXPECT_EQ(status()["right"], false);
  const auto none = client_->Get("/frame.jpg?view=right");
  ASSERT_TRUE(none);
  EXPECT_EQ(none->status, 404);
  EXPECT_NE(none->body.find("no right image"), std::string::npos) << none->body;
}

TEST_F(ViewerHttp, TheMapRouteHoldsTheTrajectoryOfEveryPublishedFrame) {
  for (std::size_t i = 0; i < 3; ++i) {
    viewer_->publish(testFrame(i));
    ASSERT_TRUE(waitForFrame(i));
  }
  const auto response = client_->Get("/map.json");
  ASSERT_TRUE(response);
  ASSERT_EQ(response->status, 200);
  const auto snapshot = nlohmann::json::parse(response->body);
  ASSERT_EQ(snapshot["trajectory"].size(), 9u);
  EXPECT_NEAR(snapshot["trajectory"][6].get<double>(), 0.02, 1e-6);
  ASSERT_TRUE(snapshot["map"].is_object()) << "refreshed while frames arrive";
  EXPECT_EQ(snapshot["map"]["keyframes"], 0);

  const auto history = client_->Get("/history.json");
  ASSERT_TRUE(history);
  const auto frames = nlohmann::json::parse(history->body);
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_EQ(frames[2]["frame"], 2);
  EXPECT_EQ(frames[2]["inliers"], 202);
}

TEST_F(ViewerHttp, TheEventStreamSendsTheStatusAtOnceAndOnEveryChange) {
  viewer_->publish(testFrame(3));
  ASSERT_TRUE(waitForFrame(3));
  std::vector<nlohmann::json> messages;
  std::string buffer;
  std::thread publisher;
  std::string content_type;
  const auto headers = [&](const httplib::Response& response) {
    content_type = response.get_header_value("Content-Type");
    return true;
  };
  // The stream does not end by itself: the receiver cancels it at frame 4.
  client_->Get("/events", headers, [&](const char* data, std::size_t size) {
    buffer.append(data, size);
    for (auto end = buffer.find("\n\n"); end != std::string::npos; end = buffer.find("\n\n")) {
      const std::string event = buffer.substr(0, end);
      buffer.erase(0, end + 2);
      if (event.rfind("data: ", 0) == 0) messages.push_back(nlohmann::json::parse(event.substr(6)));
    }
    if (messages.size() == 1 && !publisher.joinable()) {
      publisher = std::thread([this] { viewer_->publish(testFrame(4)); });
    }
    return messages.empty() || messages.back().value("frame", 0) != 4;  // stop at frame 4
  });
  if (publisher.joinable()) publisher.join();
  ASSERT_GE(messages.size(), 2u);
  EXPECT_EQ(messages.front()["frame"], 3);
  EXPECT_EQ(messages.back()["frame"], 4);
  EXPECT_EQ(content_type, "text/event-stream");
}

TEST_F(ViewerHttp, PauseHoldsTheTrackingThreadAndStepLetsOneFrameThrough) {
  ASSERT_TRUE(client_->Post("/control?action=pause", "", "text/plain"));
  EXPECT_TRUE(status()["paused"].get<bool>());
  std::atomic<int> frames{0};
  std::atomic<bool> stop{false};
  std::thread tracking([&] {
    while (frames < 3 && !stop) {
      viewer_->waitWhilePaused([&] { return stop.load(); });
      if (!stop) ++frames;
    }
  });
  ASSERT_TRUE(client_->Post("/control?action=step", "", "text/plain"));
  for (int attempt = 0; attempt < 1000 && frames < 1; ++attempt) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_EQ(frames, 1);
  ASSERT_TRUE(client_->Post("/control?action=resume", "", "text/plain"));
  EXPECT_FALSE(status()["paused"].get<bool>());
  for (int attempt = 0; attempt < 1000 && frames < 3; ++attempt) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  stop = true;
  tracking.join();
  EXPECT_EQ(frames, 3);
}

TEST(ViewerMailbox, KeepsTheNewestFrameAndEveryCameraCentre) {
  FrameMailbox mailbox;
  for (std::size_t i = 0; i < 3; ++i) mailbox.put(testFrame(i));
  const auto taken = mailbox.take(std::chrono::milliseconds(0));
  ASSERT_TRUE(taken);
  EXPECT_EQ(taken->newest.index, 2u);
  EXPECT_EQ(taken->camera_centres.size(), 3u);
  EXPECT_EQ(mailbox.putCount(), 3u);
  EXPECT_EQ(mailbox.droppedCount(), 2u);
  EXPECT_FALSE(mailbox.take(std::chrono::milliseconds(0)));
}

TEST(ViewerStart, APortInUseIsAClearError) {
  auto map = std::make_shared<lumaslam::map::Map>();
  ViewerOptions options;
  options.port = 0;
  const Viewer first(options, map);
  options.port = first.port();
  // A second viewer on the same port is an error naming the port.
  const std::string message = errorOf([&] { const Viewer second(options, map); });
  EXPECT_NE(message.find(std::to_string(options.port)), std::string::npos)
      << "a second viewer on port " << options.port << ": " << message;
}

}  // namespace
