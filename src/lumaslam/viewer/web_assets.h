#pragma once
// The viewer's page and script (web/index.html, web/viewer.js), compiled in at build time.
namespace lumaslam::viewer {

const char* indexHtml();
const char* viewerJs();

}  // namespace lumaslam::viewer
