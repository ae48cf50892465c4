// Test helper: a fresh, empty folder per test under GoogleTest's temporary directory.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace phdslam::datasets::testing {

/// Creates (emptied) <TempDir>/phdslam_datasets/<suite>.<test>.<pid> and returns it.
inline std::filesystem::path FreshTestDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string name =
      std::string(info->test_suite_name()) + "." + info->name() + "." + std::to_string(::getpid());
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / "phdslam_datasets" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace phdslam::datasets::testing
