// Fuzz-target helper: the input bytes written to a file in a folder of the process's own, for
// readers that take a path.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace phdslam::fuzz {

/// <tmp>/phdslam-fuzz-<pid>/, created on first use.
inline std::filesystem::path ScratchFolder() {
  std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("phdslam-fuzz-" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  return folder;
}

/// Writes `size` bytes at `data` to `path` (replacing it).
inline void WriteInput(const std::filesystem::path& path, const std::uint8_t* data,
                       std::size_t size) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
}

}  // namespace phdslam::fuzz
