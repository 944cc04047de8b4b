#include "lumaslam/core/settings_lines.h"

#include <optional>
#include <utility>
#include <vector>

#include "lumaslam/core/error.h"

namespace lumaslam::core {
namespace {

std::string_view trimmed(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

bool startsToken(std::string_view s, std::size_t i) {
  return i == 0 || std::string_view(" \t:[{,").find(s[i - 1]) != std::string_view::npos;
}

// Calls on_char(i) for each character outside quoted strings; stops at a comment ('#' at the
// start or after a blank) and returns where the uncommented text ends.
template <typename OnChar>
std::size_t scanUnquoted(std::string_view s, OnChar on_char) {
  char quote = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (quote) {
      if (quote == '"' && c == '\\')
        ++i;
      else if (c == quote)
        quote = 0;
    } else if ((c == '"' || c == '\'') && startsToken(s, i)) {
      quote = c;
    } else if (c == '#' && (i == 0 || s[i - 1] == ' ' || s[i - 1] == '\t')) {
      return i;
    } else {
      on_char(i);
    }
  }
  return s.size();
}

// Change of the flow-collection depth ([ and {) over `s`.
int flowDepthChange(std::string_view s) {
  int depth = 0;
  scanUnquoted(s, [&](std::size_t i) {
    if (s[i] == '[' || s[i] == '{') ++depth;
    if (s[i] == ']' || s[i] == '}') --depth;
  });
  return depth;
}

bool isDocumentMarker(std::string_view content) {
  return content.starts_with('%') || content == "---" || content.starts_with("--- ") ||
         content == "...";
}

struct KeyValue {
  std::string key;
  std::string_view value;
};

// "key: value" (key plain or quoted); nullopt for a line that sets no key.
std::optional<KeyValue> splitKey(std::string_view content) {
  if (content.starts_with('"') || content.starts_with('\'')) {
    const auto close = content.find(content[0], 1);
    if (close == std::string_view::npos) return std::nullopt;
    const auto rest = trimmed(content.substr(close + 1));
    if (!rest.starts_with(':')) return std::nullopt;
    return KeyValue{std::string(content.substr(1, close - 1)), trimmed(rest.substr(1))};
  }
  if (std::string_view("-[{]},").find(content[0]) != std::string_view::npos) return std::nullopt;
  for (std::size_t colon = content.find(':'); colon != std::string_view::npos;
       colon = content.find(':', colon + 1)) {
    if (colon + 1 == content.size() || content[colon + 1] == ' ' || content[colon + 1] == '\t') {
      return KeyValue{std::string(trimmed(content.substr(0, colon))),
                      trimmed(content.substr(colon + 1))};
    }
  }
  return std::nullopt;
}

struct OpenKey {
  std::size_t indent;
  std::string key;
};

class KeyScanner {
 public:
  explicit KeyScanner(const std::string& origin) : origin_(origin) {}

  void scanLine(std::string_view raw, int number) {
    const std::size_t indent = raw.find_first_not_of(' ');
    const std::string_view content = trimmed(withoutComment(raw));
    if (content.empty()) return;
    if (flow_depth_ > 0) {  // continuation of a [list] or {map} opened above
      flow_depth_ += flowDepthChange(content);
      return;
    }
    if (block_indent_ && indent > *block_indent_) return;  // text of a | or > block
    block_indent_.reset();
    if (indent == 0 && isDocumentMarker(content)) return;
    const auto entry = splitKey(content);
    if (!entry) return;
    add(indent, entry->key, entry->value, number);
    flow_depth_ = std::max(0, flowDepthChange(entry->value));
    if (entry->value.starts_with('|') || entry->value.starts_with('>')) block_indent_ = indent;
  }

  std::map<std::string, KeyLine> take() { return std::move(keys_); }

 private:
  void add(std::size_t indent, const std::string& key, std::string_view value, int number) {
    while (!open_.empty() && open_.back().indent >= indent) open_.pop_back();
    const std::string flat = open_.empty() ? key : open_.back().key + "." + key;
    const auto [it, inserted] = keys_.try_emplace(flat, KeyLine{number, std::string(value)});
    if (!inserted) {
      fail("{}: key '{}' is set twice: lines {} and {}", origin_, flat, it->second.line, number);
    }
    open_.push_back({indent, flat});
  }

  const std::string& origin_;
  std::map<std::string, KeyLine> keys_;
  std::vector<OpenKey> open_;  // the maps the next line may be inside, outermost first
  int flow_depth_ = 0;
  std::optional<std::size_t> block_indent_;
};

}  // namespace

std::string_view withoutComment(std::string_view line) {
  return line.substr(0, scanUnquoted(line, [](std::size_t) {}));
}

std::map<std::string, KeyLine> scanKeyLines(std::string_view text, const std::string& origin) {
  KeyScanner scanner(origin);
  int number = 1;
  for (std::size_t start = 0; start <= text.size(); ++number) {
    auto end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    scanner.scanLine(text.substr(start, end - start), number);
    start = end + 1;
  }
  return scanner.take();
}

void requireBlankAfterDocumentMarkers(std::string_view text, const std::string& origin) {
  int number = 1;
  for (std::size_t start = 0; start < text.size(); ++number) {
    auto end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(start, end - start);
    start = end + 1;
    // "---", "--- # ..." and "--- !tag" are markers; "----x" and "---YAML" are what loops.
    if (!line.starts_with("---") || line.size() == 3) continue;
    if (line[3] == ' ' || line[3] == '\t' || line[3] == '\r') continue;
    fail(
        "{}: line {}: '---' (a YAML document marker) must be followed by a blank or end the "
        "line",
        origin, number);
  }
}

namespace {

// Bytes a UTF-8 sequence starting with `lead` takes (0: not a lead byte; C0/C1 and F5-FF never
// appear in UTF-8).
int utf8Length(unsigned char lead) {
  if (lead < 0x80) return 1;
  if (lead >= 0xC2 && lead <= 0xDF) return 2;
  if (lead >= 0xE0 && lead <= 0xEF) return 3;
  if (lead >= 0xF0 && lead <= 0xF4) return 4;
  return 0;
}

bool isContinuation(unsigned char byte) {
  return (byte & 0xC0) == 0x80;
}

// Length of the valid UTF-8 sequence at `at`, or 0.
std::size_t validSequenceAt(std::string_view text, std::size_t at) {
  const auto lead = static_cast<unsigned char>(text[at]);
  if (lead == 0) return 0;
  const auto length = static_cast<std::size_t>(utf8Length(lead));
  if (length == 0 || at + length > text.size()) return 0;
  for (std::size_t k = 1; k < length; ++k) {
    if (!isContinuation(static_cast<unsigned char>(text[at + k]))) return 0;
  }
  return length;
}

}  // namespace

void requireUtf8Text(std::string_view text, const std::string& origin) {
  int line = 1;
  std::size_t line_start = 0;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t length = validSequenceAt(text, at);
    if (length == 0) {
      fail("{}: line {}: not UTF-8 text (byte 0x{:02x} at column {}); YAML files are text", origin,
           line, static_cast<unsigned char>(text[at]), at - line_start + 1);
    }
    if (text[at] == '\n') {
      ++line;
      line_start = at + 1;
    }
    at += length;
  }
}

}  // namespace lumaslam::core
