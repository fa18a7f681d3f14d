// Reading textures and sky images; writing rendered images (PNG 8-bit sRGB, OpenEXR linear float).
#pragma once

#include <filesystem>
#include <memory>
#include <optional>

#include "lightcone/scene/scene.hpp"

namespace lightcone {

// PNG and JPEG (sRGB-encoded, decoded to linear) through stb_image; EXR (linear) through
// OpenEXR. Throws InputError naming the file when it is missing, unreadable or not an image.
std::shared_ptr<Image> load_image_file(const std::filesystem::path& file);

// sRGB opto-electronic transfer function for a linear value in [0, 1].
double srgb_encode(double linear);
// Its inverse.
double srgb_decode(double encoded);

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
