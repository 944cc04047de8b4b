#pragma once
// Where each key of a YAML settings text is set, found by a light line scan beside
// cv::FileStorage, which keeps one of two equal keys without a word and stores integers in
// 32 bits. Block maps only: keys inside flow collections ({a: 1}) and sequences are not seen.
#include <map>
#include <string>
#include <string_view>

namespace lumaslam::core {

struct KeyLine {
  int line = 0;       // 1-based, in `text`
  std::string value;  // as written, without a trailing comment; empty for a map's key
};

// One line of YAML without its comment ('#' at the start or after a blank, outside quotes).
std::string_view withoutComment(std::string_view line);

// Keys in flat form: nested block maps are joined with '.', so `Camera.fx: 1` and
// `Camera:\n  fx: 1` are the same key. Throws Error "ORIGIN: key 'K' is set twice: lines A and
// B" when a key is set twice.
std::map<std::string, KeyLine> scanKeyLines(std::string_view text, const std::string& origin);

// Before cv::FileStorage reads `text`: OpenCV 4.6's YAML parser never returns on some lines
// that start with the document marker "---" followed by text ("----x", "---YAML:..."; found
// by fuzzing, fuzz/regressions/settings/). Throws Error "ORIGIN: line N: ..." for a line that
// starts with "---" directly followed by anything but a blank.
void requireBlankAfterDocumentMarkers(std::string_view text, const std::string& origin);

// Before cv::FileStorage reads `text`: YAML is Unicode text, and OpenCV 4.6's YAML parser never
// returns on some inputs with bytes that are not UTF-8 (found by fuzzing settings files and
// EuRoC sensor.yaml, fuzz/regressions/). Throws Error "ORIGIN: line N: not UTF-8 text (byte
// 0xXX at column C)" for a NUL byte or a byte sequence that is not UTF-8.
void requireUtf8Text(std::string_view text, const std::string& origin);

}  // namespace lumaslam::core
