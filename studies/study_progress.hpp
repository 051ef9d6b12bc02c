#pragma once
/// \file
/// How a study reports progress: library code never prints or exits; it hands each line of
/// its log to a callback, which a program prints (or a test collects, or nobody reads).

#include <functional>
#include <string>

namespace growshell {

/// Receives one line of a study's log at a time, without its newline. Comment lines start
/// with "# "; the others are the rows of a table whose header the study sends first. An empty
/// function discards the log.
using StudyProgress = std::function<void(const std::string& line)>;

}  // namespace growshell
