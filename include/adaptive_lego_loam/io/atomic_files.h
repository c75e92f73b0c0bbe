#pragma once
// Outputs that a failure never leaves half-written: each is written under a temporary name beside
// its place and takes that place in one rename once complete. A run that fails keeps the files
// an earlier run left there.

#include <fstream>
#include <functional>
#include <string>

namespace adaptive_lego_loam {

// `write` fills the temporary path it is given (a file, or a folder it creates); then that
// replaces `path` in one step (an older folder's contents go only then). When `write` throws,
// the temporary is removed, `path` is as it was and the exception goes on. Throws IoError when
// the replacement fails.
void write_atomically(const std::string& path,
                      const std::function<void(const std::string& temporary)>& write);

// A file streamed over a run: written under a temporary name, renamed to `path` by commit().
// Destroyed uncommitted (the run failed), it is removed.
class AtomicFile {
 public:
  // Throws IoError naming `path` when the temporary file cannot be created.
  explicit AtomicFile(std::string path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ofstream& stream() { return stream_; }
  const std::string& path() const { return path_; }
  // Flushes, closes and renames; throws IoError naming the file when any of it fails.
  void commit();

 private:
  std::string path_, temporary_;
  std::ofstream stream_;
  bool committed_ = false;
};

}  // namespace adaptive_lego_loam
