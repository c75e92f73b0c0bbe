#pragma once
// Outputs that a failure never leaves half-written: each is written under a temporary name beside
// its place and takes that place in one rename once complete. A run that fails keeps the files
// an earlier run left there.

#include <fstream>
#include <functional>
#include <string>
#include <utility>
#include <vector>

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

// Files written whole now and put in place together later: a run writes each as it finishes and
// commits them with its streamed files once everything succeeded. Destroyed uncommitted, it
// removes the temporaries.
class AtomicBatch {
 public:
  AtomicBatch() = default;
  ~AtomicBatch();
  AtomicBatch(const AtomicBatch&) = delete;
  AtomicBatch& operator=(const AtomicBatch&) = delete;

  // `write` fills the temporary path it is given; what it throws goes on (nothing is kept).
  void add(const std::string& path, const std::function<void(const std::string& temporary)>& write);
  // Renames every file into its place, in the order added; throws IoError when one fails.
  void commit();

 private:
  std::vector<std::pair<std::string, std::string>> files_;  // path, temporary
  bool committed_ = false;
};

}  // namespace adaptive_lego_loam
