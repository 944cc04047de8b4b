// framesSection of report_sections.h.
#include <fmt/format.h>

#include "html_page.h"
#include "moving_features_file.h"
#include "report_sections.h"

namespace lumaslam::cli {
namespace {

std::string introduction(const SampleFrames& samples) {
  std::string html =
      "<p>Read again from the dataset; enhancement preset " + escapeHtml(samples.enhancement) +
      " applied to each frame on its own (the run's online statistics are not kept), with the "
      "ORB keypoints extracted from the image tracking sees (green).";
  if (!samples.geometry.empty()) {
    html += " Both pictures are the frame as tracking takes it (" + escapeHtml(samples.geometry) +
            "), in the pixels of moving_features.txt.";
  }
  if (samples.unmarked.empty()) {
    return html +
           " Like the run, the keypoints are taken outside the previous frame's boxes (made "
           "again from moving_features.txt). Red: the run's detection boxes and the features it "
           "dropped, where that file puts them (circles: inside a box, crosses: flagged moving "
           "by the motion test); a keypoint at a red mark is not drawn green. The counts after "
           "\"the run\" are the run's.</p>\n";
  }
  if (samples.marks_broken) {
    return html + "</p>\n" + htmlNote("No feature is marked: " + samples.unmarked);
  }
  return html + " No feature is marked: " + escapeHtml(samples.unmarked) + ".</p>\n";
}

// "N kept, M dropped (K by boxes, L by the motion test)", each count with its data-key.
std::string markedCounts(const SampleFrame& frame) {
  const auto& marked = *frame.marked;
  const auto span = [&](const char* name, std::size_t value) {
    return fmt::format("<span data-key=\"frame.{}.{}\" data-value=\"{}\">{}</span>", frame.index,
                       name, value, value);
  };
  return fmt::format("{} kept, {} dropped ({} by boxes, {} by the motion test), {} boxes",
                     span("kept", marked.kept),
                     span("dropped", marked.by_boxes + marked.by_motion_test),
                     span("by_boxes", marked.by_boxes),
                     span("by_motion_test", marked.by_motion_test), span("boxes", marked.boxes));
}

std::string enhancedCaption(const SampleFrame& frame, const SampleFrames& samples) {
  std::string caption = fmt::format("as tracked, {} ORB keypoints", frame.keypoints);
  if (frame.marked) {
    return caption +
           fmt::format(", <span data-key=\"frame.{0}.green\" data-value=\"{1}\">{1}</span> green",
                       frame.index, frame.green) +
           "; the run: " + markedCounts(frame);
  }
  if (samples.unmarked.empty()) caption += fmt::format(" (not in {})", kMovingFeaturesFile);
  return caption;
}

}  // namespace

std::string framesSection(const SampleFrames& samples) {
  std::string html;
  if (!samples.problem.empty()) html += htmlNote("Sample frames unavailable: " + samples.problem);
  if (samples.frames.empty()) return html.empty() ? htmlNote("No frame to show.") : html;
  html += introduction(samples);
  for (const SampleFrame& frame : samples.frames) {
    const std::string caption = escapeHtml(
        fmt::format("{}: frame {}, t = {:.3f} s", frame.role, frame.index, frame.timestamp));
    html += fmt::format(
        "<div class=\"sample\">\n<figure><img class=\"raw\" alt=\"raw frame {0}\" src=\"{1}\">"
        "<figcaption>{2}, raw</figcaption></figure>\n<figure><img class=\"enhanced\" "
        "alt=\"enhanced frame {0}\" src=\"{3}\"><figcaption>{2}, {4}</figcaption></figure>\n"
        "</div>\n",
        frame.index, frame.raw_uri, caption, frame.enhanced_uri, enhancedCaption(frame, samples));
  }
  return html;
}

}  // namespace lumaslam::cli
