#pragma once
/// \file
/// Files that are never seen half-written: a whole file is written to a temporary in its own
/// directory and renamed over the target (rename is atomic within a file system), and a line
/// is appended with one write. A reader, or a study resumed after a crash, finds the old
/// content or the new, never a part of it.

#include <functional>
#include <string>

namespace growshell {

/// The temporary that write_file_atomically uses for `path`: ".<name>.tmp" in the same
/// directory (the same file system, so the rename is atomic).
std::string temporary_path_for(const std::string& path);

/// Whether `file_name` (no directory) is such a temporary, e.g. ".branch.csv.tmp": left behind
/// only by a run that was killed while writing.
bool is_temporary_file_name(const std::string& file_name);

/// Writes a file atomically: `write` is called with the temporary's path and must write the
/// whole file there (and throw if it cannot); the temporary is then renamed over `path`. If
/// `write` throws, the temporary is removed and `path` is left as it was. Throws
/// std::runtime_error naming `path` if the rename fails.
void write_atomically_with(const std::string& path,
                           const std::function<void(const std::string& temporary)>& write);

/// Writes `content` to `path` atomically (as write_atomically_with). Throws std::runtime_error
/// naming the path if the directory is missing or the file cannot be written.
void write_file_atomically(const std::string& path, const std::string& content);

/// Appends `text` (e.g. one CSV row with its newline) to `path` with a single write(2) on a
/// descriptor opened with O_APPEND, so the file ends either before or after the whole text,
/// then closes it (the data is then in the kernel, whatever happens to this process). Creates
/// the file if it is missing. Throws std::runtime_error naming the path on failure.
void append_to_file(const std::string& path, const std::string& text);

}  // namespace growshell
