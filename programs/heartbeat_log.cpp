#include "heartbeat_log.hpp"

namespace growshell {

HeartbeatLog::HeartbeatLog(std::FILE* out, std::chrono::milliseconds interval)
    : out_(out), interval_(interval), last_line_time_(std::chrono::steady_clock::now()) {
  thread_ = std::thread([this] { beat(); });
}

HeartbeatLog::~HeartbeatLog() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void HeartbeatLog::operator()(const std::string& line) {
  std::lock_guard<std::mutex> lock(mutex_);
  print(line);
  last_line_ = line;
  last_line_time_ = std::chrono::steady_clock::now();
}

void HeartbeatLog::print(const std::string& line) {
  std::fputs(line.c_str(), out_);
  std::fputc('\n', out_);
  std::fflush(out_);
}

void HeartbeatLog::beat() {
  std::unique_lock<std::mutex> lock(mutex_);
  auto next = last_line_time_ + interval_;
  while (!stop_) {
    if (wake_.wait_until(lock, next, [this] { return stop_; })) break;
    const auto now = std::chrono::steady_clock::now();
    if (now - last_line_time_ >= interval_) {
      const auto quiet =
          std::chrono::duration_cast<std::chrono::seconds>(now - last_line_time_).count();
      std::string text = "# still running: " + std::to_string(quiet) + " s since the last line";
      if (!last_line_.empty()) {
        constexpr std::size_t kShown = 100;
        text += " (" + (last_line_.size() > kShown ? last_line_.substr(0, kShown) + "..."
                                                    : last_line_) + ")";
      }
      print(text);
      next = now + interval_;
    } else {
      next = last_line_time_ + interval_;
    }
  }
}

}  // namespace growshell
