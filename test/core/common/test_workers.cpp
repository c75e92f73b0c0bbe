// Workers: every item of a loop runs once whichever thread takes it, results joined in order, a
// failure is rethrown to the caller, a background task runs beside the caller's work.

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <numeric>
#include <stdexcept>
#include <thread>
#include <vector>

#include "adaptive_lego_loam/core/common/workers.h"

using namespace adaptive_lego_loam;

TEST(Workers, EveryItemRunsOnceInChunksThatTileTheLoop) {
  for (int threads : {1, 2, 4}) {
    Workers workers(threads);
    for (std::size_t count : {0u, 1u, 7u, 1000u}) {
      for (std::size_t chunks : {1u, 3u, 16u}) {
        SCOPED_TRACE(std::to_string(threads) + " threads, " + std::to_string(count) + " items, " +
                     std::to_string(chunks) + " chunks");
        std::vector<int> runs(count, 0);
        std::vector<std::pair<std::size_t, std::size_t>> ranges(chunks, {0, 0});
        workers.for_chunks(count, chunks,
                           [&](std::size_t chunk, std::size_t begin, std::size_t end) {
                             ranges[chunk] = {begin, end};
                             for (std::size_t i = begin; i < end; ++i)
                               ++runs[i];
                           });
        EXPECT_EQ(std::count(runs.begin(), runs.end(), 1), static_cast<long>(count));
        // Consecutive, in chunk order, sizes differing by at most one.
        std::size_t expected_begin = 0;
        for (std::size_t chunk = 0; chunk < std::min(chunks, count); ++chunk) {
          EXPECT_EQ(ranges[chunk].first, expected_begin);
          const std::size_t size = ranges[chunk].second - ranges[chunk].first;
          EXPECT_GE(size, count / chunks);
          EXPECT_LE(size, count / chunks + 1);
          expected_begin = ranges[chunk].second;
        }
      }
    }
  }
}

TEST(Workers, ResultsJoinInItemOrderWhateverTheThreads) {
  std::vector<int> expected;
  for (int i = 0; i < 5000; ++i)
    if (i % 3 != 0) expected.insert(expected.end(), {i, -i});
  for (int threads : {1, 2, 3}) {
    Workers workers(threads);
    const UseWorkers use(&workers);
    std::vector<int> out = {42};
    append_in_order(5000, 16, out, [](std::size_t i, std::vector<int>& to) {
      if (i % 3 != 0) to.insert(to.end(), {static_cast<int>(i), -static_cast<int>(i)});
    });
    ASSERT_EQ(out.front(), 42) << "appended, not replaced";
    EXPECT_EQ(std::vector<int>(out.begin() + 1, out.end()), expected) << threads << " threads";
  }
}

TEST(Workers, WithoutWorkersOrForAShortLoopEverythingRunsOnTheCaller) {
  EXPECT_EQ(current_workers(), nullptr);
  EXPECT_EQ(chunk_count(100000, 10), 1u);
  Workers workers(2);
  const UseWorkers use(&workers);
  EXPECT_EQ(current_workers(), &workers);
  EXPECT_EQ(chunk_count(50, 64), 1u);
  EXPECT_EQ(chunk_count(100000, 64), 8u);  // four a thread
  const std::thread::id caller = std::this_thread::get_id();
  bool on_caller = false;
  for_chunks(50, 64, [&](std::size_t, std::size_t, std::size_t) {
    on_caller = std::this_thread::get_id() == caller;
  });
  EXPECT_TRUE(on_caller);
}

TEST(Workers, ALoopInsideAChunkRunsInlineAndFinishes) {
  Workers workers(2);
  const UseWorkers use(&workers);
  std::atomic<int> sum{0};
  for_chunks(64, 1, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      for_chunks(100, 1, [&](std::size_t, std::size_t b, std::size_t e) {
        sum += static_cast<int>(e - b);
      });
  });
  EXPECT_EQ(sum.load(), 6400);
}

TEST(Workers, AFailingChunkIsRethrownAndTheWorkersStayUsable) {
  Workers workers(2);
  EXPECT_THROW(workers.for_chunks(100, 10,
                                  [](std::size_t chunk, std::size_t, std::size_t) {
                                    if (chunk == 7) throw std::runtime_error("chunk 7");
                                  }),
               std::runtime_error);
  std::atomic<int> items{0};
  workers.for_chunks(100, 10, [&](std::size_t, std::size_t begin, std::size_t end) {
    items += static_cast<int>(end - begin);
  });
  EXPECT_EQ(items.load(), 100);
}

TEST(Workers, ABackgroundTaskRunsBesideTheCallersLoopAndItsFailureIsRethrown) {
  for (int threads : {1, 2}) {
    SCOPED_TRACE(std::to_string(threads) + " threads");
    Workers workers(threads);
    std::vector<long> squares(10000);
    workers.start_background([&] {
      for (std::size_t i = 0; i < squares.size(); ++i)
        squares[i] = static_cast<long>(i * i);
    });
    std::atomic<int> items{0};
    workers.for_chunks(1000, 8, [&](std::size_t, std::size_t begin, std::size_t end) {
      items += static_cast<int>(end - begin);
    });
    workers.wait_background();
    EXPECT_EQ(items.load(), 1000);
    EXPECT_EQ(squares[9999], 9999L * 9999L);

    workers.start_background([] { throw std::runtime_error("background"); });
    EXPECT_THROW(workers.wait_background(), std::runtime_error);
    workers.wait_background();  // nothing running: returns at once
  }
}

TEST(Workers, AThreadCountBelowOneIsRefused) {
  EXPECT_THROW(Workers(0), std::invalid_argument);
}
