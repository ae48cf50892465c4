#include "datasets/data_fetch.h"

#include <unistd.h>

#include <memory>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "datasets/data_check.h"
#include "datasets/download.h"

namespace phdslam::datasets {
namespace {

// Removes a temporary file or folder when it goes out of scope.
class TemporaryPath {
 public:
  explicit TemporaryPath(std::filesystem::path path) : path_(std::move(path)) {}
  ~TemporaryPath() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TemporaryPath(const TemporaryPath&) = delete;
  TemporaryPath& operator=(const TemporaryPath&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

std::filesystem::path TemporaryName(const std::filesystem::path& target, const std::string& tag) {
  return target.parent_path() /
         ("." + target.filename().string() + "." + tag + "-" + std::to_string(::getpid()));
}

std::string JoinSource(std::string base, const std::string& path) {
  while (!base.empty() && base.back() == '/') base.pop_back();
  return base + "/" + path;
}

// Checks the file written at `written` and moves it to `target`; throws naming the file.
void VerifyAndInstall(const std::filesystem::path& written, const std::filesystem::path& target,
                      const DataFile& file, const std::string& source) {
  const FileCheck check = VerifyDataFile(written, file);
  if (check.state == FileState::kMissing) {
    throw std::runtime_error(file.path + ": not in '" + source + "'");
  }
  if (check.state == FileState::kCorrupt) {
    throw std::runtime_error(file.path + ": the copy from '" + source + "' does not match (" +
                             check.detail + "); not installed");
  }
  std::filesystem::rename(written, target);
}

// Downloads one file from `source` into place, through a temporary name.
void FetchOne(const DataFile& file, const std::filesystem::path& target,
              const std::string& source) {
  const TemporaryPath part(TemporaryName(target, "part"));
  try {
    DownloadFile(source, part.path());
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(file.path + ": " + e.what());
  }
  VerifyAndInstall(part.path(), target, file, source);
}

// The file of an extracted archive: <folder>/<dataset folder name>/<name> or <folder>/<name>.
std::filesystem::path InArchive(const std::filesystem::path& folder, const DataFile& file) {
  const std::filesystem::path relative(file.path);
  const std::filesystem::path nested =
      folder / relative.parent_path().filename() / relative.filename();
  std::error_code ec;
  return std::filesystem::is_regular_file(nested, ec) ? nested : folder / relative.filename();
}

// Downloads the data set's archive and extracts it into a temporary folder beside its files (so
// that each file moves into place on the same file system).
std::unique_ptr<TemporaryPath> ExtractArchive(const DataSetEntry& entry,
                                              const std::filesystem::path& data_dir,
                                              std::ostream& log) {
  auto folder =
      std::make_unique<TemporaryPath>(TemporaryName(data_dir / entry.folder / "archive", "fetch"));
  std::filesystem::create_directories(folder->path());
  const std::filesystem::path archive = folder->path() / "archive.zip";
  log << "  archive    " << entry.archive_url << "\n";
  DownloadFile(entry.archive_url, archive);
  ExtractZip(archive, folder->path() / "files");
  return folder;
}

}  // namespace

FetchReport FetchDataSet(const DataSetEntry& entry, const std::filesystem::path& data_dir,
                         const std::string& from, std::ostream& log) {
  FetchReport report;
  std::vector<const DataFile*> wanted;
  for (const DataFile& file : entry.files) {
    const FileCheck check = VerifyDataFile(data_dir / file.path, file);
    if (check.state == FileState::kVerified) {
      ++report.already_verified;
      log << "  verified   " << file.path << " (already in place)\n";
    } else {
      wanted.push_back(&file);
    }
  }
  if (wanted.empty()) return report;
  std::filesystem::create_directories(data_dir / entry.folder);
  std::unique_ptr<TemporaryPath> extracted;
  std::string archive_error;
  std::string errors;
  for (const DataFile* file : wanted) {
    const std::filesystem::path target = data_dir / file->path;
    try {
      std::filesystem::create_directories(target.parent_path());
      if (!from.empty() || !file->url.empty()) {
        FetchOne(*file, target, from.empty() ? file->url : JoinSource(from, file->path));
      } else {
        if (!extracted && archive_error.empty()) {
          try {
            extracted = ExtractArchive(entry, data_dir, log);
          } catch (const std::runtime_error& e) {
            archive_error = e.what();
          }
        }
        if (!archive_error.empty()) throw std::runtime_error(file->path + ": " + archive_error);
        VerifyAndInstall(InArchive(extracted->path() / "files", *file), target, *file,
                         entry.archive_url);
      }
      ++report.installed;
      log << "  installed  " << file->path << " (SHA-256 verified)\n";
    } catch (const std::exception& e) {
      log << "  FAILED     " << e.what() << "\n";
      errors += errors.empty() ? e.what() : std::string("; ") + e.what();
    }
  }
  if (!errors.empty()) {
    throw std::runtime_error("data set '" + entry.name + "': " + errors +
                             " (by hand: download from " + entry.home + " into '" +
                             (data_dir / entry.folder).string() + "', then 'phdslam data check')");
  }
  return report;
}

}  // namespace phdslam::datasets
