// Programs the data command runs when they are installed (curl or wget, unzip), found at run time.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace phdslam::datasets {

/// The first executable called `name` in the folders of $PATH; nullopt when there is none.
std::optional<std::filesystem::path> FindProgram(const std::string& name);

/// Runs `program` with `arguments` (no shell), standard input closed, and waits for it. Returns
/// its exit status (128 + the signal when a signal ended it); throws std::runtime_error naming the
/// program when it cannot be started.
int RunProgram(const std::filesystem::path& program, const std::vector<std::string>& arguments);

}  // namespace phdslam::datasets
