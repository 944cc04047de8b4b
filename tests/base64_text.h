#pragma once
// Decoding the base64 of the report's inline images (data: URLs), for the report tests.
#include <string>
#include <vector>

namespace lumaslam::test {

// The bytes of base64 `text` (standard alphabet, '=' padding); empty when a character is not
// base64.
inline std::vector<unsigned char> decodeBase64(const std::string& text) {
  static const std::string digits =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<unsigned char> bytes;
  unsigned int block = 0;
  int bits = 0;
  for (const char c : text) {
    if (c == '=') break;
    const auto value = digits.find(c);
    if (value == std::string::npos) return {};
    block = (block << 6) | static_cast<unsigned int>(value);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      bytes.push_back(static_cast<unsigned char>((block >> bits) & 0xFF));
    }
  }
  return bytes;
}

}  // namespace lumaslam::test
