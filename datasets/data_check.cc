#include "datasets/data_check.h"

#include <system_error>

#include "datasets/data_dir.h"
#include "datasets/sha256.h"

namespace phdslam::datasets {
namespace {

bool AllMissing(const DataSetCheck& check) {
  for (const FileCheck& f : check.files) {
    if (f.state != FileState::kMissing) return false;
  }
  return true;
}

DataSetCheck CheckIn(const std::filesystem::path& dir, const DataSetEntry& entry) {
  DataSetCheck check;
  check.name = entry.name;
  check.dir = dir;
  for (const DataFile& file : entry.files)
    check.files.push_back(VerifyDataFile(dir / file.path, file));
  return check;
}

}  // namespace

std::string FileStateName(FileState state) {
  switch (state) {
    case FileState::kVerified:
      return "verified";
    case FileState::kMissing:
      return "missing";
    case FileState::kCorrupt:
      return "corrupt";
  }
  return "corrupt";
}

FileCheck VerifyDataFile(const std::filesystem::path& path, const DataFile& expected) {
  FileCheck check{path, FileState::kMissing, ""};
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return check;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || size != expected.size) {
    check.state = FileState::kCorrupt;
    check.detail = "size " + (ec ? std::string("unreadable") : std::to_string(size)) +
                   " bytes, expected " + std::to_string(expected.size);
    return check;
  }
  const std::string sha256 = FileSha256Hex(path);
  if (sha256 != expected.sha256) {
    check.state = FileState::kCorrupt;
    check.detail = "SHA-256 " + sha256 + ", expected " + expected.sha256;
    return check;
  }
  check.state = FileState::kVerified;
  return check;
}

std::string DataSetCheck::State() const {
  bool missing = false;
  for (const FileCheck& f : files) {
    if (f.state == FileState::kCorrupt) return "corrupt";
    if (f.state == FileState::kMissing) missing = true;
  }
  return missing ? "missing" : "present";
}

DataSetCheck CheckDataSet(const std::filesystem::path& data_dir, const DataSetEntry& entry) {
  DataSetCheck check = CheckIn(data_dir, entry);
  if (entry.bundled && AllMissing(check)) {
    check = CheckIn(BundledDataDir(), entry);
    check.from_repository = true;
  }
  return check;
}

}  // namespace phdslam::datasets
