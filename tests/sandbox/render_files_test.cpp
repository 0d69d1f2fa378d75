// PNG round trip, the heat-map ramp, and MP4 video through ffmpeg.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "render/colour_ramp.hpp"
#include "render/png_io.hpp"
#include "render/video_writer.hpp"
#include "render_test_support.hpp"
#include "support.hpp"

using namespace sandbox::render;
namespace fs = std::filesystem;

namespace {

// Hue in degrees [0, 360) of an RGB colour.
float hueDegrees(const Eigen::Vector3f& c) {
  const float max = c.maxCoeff(), min = c.minCoeff(), d = max - min;
  if (d <= 0.0f) return 0.0f;
  float h = 0.0f;
  if (max == c.x()) {
    h = std::fmod((c.y() - c.z()) / d + 6.0f, 6.0f);
  } else if (max == c.y()) {
    h = (c.z() - c.x()) / d + 2.0f;
  } else {
    h = (c.x() - c.y()) / d + 4.0f;
  }
  return 60.0f * h;
}

std::string runCommand(const std::string& command) {
  std::string output;
  if (FILE* pipe = popen(command.c_str(), "r")) {
    char buffer[256];
    while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) output += buffer;
    pclose(pipe);
  }
  return output;
}

Image gradientImage(int width, int height) {
  Image image{width, height, std::vector<uint8_t>(static_cast<std::size_t>(width * height * 4))};
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      uint8_t* p = &image.rgba[static_cast<std::size_t>((y * width + x) * 4)];
      p[0] = static_cast<uint8_t>(x * 255 / std::max(1, width - 1));
      p[1] = static_cast<uint8_t>(y * 255 / std::max(1, height - 1));
      p[2] = static_cast<uint8_t>((x * 7 + y * 13) % 256);
      p[3] = static_cast<uint8_t>(255 - (x + y) % 3);
    }
  }
  return image;
}

}  // namespace

TEST_CASE("heatColour runs from blue (none) to red (most) with a falling hue", "[render]") {
  const Eigen::Vector3f none = heatColour(0.0f), most = heatColour(1.0f);
  CHECK(none.z() > 0.8f);
  CHECK(none.x() < 0.2f);
  CHECK(none.y() < 0.2f);
  CHECK(most.x() > 0.8f);
  CHECK(most.y() < 0.2f);
  CHECK(most.z() < 0.2f);
  CHECK(hueDegrees(none) == Approx(240.0f).margin(10.0f));
  CHECK(hueDegrees(most) < 10.0f);
  // Clamped outside [0, 1]; NaN is shown as the worst, never as untouched.
  CHECK(heatColour(-3.0f).isApprox(none));
  CHECK(heatColour(7.0f).isApprox(most));
  CHECK(heatColour(std::nanf("")).isApprox(most));
  CHECK(heatColour(-INFINITY).isApprox(none));
  CHECK(heatColour(INFINITY).isApprox(most));
  float previous = hueDegrees(none);
  for (int i = 1; i <= 200; ++i) {
    const Eigen::Vector3f c = heatColour(static_cast<float>(i) / 200.0f);
    const float hue = hueDegrees(c);
    INFO("t = " << i / 200.0 << ", hue " << hue);
    CHECK(hue <= previous + 1e-3f);
    CHECK(c.minCoeff() >= 0.0f);
    CHECK(c.maxCoeff() <= 1.0f);
    previous = hue;
  }
}

TEST_CASE("writePng then readPng gives back the same pixels", "[render]") {
  const fs::path dir = render_test::scratchDir("render_png");
  const Image image = gradientImage(37, 23);  // odd sizes: rows are not padded
  const std::string path = (dir / "frame.png").string();
  writePng(path, image.width, image.height, image.rgba);
  CHECK_FALSE(fs::exists(path + ".tmp"));
  const Image back = readPng(path);
  CHECK(back.width == image.width);
  CHECK(back.height == image.height);
  CHECK(back.rgba == image.rgba);
  // The fast compression of a run's frames is lossless too.
  writePng(path, image.width, image.height, image.rgba, PngCompression::Fast);
  CHECK(readPng(path).rgba == image.rgba);
  fs::remove_all(dir);
}

