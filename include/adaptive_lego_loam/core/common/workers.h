#pragma once
// Threads beside the caller's for two kinds of work: one task run ahead in the background (the
// next scan's ambient filter and feature choice while this one is registered), and loops over
// independent items split into chunks that the caller and every idle thread take in turn. Each
// chunk writes only its own outputs, so the results do not depend on which thread ran it: the same
// to the last bit as one thread. With one thread (the default) everything runs on the caller, in
// order.

#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

namespace adaptive_lego_loam {

class Workers {
 public:
  // `threads` >= 1, the caller's included.
  explicit Workers(int threads);
  ~Workers();
  Workers(const Workers&) = delete;
  Workers& operator=(const Workers&) = delete;

  int threads() const;

  // Starts `task` on a helper thread (runs it now when there is none); `wait_background` returns
  // once it has finished and rethrows what it threw. One background task at a time.
  void start_background(std::function<void()> task);
  void wait_background();

  // body(chunk, begin, end) for the `chunks` consecutive pieces of [0, count) (at most `count`;
  // their sizes differ by one at most); returns when all have run, rethrowing the first exception
  // a chunk threw.
  void for_chunks(std::size_t count, std::size_t chunks,
                  const std::function<void(std::size_t, std::size_t, std::size_t)>& body);

 private:
  struct Shared;
  std::unique_ptr<Shared> shared_;
};

// The workers installed on this thread by the innermost `UseWorkers` (none: nullptr). Stages
// deep in the pipeline split their loops through it without every constructor passing it on.
Workers* current_workers();

class UseWorkers {
 public:
  explicit UseWorkers(Workers* workers);
  ~UseWorkers();
  UseWorkers(const UseWorkers&) = delete;
  UseWorkers& operator=(const UseWorkers&) = delete;

 private:
  Workers* previous_;
};

// Chunks for a loop of `count` items on the current workers: one without workers or for a loop
// too short to share (below `min_per_chunk` items a chunk), else a few per thread, so that a
// thread that joins late still finds some.
std::size_t chunk_count(std::size_t count, std::size_t min_per_chunk);

// body(chunk, begin, end) over chunk_count(count, min_per_chunk) chunks of [0, count), on the
// current workers when there are any, in order on the caller otherwise.
void for_chunks(std::size_t count, std::size_t min_per_chunk,
                const std::function<void(std::size_t, std::size_t, std::size_t)>& body);

// first() and second(), two independent jobs: on two threads of the current workers when there
// are any, one after the other otherwise.
void run_both(const std::function<void()>& first, const std::function<void()>& second);

// produce(i, out) for each i of [0, count), which appends item i's results to `out`: split among
// the current workers, each chunk into a list of its own, joined in item order.
template <class T, class Produce>
void append_in_order(std::size_t count, std::size_t min_per_chunk, std::vector<T>& out,
                     const Produce& produce) {
  const std::size_t chunks = chunk_count(count, min_per_chunk);
  if (chunks == 1) {
    for (std::size_t i = 0; i < count; ++i)
      produce(i, out);
    return;
  }
  std::vector<std::vector<T>> parts(chunks);
  for_chunks(count, min_per_chunk, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      produce(i, parts[chunk]);
  });
  for (const std::vector<T>& part : parts)
    out.insert(out.end(), part.begin(), part.end());
}

}  // namespace adaptive_lego_loam
