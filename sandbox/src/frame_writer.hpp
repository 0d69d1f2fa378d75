#pragma once
// Finishing and writing frames on a worker thread (edge smoothing, PNG compression, the pipe to ffmpeg)
// while the next frame renders: on two cores llvmpipe leaves one idle while it sets up a frame.
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>

#include "render/png_io.hpp"

namespace sandbox {

class FrameWriter {
 public:
  /// `write(image, index)` finishes and writes one frame; it runs on the worker, one frame at a time,
  /// in the order the frames were added.
  using Write = std::function<void(render::Image& image, int index)>;

  explicit FrameWriter(Write write);
  /// Stops the worker after the frame it is on; frames still waiting are dropped (call finish() first).
  ~FrameWriter();
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;

  /// Hands a frame over. Waits while one frame is already waiting (at most one frame being written and
  /// one waiting are held). Rethrows what an earlier write threw.
  void add(render::Image image, int index);
  /// Waits until every frame added is written; rethrows what a write threw.
  void finish();

 private:
  void work();
  void rethrow();

  Write write_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::optional<std::pair<render::Image, int>> waiting_;
  bool busy_ = false;
  bool stopping_ = false;
  std::exception_ptr error_;
  std::thread worker_;  ///< last: started once the rest is in place
};

}  // namespace sandbox
