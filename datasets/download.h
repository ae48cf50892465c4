// Copies one file from a local folder, a file:// address or an http(s)/ftp address.
#pragma once

#include <filesystem>
#include <string>

namespace phdslam::datasets {

/// The local path of `source` when it is a file:// address or has no scheme ("file:///a/b" and
/// "/a/b" give "/a/b"); empty for another address (http://, https://, ftp://).
std::filesystem::path LocalSourcePath(const std::string& source);

/// Writes the file at `source` to `target` (overwritten). Local sources (LocalSourcePath) are
/// copied; other addresses are downloaded with curl, else wget, found on $PATH. Throws
/// std::runtime_error naming the source: not found, download failed (with the program's exit
/// status), or neither curl nor wget installed (with how to install them).
void DownloadFile(const std::string& source, const std::filesystem::path& target);

/// Extracts the zip archive `archive` into the folder `folder` with unzip, else with python3's
/// zipfile module. Throws std::runtime_error naming the archive when neither is installed or the
/// extraction fails.
void ExtractZip(const std::filesystem::path& archive, const std::filesystem::path& folder);

}  // namespace phdslam::datasets
