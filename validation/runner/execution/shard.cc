#include "validation/runner/execution/shard.h"

#include <charconv>
#include <stdexcept>

namespace phdslam::validation {
namespace {

constexpr int kMaxShards = 1'000'000;

int ParsePart(std::string_view part, std::string_view text) {
  int value = 0;
  const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), value);
  if (part.empty() || ec != std::errc() || end != part.data() + part.size() || part[0] == '-' ||
      part[0] == '+') {
    throw std::invalid_argument("--shard '" + std::string(text) +
                                "': expected i/n with integers 1 <= i <= n, e.g. 2/8");
  }
  return value;
}

}  // namespace

Shard ParseShard(std::string_view text) {
  const std::size_t slash = text.find('/');
  if (slash == std::string_view::npos) {
    throw std::invalid_argument("--shard '" + std::string(text) +
                                "': expected i/n with integers 1 <= i <= n, e.g. 2/8");
  }
  Shard shard;
  shard.index = ParsePart(text.substr(0, slash), text);
  shard.count = ParsePart(text.substr(slash + 1), text);
  if (shard.count < 1 || shard.count > kMaxShards) {
    throw std::invalid_argument("--shard '" + std::string(text) + "': n must be in 1.." +
                                std::to_string(kMaxShards));
  }
  if (shard.index < 1 || shard.index > shard.count) {
    throw std::invalid_argument("--shard '" + std::string(text) + "': i must be in 1.." +
                                std::to_string(shard.count) + " (shards are numbered from 1)");
  }
  return shard;
}

}  // namespace phdslam::validation
