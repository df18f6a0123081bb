// output.h — writing results so that a failed write is noticed (a full disk, /dev/full, a
// closed pipe): a command whose output was lost must not exit 0 (exit_codes.h).
#pragma once

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <ostream>
#include <string>

#include <unistd.h>

#include "pdd/io/streaming.h"
#include "pdd/printable.h"

namespace pdd::io {

// Flushes `out`; the reason when anything written to it so far was lost. `where` names the
// destination in the message ("standard output", "'results.jsonl'").
inline std::optional<std::string> flush_error(std::ostream& out, const std::string& where) {
  if (out) {  // else errno still says why the last write failed
    errno = 0;
    out.flush();
    if (out) return std::nullopt;
  }
  return "cannot write to " + where + (errno ? std::string(": ") + std::strerror(errno) : "");
}

// Closes a file stream and says why the data did not all reach the file, if it did not.
inline std::optional<std::string> close_error(std::ofstream& out, const std::string& path) {
  if (auto why = flush_error(out, "'" + path + "'")) return why;
  errno = 0;
  out.close();
  if (out) return std::nullopt;
  return "cannot write to '" + path + "'" + (errno ? std::string(": ") + std::strerror(errno) : "");
}

// printable(): pdd/printable.h (a pair name in a message).
using pdd::printable;

// Whether the file `path` can be opened for writing, checked before a long run whose output
// would otherwise be lost at its end; the file is left as it was (created for the test and
// removed again when it did not exist).
inline std::optional<std::string> check_writable(const std::string& path) {
  std::error_code ec;
  const bool existed = std::filesystem::exists(path, ec);
  errno = 0;
  {
    std::ofstream o(path, std::ios::app | std::ios::binary);
    if (!o) return "cannot write '" + path + "'" + (errno ? std::string(": ") + std::strerror(errno) : "");
  }
  if (!existed) std::filesystem::remove(path, ec);
  return std::nullopt;
}

// Writes `text` to the file `path` (created or replaced); the reason when it failed. A new or
// regular file is written beside it under a temporary name and renamed over it, so that an
// interrupted or failed run leaves either the old file or the whole new one, never a part;
// anything else (a device, a pipe, a symbolic link) is written in place.
// Whether `path` is written by renaming a temporary file over it: a new or regular file (not a
// device, a pipe or a symbolic link, which must be written in place).
inline bool replaced_by_rename(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(path, ec);
  return st.type() == fs::file_type::not_found || st.type() == fs::file_type::regular;
}

inline std::optional<std::string> write_file(const std::string& path, const std::string& text) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const bool replace = replaced_by_rename(path);
  const std::string target = replace ? path + ".partial-" + std::to_string(::getpid()) : path;
  const PartialFile partial(replace ? target : std::string());  // removed if a signal ends the run
  errno = 0;
  std::ofstream out(target, std::ios::binary);
  if (!out)
    return "cannot open '" + path + "' for writing" +
           (errno ? std::string(": ") + std::strerror(errno) : "");
  out << text;
  auto why = close_error(out, path);
  if (replace && !why) {
    fs::rename(target, path, ec);
    if (ec) why = "cannot write '" + path + "': " + ec.message();
  }
  if (replace && why) fs::remove(target, ec);
  return why;
}

}  // namespace pdd::io
