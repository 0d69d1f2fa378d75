#pragma once
// MP4 video from rendered frames: raw RGB frames piped into an `ffmpeg` process (H.264, yuv420p, so
// every player can show it). Only sandbox touches ffmpeg (DESIGN.md section 3).
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace sandbox::render {

struct VideoSettings {
  int width = 1280;               ///< frame width [px]; odd sizes are padded by one pixel (yuv420p)
  int height = 720;               ///< frame height [px]
  double fps = 30.0;              ///< frames per second of the video
  int crf = 20;                   ///< H.264 constant rate factor: 0 lossless .. 51 worst; 18-23 looks good
  std::string ffmpeg = "ffmpeg";  ///< program to run (a name on PATH or a path)
};

/// Streams frames to `path` (e.g. "out/video.mp4"). ffmpeg writes `path.tmp.mp4`, which is renamed to
/// `path` only when finish() sees ffmpeg succeed, so a crashed or aborted run never leaves a
/// half-written video that looks like a result.
class VideoWriter {
 public:
  /// Starts ffmpeg. Throws std::runtime_error when ffmpeg is not installed (checked with
  /// `command -v` first, saying so) or cannot be started; deform::InputError for a bad size or fps.
  VideoWriter(std::string path, const VideoSettings& settings);
  ~VideoWriter();  ///< without finish(): stops ffmpeg and deletes the partial file
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  /// Appends one frame: RGBA8, rows top to bottom, width * height * 4 bytes (alpha ignored).
  /// Throws std::runtime_error with ffmpeg's complaint if it stopped accepting frames.
  void addFrame(const std::vector<uint8_t>& rgba);

  /// Closes the stream, waits for ffmpeg and moves the file into place. Throws std::runtime_error with
  /// ffmpeg's log when it failed (and removes the partial file).
  void finish();

  int frameCount() const { return frames_; }
  const std::string& path() const { return path_; }

  /// True when `program` can be run (`command -v program` succeeds).
  static bool available(const std::string& program = "ffmpeg");

 private:
  /// Closes the pipe and removes the partial video; ffmpeg's log is kept only when it explains a failure.
  void abandon(bool keep_log);
  std::string ffmpegLog() const;  ///< last lines ffmpeg wrote to its log, for error messages

  std::string path_;       ///< final name of the video
  std::string temporary_;  ///< what ffmpeg writes until finish() succeeds
  std::string log_;        ///< ffmpeg's stderr, removed after a success
  VideoSettings settings_;
  std::FILE* pipe_ = nullptr;  ///< ffmpeg's stdin
  std::vector<uint8_t> rgb_;   ///< one frame repacked as RGB24
  int frames_ = 0;
};

/// Quotes `text` for /bin/sh: single quotes, embedded single quotes escaped.
std::string shellQuote(const std::string& text);

}  // namespace sandbox::render
