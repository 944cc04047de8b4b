#pragma once
// The viewer's HTTP routes (docs/viewer.md lists them):
//   GET  /                  the page          GET /viewer.js          its script
//   GET  /three/three.min.js, /three/OrbitControls.js   three.js from libjs-three
//   GET  /status.json       the frame's numbers, paused, status, versions
//   GET  /events            server-sent events: /status.json's body on every change
//   GET  /frame.jpg?view=raw|enhanced   the newest frame picture (404 before the first)
//   GET  /map.json          map snapshot and trajectory (/map.js: the same as a script)
//   GET  /history.json      the last 300 frames' numbers (for the plots)
//   POST /control?action=pause|resume|step
#include <atomic>
#include <filesystem>

#include "lumaslam/viewer/published_state.h"
#include "lumaslam/viewer/run_control.h"

namespace httplib {
class Server;
}

namespace lumaslam::viewer {

struct RouteContext {
  const PublishedState& state;
  RunControl& control;
  std::filesystem::path three_js_dir;
  const std::atomic<bool>& stopping;  // event streams end when it turns true
};

void addRoutes(httplib::Server& server, const RouteContext& context);

}  // namespace lumaslam::viewer
