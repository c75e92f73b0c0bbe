#pragma once
// Files for tests in the temporary folder, and the message a call throws.

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "adaptive_lego_loam/io/io_error.h"

namespace adaptive_lego_loam::test {

// A path in a folder of the temporary directory kept for these tests.
inline std::string temp_path(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "alego_tests";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

// The message of the IoError `call` throws; empty when it throws none.
inline std::string error_of(const std::function<void()>& call) {
  try {
    call();
  } catch (const IoError& e) {
    return e.what();
  }
  return "";
}

}  // namespace adaptive_lego_loam::test
