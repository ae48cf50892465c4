// A check of a shared object's file before dlopen maps it: a file cut short (a copy interrupted,
// a disk full) is mapped past its end and the process dies of SIGBUS on first touch, without a
// word; a foreign file is refused by dlopen only after it mapped what it could.
#pragma once

#include <filesystem>

namespace phdslam::reference {

/// Throws std::runtime_error naming `path` (and saying that it does not exist, is not a regular
/// file, is cut short or is not an ELF object of this machine) unless it is a regular file holding
/// a complete ELF shared object of this machine's class, byte order and architecture: its header,
/// program headers, every loaded segment and its section headers lie inside the file.
void RequireCompleteSharedObject(const std::filesystem::path& path);

}  // namespace phdslam::reference
