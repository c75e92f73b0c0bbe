#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <vector>

#include "adaptive_lego_loam/io/process_memory.h"

namespace adaptive_lego_loam {
namespace {

constexpr std::size_t kBlockBytes = 64 * 1024;  // below glibc's mmap threshold: in the heap

// Blocks written to (so that their pages are resident), with one more block after them that
// stays: freed, they leave a hole in the middle of the heap, which glibc does not give back on
// its own.
struct HeapHole {
  std::vector<std::unique_ptr<char[]>> blocks;
  std::unique_ptr<char[]> pin;

  explicit HeapHole(double megabytes) {
    const std::size_t count = static_cast<std::size_t>(megabytes * 1024 * 1024) / kBlockBytes;
    for (std::size_t i = 0; i < count; ++i) {
      blocks.emplace_back(new char[kBlockBytes]);
      std::memset(blocks.back().get(), static_cast<int>(i + 1), kBlockBytes);
    }
    pin.reset(new char[kBlockBytes]);
    std::memset(pin.get(), 1, kBlockBytes);
  }
  void free_blocks() { blocks.clear(); }
};

// Under a sanitizer the allocator is the sanitizer's, and glibc's statistics see none of it.
bool glibc_heap_in_use() {
  const double before = heap_in_use_mb();
  auto block = std::make_unique<char[]>(4 * 1024 * 1024);
  block[0] = 1;
  return heap_in_use_mb() > before + 3.0;
}

TEST(ProcessMemory, AHoleLeftInTheHeapGoesBackToTheSystem) {
  if (!glibc_heap_in_use()) GTEST_SKIP() << "the heap is not glibc's";
  HeapHole hole(48.0);
  const double heap_before = heap_in_use_mb();
  hole.free_blocks();
  EXPECT_LT(heap_in_use_mb(), heap_before - 40.0);
  const double resident_before = resident_memory_mb();
  return_free_memory_to_system();
  EXPECT_LT(resident_memory_mb(), resident_before - 40.0);
}

TEST(ProcessMemory, TheHeapIsTrimmedEveryFewScans) {
  if (!glibc_heap_in_use()) GTEST_SKIP() << "the heap is not glibc's";
  HeapTrimmer trimmer(3);
  HeapHole hole(48.0);
  hole.free_blocks();
  const double resident_before = resident_memory_mb();
  EXPECT_FALSE(trimmer.after_scan());
  EXPECT_FALSE(trimmer.after_scan());
  EXPECT_GT(resident_memory_mb(), resident_before - 8.0) << "kept until the third scan";
  EXPECT_TRUE(trimmer.after_scan());
  EXPECT_LT(resident_memory_mb(), resident_before - 40.0);
  EXPECT_FALSE(trimmer.after_scan()) << "and counted again from there";
}

}  // namespace
}  // namespace adaptive_lego_loam
