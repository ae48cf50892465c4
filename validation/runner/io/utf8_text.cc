#include "validation/runner/io/utf8_text.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "src/core/utf8.h"

namespace phdslam::validation {

std::optional<std::size_t> FirstInvalidUtf8Byte(std::string_view text) {
  std::size_t i = 0;
  while (i < text.size()) {
    const std::size_t length = Utf8SequenceLength(text, i);
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
