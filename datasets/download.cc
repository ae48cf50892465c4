#include "datasets/download.h"

#include <optional>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "datasets/external_program.h"

namespace phdslam::datasets {
namespace {

constexpr const char* kFileScheme = "file://";

void CopyLocal(const std::filesystem::path& from, const std::string& source,
               const std::filesystem::path& target) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(from, ec)) {
    throw std::runtime_error("'" + source + "': no such file");
  }
  std::filesystem::copy_file(from, target, std::filesystem::copy_options::overwrite_existing, ec);
  if (ec) throw std::runtime_error("copying '" + source + "': " + ec.message());
}

void DownloadRemote(const std::string& source, const std::filesystem::path& target) {
  int status = 0;
  std::string program;
  if (const std::optional<std::filesystem::path> curl = FindProgram("curl")) {
    program = "curl";
    status = RunProgram(*curl, {"--fail", "--location", "--silent", "--show-error", "--output",
                                target.string(), source});
  } else if (const std::optional<std::filesystem::path> wget = FindProgram("wget")) {
    program = "wget";
    status = RunProgram(*wget, {"--quiet", "--output-document=" + target.string(), source});
  } else {
    throw std::runtime_error("cannot download '" + source +
                             "': neither curl nor wget is installed (apt-get install curl, or "
                             "download it by hand and use --from DIR)");
  }
  if (status != 0) {
    throw std::runtime_error("downloading '" + source + "' with " + program + " failed (exit " +
                             std::to_string(status) + ")");
  }
}

}  // namespace

std::filesystem::path LocalSourcePath(const std::string& source) {
  if (source.rfind(kFileScheme, 0) == 0) return source.substr(std::string(kFileScheme).size());
  if (source.find("://") == std::string::npos) return source;
  return {};
}

void DownloadFile(const std::string& source, const std::filesystem::path& target) {
  const std::filesystem::path local = LocalSourcePath(source);
  if (!local.empty()) {
    CopyLocal(local, source, target);
  } else {
    DownloadRemote(source, target);
  }
}

void ExtractZip(const std::filesystem::path& archive, const std::filesystem::path& folder) {
  int status = 0;
  if (const std::optional<std::filesystem::path> unzip = FindProgram("unzip")) {
    status = RunProgram(*unzip, {"-q", "-o", archive.string(), "-d", folder.string()});
  } else if (const std::optional<std::filesystem::path> python = FindProgram("python3")) {
    status = RunProgram(*python, {"-m", "zipfile", "-e", archive.string(), folder.string()});
  } else {
    throw std::runtime_error("cannot extract '" + archive.string() +
                             "': neither unzip nor python3 is installed (apt-get install unzip)");
  }
  if (status != 0) {
    throw std::runtime_error("extracting '" + archive.string() + "' failed (exit " +
                             std::to_string(status) + ")");
  }
}

}  // namespace phdslam::datasets
