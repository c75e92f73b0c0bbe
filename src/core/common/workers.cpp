#include "adaptive_lego_loam/core/common/workers.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

namespace adaptive_lego_loam {
namespace {

thread_local Workers* installed_workers = nullptr;
// Set while this thread runs a chunk: a loop inside it runs inline, the other threads being busy
// with (or free to take) the outer loop's chunks.
thread_local bool inside_chunk = false;

// One loop's chunks: taken by index, counted when finished.
struct Loop {
  std::size_t count = 0, chunks = 0;
  const std::function<void(std::size_t, std::size_t, std::size_t)>* body = nullptr;
  std::atomic<std::size_t> next{0};
  std::size_t finished = 0;  // under the mutex
  std::exception_ptr error;  // under the mutex

  // Runs chunks until none is left; returns how many this thread ran and their first error.
  std::size_t run(std::exception_ptr& first_error) {
    std::size_t ran = 0;
    for (std::size_t chunk = next++; chunk < chunks; chunk = next++) {
      const std::size_t begin = chunk * count / chunks, end = (chunk + 1) * count / chunks;
      inside_chunk = true;
      try {
        (*body)(chunk, begin, end);
      } catch (...) {
        if (!first_error) first_error = std::current_exception();
      }
      inside_chunk = false;
      ++ran;
    }
    return ran;
  }
};

}  // namespace

struct Workers::Shared {
  int threads = 1;
  std::mutex mutex;
  std::condition_variable wake, finished;
  bool stopping = false;
  std::function<void()> background;  // waiting to be taken
  bool background_running = false;
  std::exception_ptr background_error;
  std::shared_ptr<Loop> loop;  // the loop whose chunks are being taken
  std::vector<std::thread> helpers;

  void finish_chunks(Loop& loop, std::size_t ran, std::exception_ptr error) {
    std::lock_guard<std::mutex> lock(mutex);
    loop.finished += ran;
    if (error && !loop.error) loop.error = error;
    if (loop.finished == loop.chunks) finished.notify_all();
  }

  void helper() {
    std::unique_lock<std::mutex> lock(mutex);
    while (true) {
      wake.wait(lock, [&] {
        return stopping || background || (loop && loop->next.load() < loop->chunks);
      });
      if (stopping) return;
      // The background task first: it is the longest piece of work, and a loop's caller takes
      // chunks itself.
      if (background) {
        std::function<void()> task = std::move(background);
        background = nullptr;
        lock.unlock();
        std::exception_ptr error;
        try {
          task();
        } catch (...) {
          error = std::current_exception();
        }
        lock.lock();
        background_running = false;
        background_error = error;
        finished.notify_all();
        continue;
      }
      const std::shared_ptr<Loop> taken = loop;
      lock.unlock();
      std::exception_ptr error;
      const std::size_t ran = taken->run(error);
      finish_chunks(*taken, ran, error);
      lock.lock();
    }
  }
};

Workers::Workers(int threads) : shared_(std::make_unique<Shared>()) {
  if (threads < 1) throw std::invalid_argument("Workers: threads must be at least 1");
  shared_->threads = threads;
  for (int k = 1; k < threads; ++k)
    shared_->helpers.emplace_back([shared = shared_.get()] { shared->helper(); });
}

Workers::~Workers() {
  {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    shared_->stopping = true;
  }
  shared_->wake.notify_all();
  for (std::thread& helper : shared_->helpers)
    helper.join();
}

int Workers::threads() const {
  return shared_->threads;
}

void Workers::start_background(std::function<void()> task) {
  Shared& s = *shared_;
  if (s.helpers.empty()) {
    try {
      task();
    } catch (...) {
      s.background_error = std::current_exception();
    }
    return;
  }
  std::lock_guard<std::mutex> lock(s.mutex);
  if (s.background_running) throw std::logic_error("Workers: a background task is running");
  s.background = std::move(task);
  s.background_running = true;
  s.wake.notify_one();
}

void Workers::wait_background() {
  Shared& s = *shared_;
  std::unique_lock<std::mutex> lock(s.mutex);
  s.finished.wait(lock, [&] { return !s.background_running; });
  if (std::exception_ptr error = std::exchange(s.background_error, nullptr))
    std::rethrow_exception(error);
}

void Workers::for_chunks(std::size_t count, std::size_t chunks,
                         const std::function<void(std::size_t, std::size_t, std::size_t)>& body) {
  Shared& s = *shared_;
  chunks = std::min(chunks, count);
  if (chunks == 0) return;
  auto loop = std::make_shared<Loop>();
  loop->count = count;
  loop->chunks = chunks;
  loop->body = &body;
  if (!s.helpers.empty() && chunks > 1) {
    std::lock_guard<std::mutex> lock(s.mutex);
    s.loop = loop;
    s.wake.notify_all();
  }
  std::exception_ptr error;
  const std::size_t ran = loop->run(error);
  s.finish_chunks(*loop, ran, error);
  std::unique_lock<std::mutex> lock(s.mutex);
  s.finished.wait(lock, [&] { return loop->finished == loop->chunks; });
  if (s.loop == loop) s.loop.reset();
  if (loop->error) std::rethrow_exception(loop->error);
}

Workers* current_workers() {
  return installed_workers;
}

UseWorkers::UseWorkers(Workers* workers) : previous_(installed_workers) {
  installed_workers = workers;
}

UseWorkers::~UseWorkers() {
  installed_workers = previous_;
}

std::size_t chunk_count(std::size_t count, std::size_t min_per_chunk) {
  const Workers* workers = current_workers();
  if (!workers || workers->threads() == 1 || inside_chunk) return 1;
  const std::size_t wanted = 4 * static_cast<std::size_t>(workers->threads());
  return std::clamp<std::size_t>(count / std::max<std::size_t>(min_per_chunk, 1), 1, wanted);
}

void for_chunks(std::size_t count, std::size_t min_per_chunk,
                const std::function<void(std::size_t, std::size_t, std::size_t)>& body) {
  const std::size_t chunks = chunk_count(count, min_per_chunk);
  Workers* workers = current_workers();
  if (!workers || chunks == 1) {
    if (count > 0) body(0, 0, count);
    return;
  }
  workers->for_chunks(count, chunks, body);
}

void run_both(const std::function<void()>& first, const std::function<void()>& second) {
  for_chunks(2, 1, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t job = begin; job < end; ++job)
      (job == 0 ? first : second)();
  });
}

}  // namespace adaptive_lego_loam
