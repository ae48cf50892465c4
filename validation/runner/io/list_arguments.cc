#include "validation/runner/io/list_arguments.h"

#include <algorithm>
#include <charconv>
#include <limits>
#include <stdexcept>
#include <type_traits>

namespace phdslam::validation {
namespace {

std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> SplitCommas(std::string_view text, std::string_view what) {
  if (Trim(text).empty()) throw std::invalid_argument(std::string(what) + ": empty list");
  std::vector<std::string_view> items;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string_view item = Trim(text.substr(start, comma - start));
    if (item.empty()) {
      throw std::invalid_argument(std::string(what) + " '" + std::string(text) +
                                  "': empty item in comma list");
    }
    items.push_back(item);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return items;
}

template <typename T>
T ParseNumber(std::string_view item, std::string_view what, std::string_view text) {
  T value{};
  const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), value);
  if (ec == std::errc::result_out_of_range) {
    throw std::invalid_argument(std::string(what) + " '" + std::string(text) + "': '" +
                                std::string(item) + "' is out of range");
  }
  if (ec != std::errc() || end != item.data() + item.size() || item.front() == '-' ||
      item.front() == '+') {
    throw std::invalid_argument(std::string(what) + " '" + std::string(text) + "': '" +
                                std::string(item) + "' is not a non-negative integer");
  }
  return value;
}

template <typename T>
void RejectDuplicates(std::vector<T> values, std::string_view what, std::string_view text) {
  std::sort(values.begin(), values.end());
  const auto dup = std::adjacent_find(values.begin(), values.end());
  if (dup != values.end()) {
    std::string shown;
    if constexpr (std::is_same_v<T, std::string>) {
      shown = *dup;
    } else {
      shown = std::to_string(*dup);
    }
    throw std::invalid_argument(std::string(what) + " '" + std::string(text) + "': " + shown +
                                " is listed twice");
  }
}

std::invalid_argument TooManySeeds(std::string_view text) {
  return std::invalid_argument("seeds '" + std::string(text) + "': more than " +
                               std::to_string(kMaxSeeds) +
                               " seeds; split them over several results folders");
}

}  // namespace

std::vector<std::uint64_t> ParseSeedList(std::string_view text) {
  constexpr std::string_view kWhat = "seeds";
  std::vector<std::uint64_t> seeds;
  for (std::string_view item : SplitCommas(text, kWhat)) {
    const std::size_t dash = item.find('-', 1);  // a leading '-' is a sign, rejected below
    if (dash == std::string_view::npos) {
      if (seeds.size() >= kMaxSeeds) throw TooManySeeds(text);
      seeds.push_back(ParseNumber<std::uint64_t>(item, kWhat, text));
      continue;
    }
    const auto first = ParseNumber<std::uint64_t>(Trim(item.substr(0, dash)), kWhat, text);
    const std::string_view last_text = Trim(item.substr(dash + 1));
    if (last_text.empty()) {
      throw std::invalid_argument("seeds '" + std::string(text) + "': range '" + std::string(item) +
                                  "' has no upper end (expected a-b)");
    }
    const auto last = ParseNumber<std::uint64_t>(last_text, kWhat, text);
    if (last < first) {
      throw std::invalid_argument("seeds '" + std::string(text) + "': range '" + std::string(item) +
                                  "' is reversed (expected a-b with a <= b)");
    }
    if (last - first >= kMaxSeeds - seeds.size()) throw TooManySeeds(text);
    for (std::uint64_t s = first;; ++s) {
      seeds.push_back(s);
      if (s == last) break;
    }
  }
  RejectDuplicates(seeds, kWhat, text);
  return seeds;
}

std::vector<int> ParseParticleList(std::string_view text) {
  constexpr std::string_view kWhat = "particles";
  std::vector<int> particles;
  for (std::string_view item : SplitCommas(text, kWhat)) {
    const int n = ParseNumber<int>(item, kWhat, text);
    if (n < 1) {
      throw std::invalid_argument("particles '" + std::string(text) + "': " + std::to_string(n) +
                                  " is not a positive particle count");
    }
    if (n > kMaxParticles) {
      throw std::invalid_argument("particles '" + std::string(text) + "': " + std::to_string(n) +
                                  " is more than the " + std::to_string(kMaxParticles) +
                                  " particles accepted per filter");
    }
    particles.push_back(n);
  }
  RejectDuplicates(particles, kWhat, text);
  return particles;
}

std::vector<std::string> ParseNameList(std::string_view text, std::string_view what) {
  std::vector<std::string> names;
  for (std::string_view item : SplitCommas(text, what)) names.emplace_back(item);
  RejectDuplicates(names, what, text);
  return names;
}

}  // namespace phdslam::validation
