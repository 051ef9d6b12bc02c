#pragma once
// A study's log printed as it comes, with a line every `interval` while the study is silent:
// a long factorisation, relaxation or contact solve then still shows that the program is
// alive, for how long it has been quiet, and what it was doing (its last line).

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>

namespace growshell {

class HeartbeatLog {
 public:
  /// Prints to `out` (flushed after every line). The heartbeat thread starts at once.
  explicit HeartbeatLog(std::FILE* out = stdout,
                        std::chrono::milliseconds interval = std::chrono::seconds(10));
  ~HeartbeatLog();  ///< stops the heartbeat; nothing is printed after it returns
  HeartbeatLog(const HeartbeatLog&) = delete;
  HeartbeatLog& operator=(const HeartbeatLog&) = delete;

  /// Prints one line of the log (without its newline).
  void operator()(const std::string& line);

 private:
  void beat();
  void print(const std::string& line);  // with mutex_ held

  std::FILE* out_;
  std::chrono::milliseconds interval_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::chrono::steady_clock::time_point last_line_time_;
  std::string last_line_;
  std::thread thread_;
};

}  // namespace growshell
