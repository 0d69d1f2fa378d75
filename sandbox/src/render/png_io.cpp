#include "render/png_io.hpp"

#include <png.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>

namespace sandbox::render {
namespace {

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

// libpng reports errors by longjmp. Every setjmp lives in a small function holding only C data, so a
// longjmp never skips a C++ destructor (and GCC's -Wclobbered has nothing to warn about); the callers
// turn the failure into an exception.
[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error(path + ": " + what);
}

bool writeRows(std::FILE* file, png_uint_32 width, png_uint_32 height, png_bytepp rows, bool fast) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  if (png == nullptr) return false;
  png_infop info = png_create_info_struct(png);
  if (info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_init_io(png, file);
  // Level 6 costs a quarter of level 9's time at 1280x720 for a file a few percent larger.
  png_set_compression_level(png, fast ? 2 : 6);
  // At level 2 libpng's choice of filter per row took 43 ms of a 720p frame, Sub alone 25 ms, for about the
  // same size.
  if (fast) png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
  png_set_IHDR(png, info, width, height, 8, PNG_COLOR_TYPE_RGB_ALPHA, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

// Reads the header (after the 8 signature bytes) and sets up conversion of any PNG flavour to 8-bit RGBA.
bool readInfo(png_structp png, png_infop info, std::FILE* file, png_uint_32* width, png_uint_32* height) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_init_io(png, file);
  png_set_sig_bytes(png, 8);
  png_read_info(png, info);
  png_set_strip_16(png);
  png_set_packing(png);
  png_set_expand(png);
  png_set_gray_to_rgb(png);
  png_set_add_alpha(png, 0xff, PNG_FILLER_AFTER);
  png_read_update_info(png, info);
  *width = png_get_image_width(png, info);
  *height = png_get_image_height(png, info);
  return true;
}

bool readRows(png_structp png, png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_image(png, rows);
  png_read_end(png, nullptr);
  return true;
}

}  // namespace

void writePng(const std::string& path, int width, int height, const std::vector<uint8_t>& rgba,
              PngCompression compression) {
  if (width <= 0 || height <= 0) fail(path, "cannot write an empty image");
  if (rgba.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4) {
    fail(path, "pixel buffer has " + std::to_string(rgba.size()) + " bytes, expected " +
                   std::to_string(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4));
  }
  const std::string temporary = path + ".tmp";
  const std::size_t stride = static_cast<std::size_t>(width) * 4;
  std::vector<png_bytep> rows(static_cast<std::size_t>(height));
  for (std::size_t y = 0; y < rows.size(); ++y) rows[y] = const_cast<png_bytep>(rgba.data() + y * stride);
  std::string problem;
  {
    FilePtr file(std::fopen(temporary.c_str(), "wb"));
    if (!file) fail(path, std::string("cannot open for writing: ") + std::strerror(errno));
    if (!writeRows(file.get(), static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), rows.data(),
                   compression == PngCompression::Fast)) {
      problem = "libpng failed while writing";
    }
    if (problem.empty() && std::fflush(file.get()) != 0) problem = std::strerror(errno);
    if (problem.empty() && std::ferror(file.get())) problem = "write error";
  }
  std::error_code error;
  if (problem.empty()) std::filesystem::rename(temporary, path, error);
  if (!problem.empty() || error) {
    std::filesystem::remove(temporary, error);
    fail(path, problem.empty() ? "cannot rename " + temporary + " into place" : problem);
  }
}

Image readPng(const std::string& path) {
  FilePtr file(std::fopen(path.c_str(), "rb"));
  if (!file) fail(path, std::string("cannot open: ") + std::strerror(errno));
  png_byte signature[8] = {};
  if (std::fread(signature, 1, 8, file.get()) != 8 || png_sig_cmp(signature, 0, 8) != 0) {
    fail(path, "not a PNG file");
  }
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  if (png == nullptr) fail(path, "cannot create libpng reader");
  png_infop info = png_create_info_struct(png);
  png_uint_32 width = 0, height = 0;
  if (info == nullptr || !readInfo(png, info, file.get(), &width, &height) || width == 0 || height == 0 ||
      width > 65536 || height > 65536) {
    png_destroy_read_struct(&png, &info, nullptr);
    fail(path, "corrupt or unsupported PNG");
  }
  Image image;
  image.width = static_cast<int>(width);
  image.height = static_cast<int>(height);
  const std::size_t stride = static_cast<std::size_t>(width) * 4;
  image.rgba.resize(stride * height);
  std::vector<png_bytep> rows(height);
  for (std::size_t y = 0; y < rows.size(); ++y) rows[y] = image.rgba.data() + y * stride;
  const bool ok = readRows(png, rows.data());
  png_destroy_read_struct(&png, &info, nullptr);
  if (!ok) fail(path, "corrupt PNG");
  return image;
}

}  // namespace sandbox::render
