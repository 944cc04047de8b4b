#include "lumaslam/viewer/http_routes.h"

#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>

#include <httplib.h>

#include "lumaslam/viewer/web_assets.h"

namespace lumaslam::viewer {
namespace {

constexpr const char* kJson = "application/json";

void noStore(httplib::Response& response) {
  response.set_header("Cache-Control", "no-store");
}

void sendFile(const std::filesystem::path& file, httplib::Response& response) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    response.status = 404;
    response.set_content(file.string() + " not found (Debian package libjs-three)", "text/plain");
    return;
  }
  std::ostringstream bytes;
  bytes << in.rdbuf();
  response.set_content(bytes.str(), "application/javascript");
}

// The page with the current status filled in (web/index.html's placeholder).
std::string pageWithStatus(const PublishedState& state) {
  static const std::string kPlaceholder = "/*LUMASLAM_STATUS*/null";
  std::string page = indexHtml();
  const auto at = page.find(kPlaceholder);
  if (at == std::string::npos) return page;
  // JSON inside <script>: "</" would end the element; nlohmann's dump never escapes '/'.
  std::string status = state.statusJson();
  for (auto slash = status.find("</"); slash != std::string::npos; slash = status.find("</")) {
    status.replace(slash, 2, "<\\/");
  }
  return page.replace(at, kPlaceholder.size(), status);
}

void addPageRoutes(httplib::Server& server, const RouteContext& context) {
  const PublishedState& state = context.state;
  server.Get("/", [&state](const httplib::Request&, httplib::Response& response) {
    noStore(response);
    response.set_content(pageWithStatus(state), "text/html; charset=utf-8");
  });
  server.Get("/viewer.js", [](const httplib::Request&, httplib::Response& response) {
    response.set_content(viewerJs(), "application/javascript");
  });
  const auto three = context.three_js_dir;
  server.Get("/three/three.min.js", [three](const httplib::Request&, httplib::Response& response) {
    sendFile(three / "build" / "three.min.js", response);
  });
  server.Get("/three/OrbitControls.js",
             [three](const httplib::Request&, httplib::Response& response) {
               sendFile(three / "examples" / "js" / "controls" / "OrbitControls.js", response);
             });
}

void addFrameRoute(httplib::Server& server, const RouteContext& context) {
  const PublishedState& state = context.state;
  server.Get("/frame.jpg", [&state](const httplib::Request& request, httplib::Response& response) {
    const std::string view = request.has_param("view") ? request.get_param_value("view") : "raw";
    const std::map<std::string, FramePicture> pictures = {{"raw", FramePicture::Raw},
                                                          {"enhanced", FramePicture::Enhanced},
                                                          {"right", FramePicture::Right}};
    const auto which = pictures.find(view);
    if (which == pictures.end()) {
      response.status = 400;
      response.set_content("view must be raw, enhanced or right, not '" + view + "'", "text/plain");
      return;
    }
    const auto picture = state.picture(which->second);
    if (!picture || picture->empty()) {
      response.status = 404;
      response.set_content(picture ? "the frame has no " + view + " image (right: stereo runs)"
                                   : std::string("no frame yet"),
                           "text/plain");
      return;
    }
    noStore(response);
    response.set_content(reinterpret_cast<const char*>(picture->data()), picture->size(),
                         "image/jpeg");
  });
}

void addStateRoutes(httplib::Server& server, const RouteContext& context) {
  const PublishedState& state = context.state;
  server.Get("/status.json", [&state](const httplib::Request&, httplib::Response& response) {
    noStore(response);
    response.set_content(state.statusJson(), kJson);
  });
  server.Get("/history.json", [&state](const httplib::Request&, httplib::Response& response) {
    noStore(response);
    response.set_content(state.historyJson(), kJson);
  });
  // The map as a script (web/index.html): the page's first map arrives with the page.
  server.Get("/map.js", [&state](const httplib::Request&, httplib::Response& response) {
    noStore(response);
    response.set_content("window.lumaslamInitialMap = " + state.mapJson() + ";",
                         "application/javascript");
  });
  server.Get("/map.json", [&state](const httplib::Request&, httplib::Response& response) {
    noStore(response);
    response.set_content(state.mapJson(), kJson);
  });
}

// One message at once, then one per change; a comment line every half second keeps the
// connection checked, so a closed page or a stopping viewer ends the stream.
void addEventRoute(httplib::Server& server, const RouteContext& context) {
  const PublishedState& state = context.state;
  const std::atomic<bool>& stopping = context.stopping;
  server.Get("/events", [&state, &stopping](const httplib::Request&, httplib::Response& response) {
    noStore(response);
    auto seen = std::numeric_limits<std::uint64_t>::max();
    response.set_chunked_content_provider(
        "text/event-stream",
        [&state, &stopping, seen](std::size_t, httplib::DataSink& sink) mutable {
          if (stopping) return false;
          const auto version = seen == std::numeric_limits<std::uint64_t>::max()
                                   ? state.version()
                                   : state.waitForChange(seen, std::chrono::milliseconds(500));
          if (stopping) return false;
          if (version == seen) return sink.write(": alive\n\n", 10);
          seen = version;
          const std::string message = "data: " + state.statusJson() + "\n\n";
          return sink.write(message.data(), message.size());
        });
  });
}

void addControlRoute(httplib::Server& server, const RouteContext& context) {
  RunControl& control = context.control;
  const PublishedState& state = context.state;
  server.Post("/control", [&control, &state](const httplib::Request& request,
                                             httplib::Response& response) {
    const std::string action = request.has_param("action") ? request.get_param_value("action") : "";
    if (action == "pause") {
      control.pause();
    } else if (action == "resume") {
      control.resume();
    } else if (action == "step") {
      control.step();
    } else {
      response.status = 400;
      response.set_content("action must be pause, resume or step, not '" + action + "'",
                           "text/plain");
      return;
    }
    response.set_content(state.statusJson(), kJson);
  });
  server.Get("/control", [](const httplib::Request&, httplib::Response& response) {
    response.status = 405;
    response.set_header("Allow", "POST");
    response.set_content("POST /control?action=pause|resume|step", "text/plain");
  });
}

}  // namespace

void addRoutes(httplib::Server& server, const RouteContext& context) {
  addPageRoutes(server, context);
  addFrameRoute(server, context);
  addStateRoutes(server, context);
  addEventRoute(server, context);
  addControlRoute(server, context);
  server.set_error_handler([](const httplib::Request& request, httplib::Response& response) {
    if (!response.body.empty()) return;
    response.set_content(
        std::to_string(response.status) + ": " + request.method + " " + request.path, "text/plain");
  });
}

}  // namespace lumaslam::viewer
