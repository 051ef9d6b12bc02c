#pragma once
// The command line of the programs that read an earlier run (contact_profile,
// crit_hard_contact): the run's directory first, then `--name value` options.

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "examples/support/command_line.hpp"

namespace growshell::examples {

struct DirectoryCommandLine {
  std::string directory;  ///< the first argument
  CommandLine options;    ///< the options after it
};

/// The directory and options; or, without a directory (or with --help / -h first), prints
/// `usage` (to stdout for help, else to stderr), sets *exit_code (0 for help, else 2) and
/// returns nullopt. Throws as CommandLine for a malformed option.
inline std::optional<DirectoryCommandLine> read_directory_command_line(int argc, char** argv,
                                                                       const char* usage,
                                                                       int* exit_code) {
  if (argc < 2 || argv[1][0] == '-') {
    const bool help =
        argc >= 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h");
    std::fputs(usage, help ? stdout : stderr);
    *exit_code = help ? 0 : 2;
    return std::nullopt;
  }
  std::vector<char*> rest(argv + 2, argv + argc);
  rest.insert(rest.begin(), argv[0]);
  return DirectoryCommandLine{argv[1], CommandLine(static_cast<int>(rest.size()), rest.data())};
}

}  // namespace growshell::examples
