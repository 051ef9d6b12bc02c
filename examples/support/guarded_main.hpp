#pragma once
// The programs' main(): run, and turn any exception into a message on stderr and exit code 2
// (the library reports bad input by throwing; programs print and exit).

#include <cstdio>
#include <exception>

namespace growshell::examples {

template <class Run>
int guarded_main(const char* program, Run&& run, int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: %s\n", program, e.what());
    return 2;
  }
}

}  // namespace growshell::examples
