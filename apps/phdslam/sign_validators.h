// Validators for options that must be positive or non-negative. CLI11's own PositiveNumber and
// NonNegativeNumber print their range with the largest double written out (309 digits); these
// say what is expected and what was given.
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <string>

namespace phdslam::apps {

/// Accepts a finite number > 0 (`positive`) or >= 0 (otherwise).
inline CLI::Validator SignValidator(bool positive) {
  const std::string name = positive ? "POSITIVE" : "NONNEGATIVE";
  return CLI::Validator(
      [positive](std::string& text) -> std::string {
        double value = 0.0;
        if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value)) {
          return "'" + text + "' is not a finite number";
        }
        if (positive ? value > 0.0 : value >= 0.0) return "";
        return std::string("expected a value ") + (positive ? "> 0" : ">= 0") + ", got " + text;
      },
      name, name);
}

}  // namespace phdslam::apps
