// libFuzzer target: an experiment file's text. The parser must accept it or throw
// std::invalid_argument naming the file; any other exception is a finding.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string_view>

#include "validation/runner/experiment/experiment_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    (void)phdslam::validation::ParseExperimentYaml(text, "input.yaml", "input");
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
