// Well-formed UTF-8 (RFC 3629; table 3-7 of the Unicode standard) and a readable escape for the
// bytes that are not: text read from a hostile file may hold any bytes, but JSON, and so every
// message or results file built with nlohmann::json, holds UTF-8 only.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace phdslam {

/// The length (1 to 4) of the well-formed UTF-8 sequence that starts at `text[i]`, or 0 when the
/// byte there does not start one (a stray continuation byte, an overlong form, a surrogate, a
/// code point above U+10FFFF or a sequence cut short). `i` must be < text.size().
inline std::size_t Utf8SequenceLength(std::string_view text, std::size_t i) {
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

/// True when all of `text` is well-formed UTF-8.
inline bool IsUtf8(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t length = Utf8SequenceLength(text, i);
    if (length == 0) return false;
    i += length;
  }
  return true;
}

/// "\xNN" (two upper-case hexadecimal digits) for one byte.
inline std::string EscapedByte(char byte) {
  constexpr std::string_view kDigits = "0123456789ABCDEF";
  const auto b = static_cast<unsigned char>(byte);
  return {'\\', 'x', kDigits[b >> 4U], kDigits[b & 0x0FU]};
}

/// Calls `valid(run)` for each maximal run of well-formed UTF-8 in `text` and `invalid(byte)` for
/// each byte that is not part of one, in order.
template <class OnValid, class OnInvalid>
void ForEachUtf8Run(std::string_view text, OnValid valid, OnInvalid invalid) {
  std::size_t start = 0;
  std::size_t i = 0;
  while (i < text.size()) {
    const std::size_t length = Utf8SequenceLength(text, i);
    if (length > 0) {
      i += length;
      continue;
    }
    if (i > start) valid(text.substr(start, i - start));
    invalid(text[i]);
    start = ++i;
  }
  if (i > start) valid(text.substr(start, i - start));
}

/// `text` with every byte that is not part of well-formed UTF-8 written as \xNN, so that the
/// result is UTF-8 and still shows which bytes were there; well-formed text is returned as is.
inline std::string EscapeNonUtf8(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  ForEachUtf8Run(
      text, [&](std::string_view run) { out.append(run); },
      [&](char byte) { out += EscapedByte(byte); });
  return out;
}

}  // namespace phdslam
