#include "frame_writer.hpp"

#include <utility>

namespace sandbox {

FrameWriter::FrameWriter(Write write) : write_(std::move(write)), worker_([this] { work(); }) {}

FrameWriter::~FrameWriter() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    waiting_.reset();
  }
  changed_.notify_all();
  worker_.join();
}

void FrameWriter::add(render::Image image, int index) {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return !waiting_ || error_; });
  rethrow();
  waiting_.emplace(std::move(image), index);
  changed_.notify_all();
}

void FrameWriter::finish() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return (!waiting_ && !busy_) || error_; });
  rethrow();
}

void FrameWriter::rethrow() {
  if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
}

void FrameWriter::work() {
  for (;;) {
    std::pair<render::Image, int> frame;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [this] { return waiting_ || stopping_; });
      if (stopping_) return;
      frame = std::move(*waiting_);
      waiting_.reset();
      busy_ = true;
    }
    changed_.notify_all();
    std::exception_ptr error;
    try {
      write_(frame.first, frame.second);
    } catch (...) {
      error = std::current_exception();
    }
    {
      std::lock_guard lock(mutex_);
      busy_ = false;
      // After a failure the frames still to come are dropped: the caller hears of it on its next call.
      if (error) {
        error_ = error;
        waiting_.reset();
      }
    }
    changed_.notify_all();
  }
}

}  // namespace sandbox