TEST_CASE("PNG failures name the path and leave no file behind", "[render]") {
  const fs::path dir = render_test::scratchDir("render_png_fail");
  const Image image = gradientImage(8, 4);
  const std::string missing_folder = (dir / "no_such_folder" / "frame.png").string();
  CHECK_THROWS_WITH(writePng(missing_folder, image.width, image.height, image.rgba),
                    Catch::Contains(missing_folder));
  CHECK_THROWS_WITH(writePng((dir / "short.png").string(), 9, 4, image.rgba), Catch::Contains("short.png"));
  CHECK_FALSE(fs::exists(dir / "short.png"));
  CHECK_FALSE(fs::exists(dir / "short.png.tmp"));
  const std::string text = (dir / "not.png").string();
  {
    std::FILE* f = std::fopen(text.c_str(), "w");
    std::fputs("hello", f);
    std::fclose(f);
  }
  CHECK_THROWS_WITH(readPng(text), Catch::Contains(text) && Catch::Contains("not a PNG"));
  fs::remove_all(dir);
}

TEST_CASE("VideoWriter makes an MP4 that ffprobe decodes frame by frame", "[render]") {
  if (!VideoWriter::available("ffmpeg") || !VideoWriter::available("ffprobe")) {
    test_support::reportSkip("ffmpeg or ffprobe is not installed: the video test needs them");
    return;
  }
  const fs::path dir = render_test::scratchDir("render_video");
  // An odd size too: yuv420p needs even sides, the writer pads.
  for (const auto& [width, height] : {std::pair{64, 36}, std::pair{63, 35}}) {
    const std::string path = (dir / ("video_" + std::to_string(width) + ".mp4")).string();
    constexpr int kFrames = 7;
    {
      VideoWriter video(path, {width, height, 24.0});
      for (int i = 0; i < kFrames; ++i) {
        Image frame = gradientImage(width, height);
        frame.rgba[0] = static_cast<uint8_t>(i * 30);  // frames differ
        video.addFrame(frame.rgba);
      }
      CHECK_FALSE(fs::exists(path));  // nothing is passed off before finish()
      video.finish();
      CHECK(video.frameCount() == kFrames);
    }
    REQUIRE(fs::exists(path));
    CHECK_FALSE(fs::exists(path + ".tmp.mp4"));
    CHECK_FALSE(fs::exists(path + ".ffmpeg.log"));
    const std::string probe = runCommand(
        "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
        "stream=nb_read_frames,codec_name,pix_fmt,width -of csv=p=0 " +
        shellQuote(path));
    INFO("ffprobe says: " << probe);
    CHECK(probe.find("h264") != std::string::npos);
    CHECK(probe.find("yuv420p") != std::string::npos);
    CHECK(probe.find(std::to_string(width + width % 2)) != std::string::npos);
    CHECK(probe.find("," + std::to_string(kFrames)) != std::string::npos);
  }
  fs::remove_all(dir);
}

TEST_CASE("VideoWriter refuses a missing ffmpeg and leaves nothing when abandoned", "[render]") {
  const fs::path dir = render_test::scratchDir("render_video_fail");
  const std::string path = (dir / "video.mp4").string();
  VideoSettings settings{32, 32, 10.0};
  settings.ffmpeg = "ffmpeg-that-is-not-installed";
  CHECK_THROWS_WITH(VideoWriter(path, settings), Catch::Contains("not installed") && Catch::Contains(path));
  CHECK_THROWS_AS(VideoWriter(path, {0, 32, 10.0}), std::exception);
  if (VideoWriter::available("ffmpeg")) {
    {
      VideoWriter video(path, {32, 32, 10.0});
      video.addFrame(gradientImage(32, 32).rgba);
    }  // destroyed without finish(): an aborted run
    CHECK_FALSE(fs::exists(path));
    CHECK_FALSE(fs::exists(path + ".tmp.mp4"));
  }
  fs::remove_all(dir);
}
