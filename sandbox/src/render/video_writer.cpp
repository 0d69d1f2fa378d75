#include "render/video_writer.hpp"

#include <deform/error.hpp>

#include <sys/wait.h>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace sandbox::render {

std::string shellQuote(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) {
    if (c == '\'') {
      quoted += "'\\''";
    } else {
      quoted += c;
    }
  }
  return quoted + "'";
}

bool VideoWriter::available(const std::string& program) {
  const std::string command = "command -v " + shellQuote(program) + " >/dev/null 2>&1";
  return std::system(command.c_str()) == 0;
}

VideoWriter::VideoWriter(std::string path, const VideoSettings& settings)
    : path_(std::move(path)), settings_(settings) {
  if (settings_.width <= 0 || settings_.height <= 0) {
    throw deform::InputError(path_ + ": video size must be positive (got " + std::to_string(settings_.width) +
                             "x" + std::to_string(settings_.height) + ")");
  }
  if (!(settings_.fps > 0 && settings_.fps <= 1000)) {
    throw deform::InputError(path_ + ": video fps must be in (0, 1000] (got " +
                             std::to_string(settings_.fps) + ")");
  }
  if (!available(settings_.ffmpeg)) {
    throw std::runtime_error("cannot write " + path_ + ": '" + settings_.ffmpeg +
                             "' is not installed or not on PATH (Debian: apt install ffmpeg); PNG frames "
                             "can still be written without it");
  }
  temporary_ = path_ + ".tmp.mp4";
  log_ = path_ + ".ffmpeg.log";
  // A dying ffmpeg would otherwise kill this process with SIGPIPE on the next write; ignoring it turns
  // that into a write error we can report with ffmpeg's own message.
  std::signal(SIGPIPE, SIG_IGN);
  std::ostringstream command;
  command << shellQuote(settings_.ffmpeg) << " -y -hide_banner -loglevel error"
          << " -f rawvideo -pixel_format rgb24 -video_size " << settings_.width << "x" << settings_.height
          << " -framerate " << settings_.fps
          << " -i pipe:0"
          // yuv420p halves chroma resolution, so both sides must be even: pad odd sizes by a pixel.
          << " -vf " << shellQuote("pad=ceil(iw/2)*2:ceil(ih/2)*2") << " -c:v libx264 -preset veryfast -crf "
          << settings_.crf << " -pix_fmt yuv420p"
          << " -movflags +faststart -f mp4 " << shellQuote(temporary_) << " 2>" << shellQuote(log_);
  pipe_ = popen(command.str().c_str(), "w");
  if (pipe_ == nullptr) throw std::runtime_error("cannot start " + settings_.ffmpeg + " to write " + path_);
  rgb_.resize(static_cast<std::size_t>(settings_.width) * static_cast<std::size_t>(settings_.height) * 3);
}

VideoWriter::~VideoWriter() {
  abandon(false);
}

void VideoWriter::addFrame(const std::vector<uint8_t>& rgba) {
  if (pipe_ == nullptr) throw std::runtime_error(path_ + ": frame added after the video was finished");
  const std::size_t pixels = rgb_.size() / 3;
  if (rgba.size() != pixels * 4) {
    throw std::runtime_error(path_ + ": frame has " + std::to_string(rgba.size()) + " bytes, expected " +
                             std::to_string(pixels * 4));
  }
  for (std::size_t i = 0; i < pixels; ++i) {
    rgb_[3 * i + 0] = rgba[4 * i + 0];
    rgb_[3 * i + 1] = rgba[4 * i + 1];
    rgb_[3 * i + 2] = rgba[4 * i + 2];
  }
  if (std::fwrite(rgb_.data(), 1, rgb_.size(), pipe_) != rgb_.size()) {
    const std::string log = ffmpegLog();
    abandon(true);
    throw std::runtime_error(path_ + ": ffmpeg stopped accepting frames after " + std::to_string(frames_) +
                             (log.empty() ? std::string() : ": " + log));
  }
  ++frames_;
}

void VideoWriter::finish() {
  if (pipe_ == nullptr) throw std::runtime_error(path_ + ": video already finished or abandoned");
  const int status = pclose(pipe_);
  pipe_ = nullptr;
  const bool ok = status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  std::error_code error;
  if (ok && frames_ > 0) {
    std::filesystem::rename(temporary_, path_, error);
    if (!error) {
      std::filesystem::remove(log_, error);
      return;
    }
  }
  const std::string log = ffmpegLog();
  abandon(frames_ > 0);
  if (frames_ == 0) throw std::runtime_error(path_ + ": no frames were added; no video written");
  throw std::runtime_error(path_ + ": ffmpeg failed" + (log.empty() ? std::string() : ": " + log));
}

void VideoWriter::abandon(bool keep_log) {
  if (pipe_ != nullptr) {
    pclose(pipe_);
    pipe_ = nullptr;
  }
  std::error_code error;
  if (!temporary_.empty()) std::filesystem::remove(temporary_, error);
  // The log stays when ffmpeg failed: it is the only trace of ffmpeg's reason.
  if (!keep_log && !log_.empty()) std::filesystem::remove(log_, error);
  log_.clear();  // a later call (the destructor) must neither remove a kept log nor read a stale one
  temporary_.clear();
}

std::string VideoWriter::ffmpegLog() const {
  std::ifstream in(log_);
  std::string line, last;
  while (std::getline(in, line)) {
    if (!line.empty()) last = line;
  }
  return last;
}

}  // namespace sandbox::render
