// SPDX-License-Identifier: Apache-2.0
// stream_scene with the reader on a thread of its own (scene_io.h, stream_scene_ahead).
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>

#include "scene/scene_io.h"

namespace rastsim {

void stream_scene_ahead(const std::string& path, const ObjPlacement& placement, size_t batch_commands,
                        size_t batches_ahead, const CommandBatchFn& consume) {
  struct Stopped {};  // thrown through the reader when the consumer has failed
  std::mutex mu;
  std::condition_variable cv;
  std::deque<std::vector<Command>> ready;
  bool parsed = false, stop = false;
  std::exception_ptr parse_error;
  std::thread parser([&] {
    try {
      stream_scene(path, placement, batch_commands, [&](std::vector<Command>& batch) {
        std::unique_lock<std::mutex> lock(mu);
        cv.wait(lock, [&] { return ready.size() < batches_ahead || stop; });
        if (stop) throw Stopped{};
        ready.push_back(std::move(batch));
        cv.notify_all();
      });
    } catch (const Stopped&) {
    } catch (...) {
      const std::lock_guard<std::mutex> lock(mu);
      parse_error = std::current_exception();
    }
    const std::lock_guard<std::mutex> lock(mu);
    parsed = true;
    cv.notify_all();
  });
  try {
    for (;;) {
      std::vector<Command> batch;
      {
        std::unique_lock<std::mutex> lock(mu);
        cv.wait(lock, [&] { return !ready.empty() || parsed; });
        if (ready.empty()) break;
        batch = std::move(ready.front());
        ready.pop_front();
        cv.notify_all();
      }
      consume(batch);
    }
  } catch (...) {
    {
      const std::lock_guard<std::mutex> lock(mu);
      stop = true;
      cv.notify_all();
    }
    parser.join();
    throw;
  }
  parser.join();
  if (parse_error) std::rethrow_exception(parse_error);
}

}  // namespace rastsim
