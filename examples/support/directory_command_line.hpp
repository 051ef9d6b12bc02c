#pragma once
// The command line of the programs that read an earlier run (contact_profile,
// hard_contact_at, ...): the run's directory first, then `--name value` options; and their
// main().

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "examples/support/command_line.hpp"
#include "examples/support/guarded_main.hpp"

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

/// The main() of a program that reads an earlier run: run(directory, options), guarded as
/// guarded_main (an exception becomes a message naming `program` and exit status 2); without a
/// directory, or with --help / -h first, prints `usage` and returns 2 (0 for help).
inline int directory_main(const char* program, const char* usage,
                          int (*run)(const std::string& directory, CommandLine& options),
                          int argc, char** argv) {
  return guarded_main(
      program,
      [&](int n, char** args) {
        int exit_code = 0;
        auto command_line = read_directory_command_line(n, args, usage, &exit_code);
        return command_line ? run(command_line->directory, command_line->options) : exit_code;
      },
      argc, argv);
}

}  // namespace growshell::examples
