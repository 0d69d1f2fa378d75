#include "render/frame_output.hpp"

#include <deform/error.hpp>
#include <deform/path_checks.hpp>

#include <cstdio>
#include <filesystem>

namespace sandbox::render {

FrameOutput::FrameOutput(const FrameOutputSettings& settings) : settings_(settings) {
  if (!settings_.png_folder.empty() && !deform::isDirectory(settings_.png_folder)) {
    throw deform::InputError(settings_.png_folder + ": frame folder does not exist");
  }
  if (!settings_.video_path.empty())
    video_ = std::make_unique<VideoWriter>(settings_.video_path, settings_.video);
}

std::string FrameOutput::pngPath(int index) const {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06d.png", index);
  return (std::filesystem::path(settings_.png_folder) / name).string();
}

void FrameOutput::add(const Image& frame) {
  if (!settings_.png_folder.empty()) writePng(pngPath(frames_), frame.width, frame.height, frame.rgba);
  if (video_) video_->addFrame(frame.rgba);
  ++frames_;
}

void FrameOutput::finish() {
  if (video_) video_->finish();
}

}  // namespace sandbox::render
