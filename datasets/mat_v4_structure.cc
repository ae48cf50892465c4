#include "datasets/mat_v4_structure.h"

#include <bit>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace phdslam::datasets {
namespace {

constexpr std::size_t kV4HeaderBytes = 20;
constexpr std::int32_t kMaxTypeWord = 4052;  // M = 4 (Cray), O = 0, P = 5, T = 2

[[noreturn]] void FailMatV4(const std::string& where, const std::string& what) {
  throw std::runtime_error(where + ": " + what);
}

std::int32_t ReadInt32(std::string_view bytes, std::size_t offset, bool swap) {
  std::uint32_t v = 0;
  std::memcpy(&v, bytes.data() + offset, sizeof(v));
  return static_cast<std::int32_t>(swap ? __builtin_bswap32(v) : v);
}

/// Bytes per stored element of the type word's precision digit P; 0 for an unknown digit.
std::uint64_t ElementBytes(std::int32_t precision) {
  constexpr std::uint64_t kBytes[] = {8, 4, 4, 2, 2, 1};  // double single int32 int16 uint16 uint8
  return precision >= 0 && precision < 6 ? kBytes[precision] : 0;
}

/// The decoded type word of the variable at `offset`, and whether its other fields are stored in
/// the opposite byte order to this machine's, as libmatio reads them.
struct TypeWord {
  std::int32_t machine = 0;    ///< M: 0 little-endian IEEE, 1 big-endian IEEE
  std::int32_t precision = 0;  ///< P
  std::int32_t kind = 0;       ///< T: 0 full, 1 text, 2 sparse
  bool swap = false;
};

TypeWord ReadTypeWord(std::string_view bytes, std::size_t offset, const std::string& where) {
  std::int32_t word = ReadInt32(bytes, offset, false);
  if (word < 0 || word > kMaxTypeWord) word = ReadInt32(bytes, offset, true);
  if (word < 0 || word > kMaxTypeWord) {
    FailMatV4(where,
              "type word " + std::to_string(word) + " is not a version 4 type (MOPT, 0-4052)");
  }
  TypeWord t{word / 1000, word % 100 / 10, word % 10, false};
  const std::int32_t order = word % 1000 / 100;
  if (t.machine > 1 || order != 0 || ElementBytes(t.precision) == 0 || t.kind > 2) {
    FailMatV4(where, "type word " + std::to_string(word) +
                         " is not one libmatio reads (M 0 or 1, O 0, P 0-5, T 0-2)");
  }
  constexpr bool kLittleEndianMachine = std::endian::native == std::endian::little;
  t.swap = (t.machine == 0) != kLittleEndianMachine;
  return t;
}

/// Checks the variable whose header starts at `offset`; returns where the next one starts.
std::size_t CheckVariable(std::string_view bytes, std::size_t offset, const std::string& where) {
  if (bytes.size() - offset < kV4HeaderBytes) {
    FailMatV4(where, "ends inside a variable header at byte " + std::to_string(offset) + " (" +
                         std::to_string(bytes.size() - offset) + " of 20 bytes)");
  }
  const TypeWord type = ReadTypeWord(bytes, offset, where);
  const std::int32_t rows = ReadInt32(bytes, offset + 4, type.swap);
  const std::int32_t cols = ReadInt32(bytes, offset + 8, type.swap);
  const bool complex = ReadInt32(bytes, offset + 12, false) != 0;  // libmatio: any nonzero word
  const std::int32_t name_bytes = ReadInt32(bytes, offset + 16, type.swap);
  if (rows < 0 || cols < 0) {
    FailMatV4(where, "negative dimensions " + std::to_string(rows) + " x " + std::to_string(cols));
  }
  std::size_t p = offset + kV4HeaderBytes;
  if (name_bytes < 1 || static_cast<std::uint64_t>(name_bytes) > bytes.size() - p) {
    FailMatV4(where, "name length " + std::to_string(name_bytes) + " is not between 1 and the " +
                         std::to_string(bytes.size() - p) + " bytes left in the file");
  }
  p += static_cast<std::size_t>(name_bytes);
  // rows x cols < 2^62 fits; the byte count (up to 2^66) is formed only once it is known to fit.
  const auto count = static_cast<std::uint64_t>(rows) * static_cast<std::uint64_t>(cols);
  const std::uint64_t each = ElementBytes(type.precision) * (complex ? 2 : 1);
  const std::uint64_t left = bytes.size() - p;
  if (count > left / each) {
    FailMatV4(where, "its " + std::to_string(rows) + " x " + std::to_string(cols) +
                         (complex ? " complex" : "") + " elements of " +
                         std::to_string(ElementBytes(type.precision)) +
                         " bytes need more than the " + std::to_string(left) +
                         " bytes left in the file (truncated or corrupt)");
  }
  return p + static_cast<std::size_t>(count * each);
}

}  // namespace

void CheckMatV4Structure(std::string_view bytes, const std::string& where) {
  if (bytes.empty()) FailMatV4(where, "the file is empty");
  std::size_t offset = 0;
  for (int index = 1; offset < bytes.size(); ++index) {
    offset = CheckVariable(bytes, offset, where + ", variable #" + std::to_string(index));
  }
}

}  // namespace phdslam::datasets
