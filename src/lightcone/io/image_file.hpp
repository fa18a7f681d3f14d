// Reading textures and sky images; writing rendered images (PNG 8-bit sRGB, OpenEXR linear float).
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "lightcone/io/srgb.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

// The EXR header attribute (a double) holding Image::exposure, the EV the pixels were scaled by:
// the radiance is the pixels times 2^-value.
inline constexpr const char* kExrExposureAttribute = "lightcone:exposureEV";

// PNG and JPEG (sRGB-encoded, decoded to linear) through libspng and libjpeg-turbo; EXR (linear)
// through OpenEXR, its channels other than R, G, B (or Y) kept as Image::channels and its
// kExrExposureAttribute as Image::exposure. Throws InputError naming the file when it is
// missing, unreadable or not an image.
std::shared_ptr<Image> load_image_file(const std::filesystem::path& file);

enum class ImageFormat { kPng, kJpeg, kExr };

// The format an output file's name asks for, by its extension (.png; .jpg or .jpeg; .exr; in
// any case); nullopt for any other.
std::optional<ImageFormat> image_format_of(const std::filesystem::path& file);

struct ImageOutput {
  std::filesystem::path path;
  ImageFormat format = ImageFormat::kPng;
};

// Writes every output, PNG and JPEG (quality 95) 8-bit sRGB from `display` (values in [0, 1]),
// EXR linear 32-bit float from `linear` (with its named channels, and its exposure, where known,
// as kExrExposureAttribute), each first under a temporary name beside its target, all renamed
// only when every write succeeded: a failure leaves no half-written output. Throws
// std::runtime_error on failure.
void write_images(const Image& display, const Image& linear,
                  const std::vector<ImageOutput>& outputs);

// The 8-bit sRGB pixels (row-major, RGB) a PNG of the display image holds.
std::vector<unsigned char> display_rgb8(const Image& display);
// The same into `pixels` (3 width height bytes), which need not be initialised.
void display_rgb8(const Image& display, unsigned char* pixels);
// The codes of `count` display values (one thread; a row of a picture, say).
void display_rgb8_values(const float* values, std::size_t count, unsigned char* codes);

// The PNG file's bytes for a display image (for writing to standard output).
std::vector<unsigned char> encode_png(const Image& display);

// Writes the linear image (radiance already multiplied by 2^exposure) to the requested files:
// PNG = round(255 srgb_encode(clamp(L, 0, 1))), EXR = L as 32-bit float RGB. Every file is
// first written under a temporary name beside its target and renamed only when all writes
// succeeded, so a failure leaves no half-written output. Throws std::runtime_error on failure.
void write_images(const Image& linear, const std::optional<std::filesystem::path>& png,
                  const std::optional<std::filesystem::path>& exr);

// The same, with the PNG encoded from a separate display image (tone-mapped, values in [0, 1])
// while the EXR keeps the linear radiance.
void write_images(const Image& display, const Image& linear,
                  const std::optional<std::filesystem::path>& png,
                  const std::optional<std::filesystem::path>& exr);

}  // namespace lightcone
