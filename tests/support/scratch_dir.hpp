#pragma once
// A scratch directory per test (ctest runs tests in parallel processes), empty, under the system's temporary
// directory: peridot_<suite>_<test>_<pid>.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace peridot::testing {

inline std::filesystem::path scratch_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::filesystem::path dir = std::filesystem::temp_directory_path() /
                              ("peridot_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
                               std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace peridot::testing
