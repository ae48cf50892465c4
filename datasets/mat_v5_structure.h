// Structural check of a MAT-file in the version 5 format (compressed or not) before libmatio reads
// it: every data element must fit in the file, every compressed variable must inflate completely,
// and every numeric or char array must store exactly as many elements as its dimensions declare.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace phdslam::datasets {

/// Largest inflated size accepted for one compressed variable (bounds memory on hostile input).
inline constexpr std::size_t kMaxMatVariableBytes = std::size_t{1} << 30;

/// True when `bytes` starts with a version 5 MAT-file header (either byte order). Version 4 and
/// HDF5-based version 7.3 files give false.
bool IsMatV5(std::string_view bytes);

/// Checks the data elements of a version 5 MAT-file held in `bytes`. Throws std::runtime_error
/// starting with `where` and naming the variable (by its position and, when known, its name) and
/// the offending sizes when the file is truncated or a variable is inconsistent.
void CheckMatV5Structure(std::string_view bytes, const std::string& where);

}  // namespace phdslam::datasets
