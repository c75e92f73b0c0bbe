#pragma once
// Runs a shell command for a test and returns its exit status and combined output.

#include <sys/wait.h>

#include <cstdio>
#include <string>
#include <utility>

namespace adaptive_lego_loam::test {

inline std::pair<int, std::string> run_command(const std::string& command) {
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  std::string output;
  char buffer[512];
  while (pipe && std::fgets(buffer, sizeof(buffer), pipe))
    output += buffer;
  const int status = pipe ? pclose(pipe) : -1;
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

}  // namespace adaptive_lego_loam::test
