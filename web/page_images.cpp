// The page's images: load_image_file, which the scene reader calls for textures and sky images,
// takes them from here. An image not decoded yet is thrown as ImageNotDecoded (page_images.hpp);
// the browser decodes it (createImageBitmap, in web/page.js) and hands its 8-bit sRGB pixels
// to lc_add_image, which decodes them to linear with the native build's table. The page has no
// OpenEXR decoder.
#include "page_images.hpp"

#include <emscripten/emscripten.h>
#include <fmt/format.h>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <system_error>

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
  const std::string key = file.lexically_normal().string();
  const auto found = images.find(key);
  if (found != images.end()) return found->second;
  const std::optional<ImageFormat> format = image_format_of(file);
  if (format == ImageFormat::kExr)
    throw InputError(fmt::format("{}: OpenEXR images are not read in the browser (use PNG or JPEG)",
                                 file.string()));
  std::error_code error;
  if (!format || !std::filesystem::is_regular_file(file, error))
    throw InputError(
        fmt::format("{}: no such PNG or JPEG image among the page's files", file.string()));
  throw ImageNotDecoded{key};
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
