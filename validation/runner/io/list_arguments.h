// Parsing of the list-valued command-line arguments that select Monte Carlo runs:
// seeds ("1-100", "7", "1,3,10-12"), particle counts ("1,10,100") and names ("phd3,odometry").
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace phdslam::validation {

/// Parses a comma list of seeds and inclusive ranges a-b (a <= b). Seeds are decimal integers in
/// [0, 2^64 - 1]; spaces around items are allowed. Returns the seeds in the order given.
/// Throws std::invalid_argument for an empty list or item, a non-number, a reversed range, more
/// than kMaxSeeds seeds in all or a seed listed twice.
std::vector<std::uint64_t> ParseSeedList(std::string_view text);

/// Most particles one filter may use (memory grows with particles x map size).
inline constexpr int kMaxParticles = 100000;
/// The most seeds one list may give, and the most runs one results folder may plan (monte_carlo.h):
/// each planned run holds about 200 bytes before the first one starts (measured: 206 MB for
/// 10^6 seeds), and a folder of 10^6 run folders is already slow to list. Larger studies are
/// split over several results folders.
inline constexpr std::uint64_t kMaxSeeds = 1'000'000;

/// Parses a comma list of particle counts, each a positive decimal int. Throws
/// std::invalid_argument for an empty list or item, a non-number, a value < 1 or
/// > kMaxParticles, or a duplicate.
std::vector<int> ParseParticleList(std::string_view text);

/// Parses a comma list of names (no empty items, no duplicates); spaces are trimmed.
std::vector<std::string> ParseNameList(std::string_view text, std::string_view what);

}  // namespace phdslam::validation
