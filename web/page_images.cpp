// The page's images: the browser decodes each PNG and JPEG file of the page's file system
// (createImageBitmap, in web/page.js) and hands its 8-bit sRGB pixels here; load_image_file,
// which the scene reader calls for textures and sky images, takes them from here, decoded to
// linear with the native build's table. The page has no OpenEXR decoder.
#include <emscripten/emscripten.h>
#include <fmt/format.h>

#include <map>
#include <memory>
#include <string>

#include "lightcone/io/image_file.hpp"
#include "lightcone/io/input_error.hpp"

namespace lightcone {
namespace {

std::map<std::string, std::shared_ptr<Image>>& decoded_images() {
  static std::map<std::string, std::shared_ptr<Image>> images;
  return images;
}

}  // namespace

std::shared_ptr<Image> load_image_file(const std::filesystem::path& file) {
  const auto& images = decoded_images();
  const auto found = images.find(file.lexically_normal().string());
  if (found != images.end()) return found->second;
  if (image_format_of(file) == ImageFormat::kExr)
    throw InputError(fmt::format("{}: OpenEXR images are not read in the browser (use PNG or JPEG)",
                                 file.string()));
  throw InputError(
      fmt::format("{}: no such PNG or JPEG image among the page's files", file.string()));
}

std::optional<ImageFormat> image_format_of(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (extension == ".png") return ImageFormat::kPng;
  if (extension == ".jpg" || extension == ".jpeg") return ImageFormat::kJpeg;
  if (extension == ".exr") return ImageFormat::kExr;
  return std::nullopt;
}

}  // namespace lightcone

extern "C" {

// The pixels of the image file at `path`: width x height, RGBA, 8 bits, sRGB, rows from the
// top (alpha is ignored, as the native reader ignores it).
EMSCRIPTEN_KEEPALIVE void lc_add_image(const char* path, int width, int height,
                                       const unsigned char* rgba) {
  using namespace lightcone;
  auto image = std::make_shared<Image>();
  image->source = path;
  image->width = width;
  image->height = height;
  image->rgb.resize(3 * static_cast<std::size_t>(width) * height);
  const auto& decoded = srgb_8bit_decoded();
  for (std::size_t i = 0; i < image->rgb.size() / 3; ++i)
    for (int c = 0; c < 3; ++c) image->rgb[3 * i + c] = decoded[rgba[4 * i + c]];
  decoded_images()[std::filesystem::path(path).lexically_normal().string()] = std::move(image);
}

}  // extern "C"
