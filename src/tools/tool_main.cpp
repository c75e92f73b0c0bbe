#include "tool_main.h"

#include <cstdio>

namespace adaptive_lego_loam::tools {

std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv,
                                      const std::string& tool) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    app.exit(e);
    return kExitOk;
  } catch (const CLI::CallForAllHelp& e) {
    app.exit(e);
    return kExitOk;
  } catch (const CLI::ParseError& e) {
    return usage_error(tool, e.what());
  }
  return std::nullopt;
}

int usage_error(const std::string& tool, const std::string& what) {
  std::fprintf(stderr, "%s: %s (see %s --help)\n", tool.c_str(), what.c_str(), tool.c_str());
  return kExitUsage;
}

}  // namespace adaptive_lego_loam::tools
