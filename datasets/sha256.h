// SHA-256 content checksums of data files (FIPS 180-4).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace phdslam::datasets {

/// The SHA-256 digest of `bytes` as 64 lower-case hexadecimal digits.
std::string Sha256Hex(std::string_view bytes);

/// The SHA-256 digest of the file's content; throws std::runtime_error naming the file when it
/// cannot be read.
std::string FileSha256Hex(const std::filesystem::path& path);

}  // namespace phdslam::datasets
