// Structural check of a MAT-file in the version 5 format (compressed or not) before libmatio reads
// it: every data element must fit in the file, every compressed variable must inflate completely,
// and every numeric or char array must store exactly as many elements as its dimensions declare.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace phdslam::datasets {

/// Largest size accepted for one variable, both inflated (a compressed variable) and read as
/// doubles (MatFile::ReadMatrix). It bounds memory on hostile input: reading a variable holds it
/// twice (libmatio's copy in the variable's class and the matrix of doubles), and a few hundred
/// bytes of deflated zeros can declare gigabytes. 256 MiB is 33.5 million doubles, far above the
/// data sets' largest variable (61,945 x 1 in aa3_dr.mat).
inline constexpr std::size_t kMaxMatVariableBytes = std::size_t{1} << 28;

/// True when `bytes` starts with a version 5 MAT-file header (either byte order). Version 4 and
/// HDF5-based version 7.3 files give false.
bool IsMatV5(std::string_view bytes);

/// True when `bytes` starts with the 128-byte header of an HDF5-based version 7.3 MAT-file (which
/// MatFile refuses).
bool IsMatV73(std::string_view bytes);

/// Checks the data elements of a version 5 MAT-file held in `bytes`. Throws std::runtime_error
/// starting with `where` and naming the variable (by its position and, when known, its name) and
/// the offending sizes when the file is truncated or a variable is inconsistent.
void CheckMatV5Structure(std::string_view bytes, const std::string& where);

}  // namespace phdslam::datasets
