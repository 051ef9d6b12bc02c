#include "programs/heartbeat_log.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

namespace growshell {
namespace {

/// Everything written to `file` so far, as lines.
std::vector<std::string> lines_of(std::FILE* file) {
  std::fflush(file);
  std::rewind(file);
  std::vector<std::string> lines;
  std::string line;
  for (int c = std::fgetc(file); c != EOF; c = std::fgetc(file)) {
    if (c == '\n') {
      lines.push_back(line);
      line.clear();
    } else {
      line += static_cast<char>(c);
    }
  }
  return lines;
}

TEST(HeartbeatLog, PrintsLinesAsTheyComeAndSaysItIsAliveWhileSilent) {
  std::FILE* file = std::tmpfile();
  ASSERT_NE(file, nullptr);
  {
    HeartbeatLog log(file, std::chrono::milliseconds(40));
    log("phi_e 1.0");
    // Silent for more than five intervals: at least one heartbeat, naming the last line.
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    log("phi_e 2.0");
  }
  const std::vector<std::string> lines = lines_of(file);
  ASSERT_GE(lines.size(), 3u);
  EXPECT_EQ(lines.front(), "phi_e 1.0");
  EXPECT_EQ(lines.back(), "phi_e 2.0");
  for (std::size_t k = 1; k + 1 < lines.size(); ++k) {
    EXPECT_EQ(lines[k].rfind("# still running: ", 0), 0u) << lines[k];
    EXPECT_NE(lines[k].find("since the last line (phi_e 1.0)"), std::string::npos) << lines[k];
  }
  std::fclose(file);
}

TEST(HeartbeatLog, IsQuietWhileLinesComeOftenAndStopsWithItsOwner) {
  std::FILE* file = std::tmpfile();
  ASSERT_NE(file, nullptr);
  {
    HeartbeatLog log(file, std::chrono::seconds(5));
    for (int k = 0; k < 5; ++k) log("row " + std::to_string(k));
  }  // returns at once, not after the interval
  const std::vector<std::string> lines = lines_of(file);
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_EQ(lines[4], "row 4");
  std::fclose(file);
}

}  // namespace
}  // namespace growshell
