#include "studies/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace growshell {
namespace {

const std::string kTemporarySuffix = ".tmp";

[[noreturn]] void fail_on(const std::string& path, const std::string& what) {
  throw std::runtime_error("cannot " + what + " '" + path + "': " + std::strerror(errno));
}

}  // namespace

std::string temporary_path_for(const std::string& path) {
  const std::filesystem::path p(path);
  std::string name(1, '.');
  name += p.filename().string();
  name += kTemporarySuffix;
  return (p.parent_path() / name).string();
}

bool is_temporary_file_name(const std::string& file_name) {
  return file_name.size() > 1 + kTemporarySuffix.size() && file_name.front() == '.' &&
         file_name.compare(file_name.size() - kTemporarySuffix.size(), kTemporarySuffix.size(),
                           kTemporarySuffix) == 0;
}

void write_atomically_with(const std::string& path,
                           const std::function<void(const std::string& temporary)>& write) {
  const std::string temporary = temporary_path_for(path);
  try {
    write(temporary);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    const int error = errno;
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    errno = error;
    fail_on(path, "rename a temporary onto");
  }
}

void write_file_atomically(const std::string& path, const std::string& content) {
  write_atomically_with(path, [&](const std::string& temporary) {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) fail_on(path, "write");
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.close();
    if (!out) fail_on(path, "write");
  });
}

void append_to_file(const std::string& path, const std::string& text) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) fail_on(path, "open for appending");
  const off_t size_before = ::lseek(fd, 0, SEEK_END);
  // One write for the whole text: a regular file takes it whole unless the disk is full; a
  // short write is cut back off, so the file never ends in a partial line.
  const ssize_t written = ::write(fd, text.data(), text.size());
  const int error = written < 0 ? errno : ENOSPC;
  if (written != static_cast<ssize_t>(text.size()) && size_before >= 0)
    static_cast<void>(::ftruncate(fd, size_before));
  ::close(fd);
  if (written != static_cast<ssize_t>(text.size())) {
    errno = error;
    fail_on(path, "append to");
  }
}

}  // namespace growshell
