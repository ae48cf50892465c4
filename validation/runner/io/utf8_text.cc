#include "validation/runner/io/utf8_text.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace phdslam::validation {
namespace {

// The length of the well-formed sequence starting at `text[i]`, or 0 (RFC 3629, table 3-7 of
// the Unicode standard: the second byte's range depends on the first).
std::size_t SequenceLength(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char b0 = byte(i);
  if (b0 < 0x80) return 1;
  std::size_t length = 0;
  unsigned char low = 0x80;
  unsigned char high = 0xBF;
  if (b0 >= 0xC2 && b0 <= 0xDF) {
    length = 2;
  } else if (b0 >= 0xE0 && b0 <= 0xEF) {
    length = 3;
    if (b0 == 0xE0) low = 0xA0;   // no overlong form
    if (b0 == 0xED) high = 0x9F;  // no surrogate
  } else if (b0 >= 0xF0 && b0 <= 0xF4) {
    length = 4;
    if (b0 == 0xF0) low = 0x90;   // no overlong form
    if (b0 == 0xF4) high = 0x8F;  // nothing above U+10FFFF
  } else {
    return 0;
  }
  if (i + length > text.size()) return 0;
  if (byte(i + 1) < low || byte(i + 1) > high) return 0;
  for (std::size_t k = 2; k < length; ++k) {
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
  }
  return length;
}

}  // namespace

std::optional<std::size_t> FirstInvalidUtf8Byte(std::string_view text) {
  std::size_t i = 0;
  while (i < text.size()) {
    const std::size_t length = SequenceLength(text, i);
    if (length == 0) return i;
    i += length;
  }
  return std::nullopt;
}

std::string ByteText(char byte) {
  char hex[8];
  std::snprintf(hex, sizeof hex, "0x%02X", static_cast<unsigned>(static_cast<unsigned char>(byte)));
  return hex;
}

void RequireUtf8(std::string_view text, const std::string& source) {
  const std::optional<std::size_t> bad = FirstInvalidUtf8Byte(text);
  if (!bad) return;
  const std::string_view before = text.substr(0, *bad);
  const std::size_t line =
      1 + static_cast<std::size_t>(std::count(before.begin(), before.end(), '\n'));
  const std::size_t line_start = before.rfind('\n');
  const std::size_t column = *bad - (line_start == std::string_view::npos ? 0 : line_start + 1) + 1;
  throw std::invalid_argument(source + ": line " + std::to_string(line) + ", column " +
                              std::to_string(column) + ": not valid UTF-8 (byte " +
                              ByteText(text[*bad]) + ")");
}

}  // namespace phdslam::validation
