#include "lumaslam/viewer/viewer.h"

#include <sys/socket.h>

#include <httplib.h>
#include <spdlog/spdlog.h>

#include "lumaslam/core/error.h"
#include "lumaslam/viewer/frame_info.h"
#include "lumaslam/viewer/http_routes.h"
#include "lumaslam/viewer/map_snapshot.h"

namespace lumaslam::viewer {
namespace {

constexpr std::size_t kServerThreads = 32;

}  // namespace

std::filesystem::path defaultThreeJsDir() {
  return LUMASLAM_THREE_JS_DIR;
}

Viewer::Viewer(ViewerOptions options, std::shared_ptr<const map::Map> map)
    : options_(std::move(options)),
      map_(std::move(map)),
      control_(options_.start_paused),
      server_(std::make_unique<httplib::Server>()) {
  const auto three = options_.three_js_dir.empty() ? defaultThreeJsDir() : options_.three_js_dir;
  if (!threeJsFound()) {
    spdlog::warn(
        "viewer: three.js not found in {} (Debian package libjs-three): the page shows "
        "frames and numbers but no 3D map",
        three.string());
  }
  state_.setPaused(options_.start_paused);
  state_.setStatus(run_status_);
  control_.onChange([this] { state_.setPaused(control_.paused()); });
  addRoutes(*server_, RouteContext{state_, control_, three, stopping_});
  // Every connection holds a pool thread while it is kept alive, each open page's event stream
  // one for good: a pool of 8 (httplib's default here) makes a second page or a reload wait
  // for idle connections to time out. httplib owns the queue it is given.
  server_->new_task_queue = [] { return new httplib::ThreadPool(kServerThreads); };
  server_->set_keep_alive_timeout(1);
  // httplib's default adds SO_REUSEPORT: a second run on the same port would then share it
  // silently (requests going to either). SO_REUSEADDR only: the port is ours or an error.
  server_->set_socket_options([](int socket) {
    const int yes = 1;
    setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  port_ = options_.port == 0
              ? server_->bind_to_any_port(options_.address)
              : (server_->bind_to_port(options_.address, options_.port) ? options_.port : -1);
  if (port_ <= 0) {
    fail("viewer: cannot listen on {}:{} (in use, or not an address of this machine)",
         options_.address, options_.port);
  }
  server_thread_ = std::thread([this] { server_->listen_after_bind(); });
  publisher_ = std::thread([this] { publishLoop(); });
}

Viewer::~Viewer() {
  stopping_ = true;
  if (publisher_.joinable()) publisher_.join();
  server_->stop();
  if (server_thread_.joinable()) server_thread_.join();
}

std::string Viewer::url() const {
  return fmt::format("http://{}:{}/", options_.address, port_);
}

bool Viewer::threeJsFound() const {
  const auto three = options_.three_js_dir.empty() ? defaultThreeJsDir() : options_.three_js_dir;
  return std::filesystem::exists(three / "build" / "three.min.js");
}

void Viewer::finish(const std::string& status) {
  finished_ = true;
  // Local mapping has finished: this snapshot is the final map.
  state_.setMap(mapSnapshotJson(*map_));
  state_.setStatus(status);
}

void Viewer::publishLoop() {
  while (!stopping_) {
    auto taken = mailbox_.take(std::chrono::milliseconds(100));
    if (taken) show(std::move(*taken));
    // The map changes only with frames: no new frame, no new snapshot.
    const bool new_frames = frames_shown_ != frames_in_map_;
    if (!finished_ && new_frames &&
        std::chrono::steady_clock::now() - last_map_ >= options_.map_interval) {
      refreshMap();
    }
  }
}

void Viewer::show(TakenFrames taken) {
  ShownFrame shown;
  shown.info = frameInfoJson(taken.newest);
  shown.info["keyframes"] = map_->keyFrameCount();
  shown.info["map_points"] = map_->mapPointCount();
  shown.view = std::make_shared<const FrameView>(std::move(taken.newest));
  ++frames_shown_;
  state_.setCounts(frames_shown_, mailbox_.droppedCount());
  state_.setFrame(std::move(shown), taken.camera_centres);
}

void Viewer::refreshMap() {
  last_map_ = std::chrono::steady_clock::now();
  frames_in_map_ = frames_shown_;
  state_.setMap(mapSnapshotJson(*map_));
}

}  // namespace lumaslam::viewer
