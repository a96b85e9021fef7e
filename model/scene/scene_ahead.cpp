// SPDX-License-Identifier: Apache-2.0
// stream_scene with the reader on a thread of its own (scene_io.h: SceneAhead,
// stream_scene_ahead).
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>
#include <utility>

#include "scene/scene_io.h"

namespace rastsim {

struct SceneAhead::Impl {
  struct Stopped {};  // thrown through the reader when the consumer has gone
  std::mutex mu;
  std::condition_variable cv;
  std::deque<std::vector<Command>> ready;
  bool parsed = false, stop = false;
  std::exception_ptr parse_error;
  std::thread parser;

  Impl(const std::string& path, const ObjPlacement& placement, size_t batch_commands, size_t batches_ahead) {
    parser = std::thread([this, path, placement, batch_commands, batches_ahead] {
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
  }
  ~Impl() {
    {
      const std::lock_guard<std::mutex> lock(mu);
      stop = true;
      cv.notify_all();
    }
    parser.join();
  }
};

SceneAhead::SceneAhead(const std::string& path, const ObjPlacement& placement, size_t batch_commands,
                       size_t batches_ahead)
    : impl_(std::make_unique<Impl>(path, placement, batch_commands, batches_ahead)) {}

SceneAhead::~SceneAhead() = default;

bool SceneAhead::next(std::vector<Command>& batch) {
  Impl& m = *impl_;
  std::unique_lock<std::mutex> lock(m.mu);
  m.cv.wait(lock, [&] { return !m.ready.empty() || m.parsed; });
  if (m.ready.empty()) {
    if (m.parse_error) std::rethrow_exception(std::exchange(m.parse_error, nullptr));
    return false;
  }
  batch = std::move(m.ready.front());
  m.ready.pop_front();
  m.cv.notify_all();
  return true;
}

void stream_scene_ahead(const std::string& path, const ObjPlacement& placement, size_t batch_commands,
                        size_t batches_ahead, const CommandBatchFn& consume) {
  SceneAhead reader(path, placement, batch_commands, batches_ahead);
  std::vector<Command> batch;
  while (reader.next(batch)) consume(batch);
}

}  // namespace rastsim
