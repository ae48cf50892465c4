#include "datasets/mat_file.h"

#include <matio.h>

#include <cstdint>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "datasets/mat_v4_structure.h"
#include "datasets/mat_v5_structure.h"

namespace phdslam::datasets {
namespace {

struct VarFreer {
  void operator()(matvar_t* var) const { Mat_VarFree(var); }
};
using VarPtr = std::unique_ptr<matvar_t, VarFreer>;

const char* ClassName(matio_classes c) {
  switch (c) {
    case MAT_C_EMPTY:
      return "empty";
    case MAT_C_CELL:
      return "cell";
    case MAT_C_STRUCT:
      return "struct";
    case MAT_C_OBJECT:
      return "object";
    case MAT_C_CHAR:
      return "char";
    case MAT_C_SPARSE:
      return "sparse";
    case MAT_C_DOUBLE:
      return "double";
    case MAT_C_SINGLE:
      return "single";
    case MAT_C_INT8:
      return "int8";
    case MAT_C_UINT8:
      return "uint8";
    case MAT_C_INT16:
      return "int16";
    case MAT_C_UINT16:
      return "uint16";
    case MAT_C_INT32:
      return "int32";
    case MAT_C_UINT32:
      return "uint32";
    case MAT_C_INT64:
      return "int64";
    case MAT_C_UINT64:
      return "uint64";
    case MAT_C_FUNCTION:
      return "function";
    case MAT_C_OPAQUE:
      return "opaque";
  }
  return "unknown";
}

bool IsNumericClass(matio_classes c) {
  switch (c) {
    case MAT_C_DOUBLE:
    case MAT_C_SINGLE:
    case MAT_C_INT8:
    case MAT_C_UINT8:
    case MAT_C_INT16:
    case MAT_C_UINT16:
    case MAT_C_INT32:
    case MAT_C_UINT32:
    case MAT_C_INT64:
    case MAT_C_UINT64:
      return true;
    default:
      return false;
  }
}

template <typename T>
Eigen::MatrixXd CopyColumnMajor(const matvar_t& var, Eigen::Index rows, Eigen::Index cols,
                                const std::string& where) {
  if (var.nbytes < static_cast<size_t>(rows * cols) * sizeof(T)) {
    throw std::runtime_error(where + ": its data is shorter than its dimensions say");
  }
  const T* src = static_cast<const T*>(var.data);
  Eigen::MatrixXd out(rows, cols);
  for (Eigen::Index i = 0; i < rows * cols; ++i) out.data()[i] = static_cast<double>(src[i]);
  return out;
}

// Reads the whole file and checks its structure, so that a truncated or inconsistent file is
// refused before libmatio reads past what is stored or allocates what a corrupt header declares.
// libmatio reads a file without a version 5 or 7.3 header as version 4. Version 7.3 files are
// refused: libmatio hands them to the HDF5 library, whose parser leaks memory on malformed files
// (the MAT-file fuzzer found a leak within two minutes of HDF5 input) and checks no structure we
// could bound; every data set of the suite is version 5.
void CheckStructure(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open MAT-file '" + path.string() + "' for reading");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw std::runtime_error("cannot read MAT-file '" + path.string() + "'");
  const std::string where = "MAT-file '" + path.string() + "'";
  if (IsMatV73(bytes)) {
    throw std::runtime_error(where +
                             " is version 7.3 (HDF5-based), which is not read: save it as "
                             "version 7 (MATLAB: save(file, ..., '-v7'); GNU Octave: save -v7)");
  }
  if (IsMatV5(bytes)) {
    CheckMatV5Structure(bytes, where);
  } else {
    CheckMatV4Structure(bytes, where + " (no version 5 header, so read as version 4)");
  }
}

}  // namespace

void MatFile::Closer::operator()(_mat_t* mat) const { Mat_Close(mat); }

MatFile::MatFile(const std::filesystem::path& path) : path_(path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw std::runtime_error("MAT-file '" + path.string() + "' does not exist or is not a file");
  }
  CheckStructure(path);
  mat_.reset(Mat_Open(path.c_str(), MAT_ACC_RDONLY));
  if (!mat_) {
    throw std::runtime_error("cannot open '" + path.string() +
                             "' as a MAT-file (libmatio could not read its header)");
  }
}

MatFile::~MatFile() = default;
MatFile::MatFile(MatFile&&) noexcept = default;
MatFile& MatFile::operator=(MatFile&&) noexcept = default;

bool MatFile::Has(const std::string& variable) const {
  const VarPtr info(Mat_VarReadInfo(mat_.get(), variable.c_str()));
  return info != nullptr;
}

Eigen::MatrixXd MatFile::ReadMatrix(const std::string& variable) const {
  const std::string where = "MAT-file '" + path_.string() + "', variable '" + variable + "'";
  const VarPtr info(Mat_VarReadInfo(mat_.get(), variable.c_str()));
  if (!info) throw std::runtime_error(where + ": no such variable");
  if (!IsNumericClass(info->class_type)) {
    throw std::runtime_error(where + ": expected a numeric matrix, found class " +
                             ClassName(info->class_type));
  }
  if (info->isComplex) throw std::runtime_error(where + ": expected real values, found complex");
  if (info->rank != 2) {
    throw std::runtime_error(where + ": expected a 2-D matrix, found " +
                             std::to_string(info->rank) + " dimensions");
  }
  const auto rows = static_cast<Eigen::Index>(info->dims[0]);
  const auto cols = static_cast<Eigen::Index>(info->dims[1]);
  if (rows == 0 || cols == 0) return Eigen::MatrixXd(rows, cols);
  if (static_cast<std::uint64_t>(rows) >
      kMaxMatVariableBytes / sizeof(double) / static_cast<std::uint64_t>(cols)) {
    throw std::runtime_error(where + ": its " + std::to_string(rows) + " x " +
                             std::to_string(cols) + " elements would take more than the " +
                             std::to_string(kMaxMatVariableBytes) +
                             " bytes accepted for one variable");
  }

  const VarPtr var(Mat_VarRead(mat_.get(), variable.c_str()));
  if (!var || var->data == nullptr) throw std::runtime_error(where + ": cannot read its data");
  // libmatio converts numeric data to the variable's class on reading; data_type says which.
  switch (var->data_type) {
    case MAT_T_DOUBLE:
      return CopyColumnMajor<double>(*var, rows, cols, where);
    case MAT_T_SINGLE:
      return CopyColumnMajor<float>(*var, rows, cols, where);
    case MAT_T_INT8:
      return CopyColumnMajor<std::int8_t>(*var, rows, cols, where);
    case MAT_T_UINT8:
      return CopyColumnMajor<std::uint8_t>(*var, rows, cols, where);
    case MAT_T_INT16:
      return CopyColumnMajor<std::int16_t>(*var, rows, cols, where);
    case MAT_T_UINT16:
      return CopyColumnMajor<std::uint16_t>(*var, rows, cols, where);
    case MAT_T_INT32:
      return CopyColumnMajor<std::int32_t>(*var, rows, cols, where);
    case MAT_T_UINT32:
      return CopyColumnMajor<std::uint32_t>(*var, rows, cols, where);
    case MAT_T_INT64:
      return CopyColumnMajor<std::int64_t>(*var, rows, cols, where);
    case MAT_T_UINT64:
      return CopyColumnMajor<std::uint64_t>(*var, rows, cols, where);
    default:
      throw std::runtime_error(where + ": unsupported stored data type " +
                               std::to_string(static_cast<int>(var->data_type)));
  }
}

}  // namespace phdslam::datasets
