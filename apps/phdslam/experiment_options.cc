#include "apps/phdslam/experiment_options.h"

#include "apps/phdslam/sign_validators.h"

namespace phdslam::apps {
namespace {

namespace v = phdslam::validation;

// The option's help; for `run`, which also reads experiment files, with the key there.
std::string HelpOf(const v::ExperimentKey& key, ExperimentOptionSet::Keys keys) {
  if (key.file_key.empty() || keys != ExperimentOptionSet::Keys::kAll) return key.help;
  return key.help + " (experiment file key `" + key.file_key + "`)";
}

}  // namespace

CLI::Option* ExperimentOptionSet::Bind(CLI::App* command, Bound& b, Keys keys) {
  const v::ExperimentKey& key = *b.key;
  const std::string help = HelpOf(key, keys);
  switch (key.kind) {
    case v::OptionKind::kText:
      b.text = key.default_text;
      return command->add_option(key.option, b.text, help);
    case v::OptionKind::kCount:
      return command->add_option(key.option, b.count, help)->check(SignValidator(false));
    case v::OptionKind::kNumber:
      return command->add_option(key.option, b.number, help);
    case v::OptionKind::kPositiveNumber:
      return command->add_option(key.option, b.number, help)->check(SignValidator(true));
    case v::OptionKind::kFlag:
      return command->add_flag(key.option, b.flag, help);
    case v::OptionKind::kRepeated:
      return command->add_option(key.option, b.texts, help);
  }
  return nullptr;
}

void ExperimentOptionSet::AddTo(CLI::App* command, Keys keys) {
  for (const v::ExperimentKey& key : v::ExperimentKeys()) {
    if (key.option.empty() || (keys == Keys::kExport && !key.export_option)) continue;
    Bound& b = bound_.emplace_back();
    b.key = &key;
    b.option = Bind(command, b, keys);
    if (!key.default_text.empty()) b.option->capture_default_str();
  }
}

nlohmann::json ExperimentOptionSet::ValueOf(const Bound& b) {
  switch (b.key->kind) {
    case v::OptionKind::kText:
      return b.text;
    case v::OptionKind::kCount:
      return b.count;
    case v::OptionKind::kNumber:
    case v::OptionKind::kPositiveNumber:
      return b.number;
    case v::OptionKind::kFlag:
      return b.flag;
    case v::OptionKind::kRepeated:
      return b.texts;
  }
  return nullptr;
}

std::map<std::string, nlohmann::json> ExperimentOptionSet::Given() const {
  std::map<std::string, nlohmann::json> given;
  for (const Bound& b : bound_) {
    if (b.option->count() > 0) given[b.key->option] = ValueOf(b);
  }
  return given;
}

}  // namespace phdslam::apps
