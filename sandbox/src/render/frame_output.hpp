#pragma once
// Where the frames of a run go: numbered PNGs in a folder, an MP4 video, or both. A scene runner
// renders a frame and hands it here; nothing else needs to know about libpng or ffmpeg.
#include "render/png_io.hpp"
#include "render/video_writer.hpp"

#include <memory>
#include <string>

namespace sandbox::render {

struct FrameOutputSettings {
  std::string png_folder;  ///< frames as png_folder/frame_000000.png ...; empty: no PNGs
  std::string video_path;  ///< e.g. "out/video.mp4"; empty: no video
  VideoSettings video;     ///< size, fps and encoder of the video (size must match the frames)
};

class FrameOutput {
 public:
  /// Checks the PNG folder exists (deform::InputError naming it otherwise) and starts ffmpeg if a
  /// video is wanted (its errors as VideoWriter's).
  explicit FrameOutput(const FrameOutputSettings& settings);

  /// Writes one frame to every output.
  void add(const Image& frame);

  /// Completes the video (renamed into place only now). Without this call the partial video is deleted.
  void finish();

  int frameCount() const { return frames_; }
  /// Path of PNG frame `index`.
  std::string pngPath(int index) const;

 private:
  FrameOutputSettings settings_;
  std::unique_ptr<VideoWriter> video_;
  int frames_ = 0;
};

}  // namespace sandbox::render
