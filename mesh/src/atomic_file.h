// atomic_file.h — writing a whole file or nothing (write_mesh, write_resolution_vtk).
//
// A new or regular file is written beside its final name (same folder, so the rename cannot
// cross file systems) under a temporary name and renamed over it once every byte is written
// and the stream closed without error: a failed or interrupted run leaves the old file or the
// whole new one, never a part, and no temporary file. Anything else (a device such as
// /dev/null or /dev/full, a pipe, a symbolic link) is written in place: renaming over it would
// replace the device node or the link itself. The same rule as compare/io's write_file.
#pragma once

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include <unistd.h>

namespace pdd::mesh::detail {

// Whether `path` is written through a temporary file and a rename: it does not exist yet or is
// a regular file (not followed when it is a symbolic link).
inline bool replaced_by_rename(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(path, ec);
  return st.type() == fs::file_type::not_found || st.type() == fs::file_type::regular;
}

// The temporary name `path` is written under before the rename.
inline std::string partial_name(const std::string& path) {
  return path + ".partial-" + std::to_string(::getpid());
}

// Writes `text` to `path` as described above. Throws std::runtime_error naming the path and
// the system's reason.
inline void write_whole_file(const std::string& path, const std::string& text) {
  namespace fs = std::filesystem;
  const bool replace = replaced_by_rename(path);
  const std::string target = replace ? partial_name(path) : path;
  auto reason = [] { return errno ? std::string(": ") + std::strerror(errno) : std::string(); };
  std::error_code ec;
  std::string why;
  {
    errno = 0;
    std::ofstream out(target, std::ios::binary | std::ios::trunc);
    if (!out) {
      why = "cannot open '" + path + "' for writing" + reason();
    } else {
      out.write(text.data(), static_cast<std::streamsize>(text.size()));
      out.flush();
      if (out) {
        errno = 0;
        out.close();
      }
      if (!out) why = "cannot write to '" + path + "'" + reason();
    }
  }
  if (replace && why.empty()) {
    fs::rename(target, path, ec);
    if (ec) why = "cannot write '" + path + "': " + ec.message();
  }
  if (replace && !why.empty()) fs::remove(target, ec);
  if (!why.empty()) throw std::runtime_error(why);
}

}  // namespace pdd::mesh::detail
