#include "adaptive_lego_loam/io/atomic_files.h"

#include <fcntl.h>
#include <stdio.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "adaptive_lego_loam/io/io_error.h"

namespace adaptive_lego_loam {
namespace fs = std::filesystem;
namespace {

// `path` without a trailing slash: "out/map/" names the folder map, as "out/map" does.
fs::path normalised(const std::string& path) {
  fs::path target = fs::path(path).lexically_normal();
  if (!target.has_filename()) target = target.parent_path();
  return target;
}

// Beside `path`, unique to this process: two runs writing the same output do not share one.
std::string temporary_beside(const std::string& path) {
  const fs::path target = normalised(path);
  return (target.parent_path() /
          ("." + target.filename().string() + ".partial-" + std::to_string(::getpid())))
      .string();
}

void remove_quietly(const std::string& path) {
  std::error_code ignored;
  fs::remove_all(path, ignored);
}

// Puts `temporary` in the place of `path`. A folder cannot be renamed over a non-empty one: the
// two are swapped in one step (renameat2), and the old one, now at `temporary`, removed.
void replace(const std::string& temporary, const std::string& target) {
  const std::string path = normalised(target).string();
  std::error_code error;
  const bool folder_there = fs::is_directory(path, error);
  if (!folder_there) {
    if (::rename(temporary.c_str(), path.c_str()) == 0) return;
  } else if (::renameat2(AT_FDCWD, temporary.c_str(), AT_FDCWD, path.c_str(), RENAME_EXCHANGE) ==
             0) {
    remove_quietly(temporary);
    return;
  }
  const std::string reason = std::strerror(errno);
  remove_quietly(temporary);
  throw IoError(path + ": cannot put the new output in place: " + reason);
}

// Runs `write` on the temporary beside `path` and returns it; removes it when `write` throws.
std::string write_temporary(const std::string& path,
                            const std::function<void(const std::string& temporary)>& write) {
  const std::string temporary = temporary_beside(path);
  remove_quietly(temporary);
  try {
    write(temporary);
  } catch (...) {
    remove_quietly(temporary);
    throw;
  }
  return temporary;
}

}  // namespace

void write_atomically(const std::string& path,
                      const std::function<void(const std::string& temporary)>& write) {
  replace(write_temporary(path, write), path);
}

AtomicFile::AtomicFile(std::string path)
    : path_(std::move(path)), temporary_(temporary_beside(path_)) {
  stream_.open(temporary_);
  if (!stream_) throw IoError(path_ + ": cannot write there: " + std::strerror(errno));
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  stream_.close();
  remove_quietly(temporary_);
}

void AtomicFile::commit() {
  if (committed_) return;
  stream_.flush();
  const bool written = static_cast<bool>(stream_);
  stream_.close();
  if (!written || stream_.fail()) {
    remove_quietly(temporary_);
    throw IoError(path_ + ": writing failed (disk full?)");
  }
  committed_ = true;
  replace(temporary_, path_);
}

AtomicBatch::~AtomicBatch() {
  if (committed_) return;
  for (const auto& [path, temporary] : files_)
    remove_quietly(temporary);
}

void AtomicBatch::add(const std::string& path,
                      const std::function<void(const std::string& temporary)>& write) {
  files_.emplace_back(path, write_temporary(path, write));
}

void AtomicBatch::commit() {
  if (committed_) return;
  committed_ = true;
  for (const auto& [path, temporary] : files_)
    replace(temporary, path);
}

}  // namespace adaptive_lego_loam
