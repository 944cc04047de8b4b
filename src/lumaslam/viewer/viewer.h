#pragma once
// The live viewer (docs/viewer.md): an HTTP server on its own threads showing the run as it
// goes. The tracking thread only hands frames over (publish: no drawing, encoding or waiting
// for the browser) and waits between frames while the page has paused the run. The map is
// read in the viewer's thread through its own locks; the viewer never writes to it, so results
// are the same with and without it.
#include <atomic>
#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <thread>

#include "lumaslam/map/map.h"
#include "lumaslam/viewer/frame_mailbox.h"
#include "lumaslam/viewer/frame_view.h"
#include "lumaslam/viewer/published_state.h"
#include "lumaslam/viewer/run_control.h"

namespace httplib {
class Server;
}

namespace lumaslam::viewer {

struct ViewerOptions {
  std::string address = "127.0.0.1";            // another address serves the page to the network
  int port = 7878;                              // 0: any free port (port() tells which)
  bool start_paused = false;                    // wait for the page's Step / Resume before frame 0
  std::filesystem::path three_js_dir;           // empty: Debian's libjs-three (defaultThreeJsDir)
  std::chrono::milliseconds map_interval{500};  // how often the map snapshot is refreshed
};

std::filesystem::path defaultThreeJsDir();

class Viewer {
 public:
  // Throws Error when the address or port cannot be bound.
  Viewer(ViewerOptions options, std::shared_ptr<const map::Map> map);
  ~Viewer();
  Viewer(const Viewer&) = delete;
  Viewer& operator=(const Viewer&) = delete;

  int port() const { return port_; }
  std::string url() const;

  // Tracking thread.
  void publish(FrameView view) { mailbox_.put(std::move(view)); }
  void waitWhilePaused(const std::function<bool()>& stop_requested) {
    control_.waitWhilePaused(stop_requested);
  }
  // After the last frame (and after local mapping finished): a last map snapshot, and the page
  // shows `status` ("complete", "partial", ...).
  void finish(const std::string& status);

  std::size_t framesPublished() const { return mailbox_.putCount(); }
  std::size_t framesDropped() const { return mailbox_.droppedCount(); }
  bool threeJsFound() const;

 private:
  void publishLoop();
  void show(TakenFrames taken);
  void refreshMap();

  const ViewerOptions options_;
  const std::shared_ptr<const map::Map> map_;
  FrameMailbox mailbox_;
  PublishedState state_;
  RunControl control_;
  std::string run_status_ = "running";  // set at construction
  std::atomic<bool> stopping_{false};
  std::atomic<bool> finished_{false};
  std::size_t frames_shown_ = 0;   // viewer thread
  std::size_t frames_in_map_ = 0;  // frames_shown_ at the last map snapshot
  std::chrono::steady_clock::time_point last_map_{};
  std::unique_ptr<httplib::Server> server_;
  int port_ = 0;
  std::thread publisher_;  // takes frames from the mailbox, refreshes the map snapshot
  std::thread server_thread_;
};

}  // namespace lumaslam::viewer
