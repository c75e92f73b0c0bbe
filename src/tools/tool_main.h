#pragma once
// What every command-line tool shares: the exit statuses, command-line parsing, and one line on
// stderr for a failure.

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <optional>
#include <string>

namespace adaptive_lego_loam::tools {

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;  // bad input, or the job failed
constexpr int kExitUsage = 2;    // the command line itself is wrong

// Parses the command line. Returns the status to exit with when the tool must not go on:
// 0 after --help, 2 after a usage error (one line on stderr naming the tool).
std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv,
                                      const std::string& tool);

// A usage error found after parsing (options that do not go together).
int usage_error(const std::string& tool, const std::string& what);

// Runs the tool's job: an exception becomes one line "tool: what" on stderr and status 1.
template <class Job>
int run_job(const std::string& tool, Job&& job) {
  try {
    return job();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", tool.c_str(), e.what());
    return kExitFailure;
  }
}

}  // namespace adaptive_lego_loam::tools
