// Outputs written under a temporary name and put in place whole: a failure keeps what was there.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "adaptive_lego_loam/io/atomic_files.h"
#include "adaptive_lego_loam/io/io_error.h"
#include "support/temp_files.h"

using namespace adaptive_lego_loam;
using adaptive_lego_loam::test::temp_path;
namespace fs = std::filesystem;

namespace {

std::string read_file(const fs::path& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = temp_path(name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

int entries_in(const fs::path& dir) {
  int count = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir))
    ++count;
  return count;
}

}  // namespace

TEST(AtomicFiles, AWriterThatThrowsLeavesTheOldFile) {
  const fs::path dir = fresh_dir("atomic_throw");
  std::ofstream(dir / "out.txt") << "old\n";
  EXPECT_THROW(write_atomically((dir / "out.txt").string(),
                                [](const std::string& temporary) {
                                  std::ofstream(temporary) << "half";
                                  throw std::runtime_error("disk full");
                                }),
               std::runtime_error);
  EXPECT_EQ(read_file(dir / "out.txt"), "old\n");
  EXPECT_EQ(entries_in(dir), 1) << "the temporary is removed";
}

TEST(AtomicFiles, AFolderReplacesTheOldOneWholeAndATrailingSlashNamesTheSame) {
  const fs::path dir = fresh_dir("atomic_folder");
  fs::create_directories(dir / "map");
  std::ofstream(dir / "map" / "old.txt") << "old\n";
  write_atomically((dir / "map").string() + "/", [](const std::string& temporary) {
    fs::create_directories(temporary);
    std::ofstream(fs::path(temporary) / "new.txt") << "new\n";
  });
  EXPECT_EQ(read_file(dir / "map" / "new.txt"), "new\n");
  EXPECT_FALSE(fs::exists(dir / "map" / "old.txt"));
  EXPECT_EQ(entries_in(dir), 1) << "no temporary beside it";
}

TEST(AtomicFiles, ABatchIsPutInPlaceOnlyWhenCommitted) {
  const fs::path dir = fresh_dir("atomic_batch");
  std::ofstream(dir / "a.txt") << "old a\n";
  {
    AtomicBatch batch;
    batch.add((dir / "a.txt").string(),
              [](const std::string& temporary) { std::ofstream(temporary) << "new a\n"; });
    batch.add((dir / "b.txt").string(),
              [](const std::string& temporary) { std::ofstream(temporary) << "new b\n"; });
    EXPECT_EQ(read_file(dir / "a.txt"), "old a\n");
    EXPECT_FALSE(fs::exists(dir / "b.txt"));
  }  // the run failed before committing
  EXPECT_EQ(read_file(dir / "a.txt"), "old a\n");
  EXPECT_EQ(entries_in(dir), 1) << "the temporaries are removed";
  AtomicBatch batch;
  batch.add((dir / "a.txt").string(),
            [](const std::string& temporary) { std::ofstream(temporary) << "new a\n"; });
  batch.commit();
  EXPECT_EQ(read_file(dir / "a.txt"), "new a\n");
}

TEST(AtomicFiles, AStreamedFileAppearsOnCommitOnly) {
  const fs::path dir = fresh_dir("atomic_stream");
  {
    AtomicFile file((dir / "timing.csv").string());
    file.stream() << "frame\n";
  }
  EXPECT_EQ(entries_in(dir), 0);
  AtomicFile file((dir / "timing.csv").string());
  file.stream() << "frame\n";
  file.commit();
  EXPECT_EQ(read_file(dir / "timing.csv"), "frame\n");
}
