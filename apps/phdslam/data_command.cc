#include "apps/phdslam/data_command.h"

#include <iostream>
#include <optional>

#include "apps/phdslam/exit_codes.h"
#include "datasets/data_catalog.h"
#include "datasets/data_check.h"
#include "datasets/data_dir.h"
#include "datasets/data_fetch.h"

namespace phdslam::apps {
namespace {

namespace d = phdslam::datasets;

constexpr const char* kDataDirHelp =
    "Data folder (default: $PHDSLAM_DATA, then the compiled default ../shared/datasets)";

d::DataDirSetting Folder(const DataArguments& a) {
  return d::DataDirFromSettings(a.data_dir.empty() ? std::nullopt
                                                   : std::optional<std::string>(a.data_dir));
}

void PrintCheck(const d::DataSetCheck& check, const d::DataSetEntry& entry) {
  std::cout << entry.name << ": " << check.State();
  if (check.from_repository) std::cout << " (the repository's copy, " << check.dir.string() << ")";
  if (check.State() == "missing") std::cout << " (phdslam data fetch " << entry.name << ")";
  std::cout << "\n";
  for (const d::FileCheck& f : check.files) {
    std::cout << "  " << d::FileStateName(f.state)
              << std::string(10 - d::FileStateName(f.state).size(), ' ') << f.path.string()
              << (f.detail.empty() ? "" : " (" + f.detail + ")") << "\n";
  }
}

int Check(const DataArguments& a) {
  const d::DataDirSetting folder = Folder(a);
  std::cout << "data folder: " << folder.dir.string() << " (from " << folder.origin << ")\n";
  bool corrupt = false;
  for (const d::DataSetEntry& entry : d::DataSetCatalog()) {
    const d::DataSetCheck check = d::CheckDataSet(folder.dir, entry);
    PrintCheck(check, entry);
    corrupt = corrupt || check.State() == "corrupt";
  }
  return corrupt ? kExitRunFailed : 0;
}

std::vector<const d::DataSetEntry*> Requested(const std::vector<std::string>& names) {
  std::vector<const d::DataSetEntry*> entries;
  for (const std::string& name : names) {
    if (name == "all") {
      for (const d::DataSetEntry& e : d::DataSetCatalog()) entries.push_back(&e);
    } else {
      entries.push_back(&d::FindDataSet(name));  // std::invalid_argument: a usage error
    }
  }
  return entries;
}

int Fetch(const DataArguments& a) {
  const std::vector<const d::DataSetEntry*> entries = Requested(a.names);
  const d::DataDirSetting folder = Folder(a);
  std::cout << "data folder: " << folder.dir.string() << " (from " << folder.origin << ")\n";
  bool failed = false;
  for (const d::DataSetEntry* entry : entries) {
    std::cout << entry->name << ": from "
              << (a.from.empty() ? std::string("its public sources") : a.from) << "\n";
    try {
      const d::FetchReport r = d::FetchDataSet(*entry, folder.dir, a.from, std::cout);
      std::cout << entry->name << ": " << r.installed << " files installed, " << r.already_verified
                << " already verified\n";
    } catch (const std::runtime_error& e) {
      std::cerr << "phdslam: error: " << e.what() << "\n";
      failed = true;
    }
  }
  return failed ? kExitRunFailed : 0;
}

}  // namespace

void AddDataCommand(CLI::App& app, DataArguments& a) {
  CLI::App* data = app.add_subcommand(
      "data",
      "The data sets: 'fetch' downloads them into the data folder, 'check' lists what it holds. "
      "Every file is checked against the SHA-256 list kept in the repository. The synthetic "
      "scenario is carried in the repository (datasets/data) and needs no data folder.");
  data->require_subcommand(1);
  CLI::App* fetch = data->add_subcommand(
      "fetch",
      "Downloads data sets (synthetic, victoria-park, mrclam, or all) into the data folder: each "
      "file to a temporary name beside its place, checked against its size and SHA-256, then "
      "moved there; a file that does not match is not installed and is named (exit 1). Files "
      "already verified are kept. Public sources: the PHD-SLAM 3.0 and RFS-SLAM repositories on "
      "GitHub, the MRCLAM archive of UTIAS (curl or wget; unzip or python3 for the archive). By "
      "hand: put the files at the paths 'phdslam data check' lists, or pass the folder as --from "
      "(docs/guide/data-and-credits.md).");
  fetch->add_option("names", a.names, "Data sets: synthetic, victoria-park, mrclam, all")
      ->required();
  fetch->add_option("--from", a.from,
                    "A copy laid out as a data folder (<from>/victoria-park/measurements.dat, "
                    "...): a folder, a file:// address or an http(s) address; default: the "
                    "public sources");
  fetch->add_option("--data-dir", a.data_dir, kDataDirHelp);
  CLI::App* check = data->add_subcommand(
      "check",
      "Lists each data set (synthetic, victoria-park, mrclam) as present, missing or corrupt, "
      "and each of its files as verified, missing or corrupt (size or SHA-256 differs). Exit 1 "
      "when a file is corrupt, 0 otherwise (missing data sets included).");
  check->add_option("--data-dir", a.data_dir, kDataDirHelp);
}

int Data(const CLI::App& app, const DataArguments& a) {
  const CLI::App* data = app.get_subcommand("data");
  if (data->got_subcommand("fetch")) return Fetch(a);
  return Check(a);
}

}  // namespace phdslam::apps
