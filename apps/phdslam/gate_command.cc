#include "apps/phdslam/gate_command.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <vector>

#include "apps/phdslam/exit_codes.h"

namespace phdslam::apps {
namespace {

/// The checker: $PHDSLAM_GATES_SCRIPT, else the source tree's ci/gates.py compiled in.
std::string GatesScript() {
  if (const char* env = std::getenv("PHDSLAM_GATES_SCRIPT"); env != nullptr && *env != '\0') {
    return env;
  }
  return PHDSLAM_GATES_SCRIPT;
}

int RunAndWait(std::vector<std::string> words) {
  std::vector<char*> argv;
  argv.reserve(words.size() + 1);
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  const pid_t child = fork();
  if (child < 0) {
    std::cerr << "phdslam gate: error: cannot start python3: " << std::strerror(errno) << "\n";
    return kExitRunFailed;
  }
  if (child == 0) {
    execvp(argv[0], argv.data());
    std::cerr << "phdslam gate: error: cannot run python3 (" << std::strerror(errno)
              << "); install Debian's python3 and python3-yaml (ci/install-deps.sh)\n";
    _exit(kExitUsage);
  }
  int status = 0;
  while (waitpid(child, &status, 0) < 0) {
    if (errno != EINTR) return kExitRunFailed;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : kExitRunFailed;
}

}  // namespace

void AddGateCommand(CLI::App& app, GateArguments& a) {
  CLI::App* gate = app.add_subcommand(
      "gate",
      "Accuracy gates over a results folder (ci/GATES.md): the exact tier (every non-timing "
      "column of runs.csv against the stored baseline, run by run), the paired tier (a one-sided "
      "paired test per gated metric, with its seeds, margin, minimum detectable effect and "
      "power) and the anchor tier (the published values). Prints one table per tier; exit 0 when "
      "every gate passes, 1 when one fails, 2 for bad input (naming the file and field). Runs "
      "ci/gates.py check (PHDSLAM_GATES_SCRIPT overrides its path).");
  gate->add_option("--gates", a.gates, "Gates file (e.g. ci/gates.yaml)")->required();
  gate->add_option("--results", a.results,
                   "Results folder: <results>/<suite>/runs.csv per suite of the gates file, or "
                   "<results>/runs.csv when it has one suite")
      ->required();
  gate->add_option("--baseline", a.baseline,
                   "Baseline folder (default: the gates file's `baseline`)");
  gate->add_option("--tiers", a.tiers, "Comma list of exact, paired, anchor")
      ->capture_default_str();
  gate->add_option("--csv", a.csv, "Also write one row per gate to this CSV file");
}

int Gate(const GateArguments& a) {
  const std::string script = GatesScript();
  if (!std::filesystem::is_regular_file(script)) {
    std::cerr << "phdslam gate: error: the checker " << script
              << " does not exist; set PHDSLAM_GATES_SCRIPT to ci/gates.py of the source tree\n";
    return kExitUsage;
  }
  std::vector<std::string> words = {"python3",   script,    "check",   "--gates", a.gates,
                                    "--results", a.results, "--tiers", a.tiers};
  if (!a.baseline.empty()) words.insert(words.end(), {"--baseline", a.baseline});
  if (!a.csv.empty()) words.insert(words.end(), {"--csv", a.csv});
  return RunAndWait(std::move(words));
}

}  // namespace phdslam::apps
