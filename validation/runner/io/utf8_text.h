// UTF-8 validation of text that reaches the results files. config.json records the experiment
// file and every --set value; JSON text must be UTF-8, so invalid bytes are refused where they
// enter, with their position, instead of failing later when the configuration is written.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace phdslam::validation {

/// The offset of the first byte of `text` that does not start or continue a well-formed UTF-8
/// sequence (RFC 3629: no overlong forms, no surrogates, nothing above U+10FFFF), or nullopt.
std::optional<std::size_t> FirstInvalidUtf8Byte(std::string_view text);

/// "0xHH": a byte as error messages show it.
std::string ByteText(char byte);

/// Throws std::invalid_argument "<source>: line L, column C: not valid UTF-8 (byte 0xHH)" at the
/// first invalid byte; lines and columns count from 1, columns in bytes.
void RequireUtf8(std::string_view text, const std::string& source);

}  // namespace phdslam::validation
