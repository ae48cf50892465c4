// Read access to MATLAB MAT-files of version 4, 5 and 7 (version 5 with compressed variables) via
// libmatio. Version 7.3 (HDF5-based) files are refused with an error that says how to re-save them.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <memory>
#include <string>

// libmatio's file handle; the header <matio.h> is included by mat_file.cc only.
struct _mat_t;  // NOLINT(bugprone-reserved-identifier): the name is libmatio's

namespace phdslam::datasets {

/// An open MAT-file, closed on destruction. Movable, not copyable.
class MatFile {
 public:
  /// Opens `path` read-only. Throws std::runtime_error naming the file when it does not exist,
  /// is a version 7.3 (HDF5-based) MAT-file, is not a MAT-file libmatio can read, or fails
  /// CheckMatV5Structure (a version 5 file: truncated, or a variable storing fewer or more elements
  /// than declared) or CheckMatV4Structure (a file without a version 5 or 7.3 header: a name or
  /// data that does not fit in the file).
  explicit MatFile(const std::filesystem::path& path);
  ~MatFile();
  MatFile(MatFile&&) noexcept;
  MatFile& operator=(MatFile&&) noexcept;
  MatFile(const MatFile&) = delete;
  MatFile& operator=(const MatFile&) = delete;

  /// True when the file holds a variable of that name.
  [[nodiscard]] bool Has(const std::string& variable) const;

  /// Reads a real numeric 2-D variable (class double, single or any integer class, logical
  /// included) and converts it to double. Throws std::runtime_error naming the file and the
  /// variable when it is missing, not numeric (char, cell, struct, sparse, ...), complex, not
  /// 2-D, or larger than kMaxMatVariableBytes as doubles (checked before anything is read).
  [[nodiscard]] Eigen::MatrixXd ReadMatrix(const std::string& variable) const;

  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  struct Closer {
    void operator()(_mat_t* mat) const;
  };
  std::filesystem::path path_;
  std::unique_ptr<_mat_t, Closer> mat_;
};

}  // namespace phdslam::datasets
