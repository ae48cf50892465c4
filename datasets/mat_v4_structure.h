// Structural check of a MAT-file in the version 4 format before libmatio reads it. A version 4
// file has no file header: it is a sequence of variables, each a 20-byte header (type word, rows,
// columns, imaginary flag, name length), the name, and the data. libmatio takes every file that is
// neither version 5 nor 7.3 for version 4 and allocates what the headers declare, so a few hostile
// bytes could make it reserve gigabytes; the check refuses any header whose name or data does not
// fit in the file.
#pragma once

#include <string>
#include <string_view>

namespace phdslam::datasets {

/// Checks every variable header of a version 4 MAT-file held in `bytes`: a type word libmatio
/// accepts (little- or big-endian IEEE; double, single, int32, int16, uint16 or uint8 data; full,
/// text or sparse), non-negative dimensions, a name of at least one byte, and a name and data that
/// end inside the file. Throws std::runtime_error starting with `where` and naming the variable
/// (by position) and the offending values.
void CheckMatV4Structure(std::string_view bytes, const std::string& where);

}  // namespace phdslam::datasets
