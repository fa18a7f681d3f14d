// Images: PNG/JPEG/BMP/TGA/HDR read through stb_image and PNG written through stb_image_write
// (both implemented in Debian's libstb, so no *_IMPLEMENTATION here); EXR through OpenEXR.
#include "lightcone/io/image_file.hpp"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <fmt/format.h>
#include <stb_image.h>
#include <stb_image_write.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "lightcone/io/input_error.hpp"
#include "lightcone/io/input_file.hpp"

namespace lightcone {

double srgb_encode(double linear) {
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
}

double srgb_decode(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const fs::path& file, std::string_view what) {
  throw InputError(fmt::format("{}: {}", file.string(), what));
}

std::vector<unsigned char> read_bytes(const fs::path& file) {
  const std::string bytes = read_input_file(file, "image", kMaxAssetFileBytes);
  return {bytes.begin(), bytes.end()};
}

bool is_exr(const std::vector<unsigned char>& bytes) {
  static constexpr unsigned char magic[] = {0x76, 0x2f, 0x31, 0x01};
  return bytes.size() >= 4 && std::equal(std::begin(magic), std::end(magic), bytes.begin());
}

// Images larger than this many pixels are refused before anything is allocated for them (a
// header may declare any size).
constexpr long long kMaxImagePixels = 1LL << 26;  // 67 million: 8192 x 8192

void check_image_size(const fs::path& file, long long width, long long height) {
  if (width <= 0 || height <= 0 || width * height > kMaxImagePixels)
    fail(file, fmt::format("{}x{} pixels: more than the limit of {} pixels for an image", width,
                           height, kMaxImagePixels));
}

std::shared_ptr<Image> load_exr(const fs::path& file) {
  auto image = std::make_shared<Image>();
  image->source = file.string();
  try {
    Imf::InputFile in(file.c_str());
    const Imath::Box2i window = in.header().dataWindow();
    check_image_size(file, static_cast<long long>(window.max.x) - window.min.x + 1,
                     static_cast<long long>(window.max.y) - window.min.y + 1);
    image->width = window.max.x - window.min.x + 1;
    image->height = window.max.y - window.min.y + 1;
    image->rgb.assign(3 * static_cast<std::size_t>(image->width) * image->height, 0.0f);
    const Imf::ChannelList& channels = in.header().channels();
    const bool rgb =
        channels.findChannel("R") || channels.findChannel("G") || channels.findChannel("B");
    const bool grey = !rgb && channels.findChannel("Y");
    if (!rgb && !grey) fail(file, "OpenEXR image has no R, G, B or Y channel");
    const std::size_t x_stride = 3 * sizeof(float), y_stride = x_stride * image->width;
    Imf::FrameBuffer frame;
    // Absent channels of R, G, B read as 0.
    const char* names[] = {"R", "G", "B"};
    for (int c = 0; c < (grey ? 1 : 3); ++c)
      frame.insert(grey ? "Y" : names[c],
                   Imf::Slice::Make(Imf::FLOAT, image->rgb.data() + c, window, x_stride, y_stride));
    // Every other channel (output variables such as "doppler") is kept by name.
    for (auto c = channels.begin(); c != channels.end(); ++c) {
      const std::string name = c.name();
      if (name == "R" || name == "G" || name == "B" || name == "Y") continue;
      image->channels.push_back(
          {name, std::vector<float>(static_cast<std::size_t>(image->width) * image->height)});
    }
    for (NamedChannel& c : image->channels)
      frame.insert(c.name, Imf::Slice::Make(Imf::FLOAT, c.values.data(), window, sizeof(float),
                                            sizeof(float) * image->width));
    in.setFrameBuffer(frame);
    in.readPixels(window.min.y, window.max.y);
    if (grey)
      for (std::size_t i = 0; i < image->rgb.size(); i += 3)
        image->rgb[i + 1] = image->rgb[i + 2] = image->rgb[i];
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    fail(file, fmt::format("cannot read OpenEXR image ({})", e.what()));
  }
  return image;
}

struct StbFree {
  void operator()(void* p) const { stbi_image_free(p); }
};

// Spreads n-channel pixels (grey, grey+alpha, RGB, RGBA) to RGB, decoding each value. stb's own
// conversion (req_comp = 3) mangles 16-bit PNM in the packaged version, so it is done here.
template <class T, class Decode>
void to_rgb(const T* pixels, int channels, Image& image, Decode decode) {
  const std::size_t count = static_cast<std::size_t>(image.width) * image.height;
  image.rgb.resize(3 * count);
  const bool grey = channels < 3;
  for (std::size_t i = 0; i < count; ++i) {
    const T* p = pixels + i * channels;
    for (int c = 0; c < 3; ++c) image.rgb[3 * i + c] = decode(p[grey ? 0 : c]);
  }
}

std::shared_ptr<Image> load_stb(const fs::path& file, const std::vector<unsigned char>& bytes) {
  if (bytes.size() > static_cast<std::size_t>(INT_MAX)) fail(file, "image file too large");
  const auto* data = bytes.data();
  const int size = static_cast<int>(bytes.size());
  int declared_width = 0, declared_height = 0, declared_channels = 0;
  if (stbi_info_from_memory(data, size, &declared_width, &declared_height, &declared_channels))
    check_image_size(file, declared_width, declared_height);
  auto image = std::make_shared<Image>();
  image->source = file.string();
  int channels = 0;
  const auto check = [&](const void* pixels) {
    if (pixels == nullptr)
      fail(file, fmt::format("not a readable image ({})", stbi_failure_reason()));
    if (channels < 1 || channels > 4) fail(file, fmt::format("unsupported {} channels", channels));
  };
  if (stbi_is_hdr_from_memory(data, size)) {
    // Radiance HDR holds linear values already.
    std::unique_ptr<float, StbFree> pixels(
        stbi_loadf_from_memory(data, size, &image->width, &image->height, &channels, 0));
    check(pixels.get());
    to_rgb(pixels.get(), channels, *image, [](float v) { return v; });
  } else if (stbi_is_16_bit_from_memory(data, size)) {
    std::unique_ptr<stbi_us, StbFree> pixels(
        stbi_load_16_from_memory(data, size, &image->width, &image->height, &channels, 0));
    check(pixels.get());
    to_rgb(pixels.get(), channels, *image,
           [](stbi_us v) { return static_cast<float>(srgb_decode(v / 65535.0)); });
  } else {
    std::unique_ptr<stbi_uc, StbFree> pixels(
        stbi_load_from_memory(data, size, &image->width, &image->height, &channels, 0));
    check(pixels.get());
    static const std::array<float, 256> decoded = [] {
      std::array<float, 256> table;
      for (int i = 0; i < 256; ++i) table[i] = static_cast<float>(srgb_decode(i / 255.0));
      return table;
    }();
    to_rgb(pixels.get(), channels, *image, [](stbi_uc v) { return decoded[v]; });
  }
  return image;
}

[[noreturn]] void fail_write(const fs::path& target, std::string_view what) {
  throw std::runtime_error(fmt::format("{}: {}", target.string(), what));
}

void append_bytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<unsigned char>*>(context);
  const auto* bytes = static_cast<const unsigned char*>(data);
  out->insert(out->end(), bytes, bytes + size);
}

std::vector<unsigned char> display_bytes(const Image& image) {
  std::vector<unsigned char> pixels(image.rgb.size());
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const float v = image.rgb[i];
    const double clamped = std::isnan(v) ? 0.0 : std::clamp<double>(v, 0.0, 1.0);
    pixels[i] = static_cast<unsigned char>(std::lround(255 * srgb_encode(clamped)));
  }
  return pixels;
}

void write_bytes(const std::vector<unsigned char>& encoded, const char* kind, const fs::path& temp,
                 const fs::path& target) {
  std::FILE* f = std::fopen(temp.c_str(), "wb");
  if (f == nullptr)
    fail_write(target, fmt::format("cannot write {} image: {}", kind, std::strerror(errno)));
  // Every byte written and on the disk (fsync) before the file may replace its target.
  const bool written = std::fwrite(encoded.data(), 1, encoded.size(), f) == encoded.size() &&
                       std::fflush(f) == 0 && ::fsync(fileno(f)) == 0;
  const int saved_errno = errno;
  if (std::fclose(f) != 0 || !written)
    fail_write(target, fmt::format("cannot write {} image: {}", kind,
                                   std::strerror(written ? errno : saved_errno)));
}

// Encoding to memory lets every write error be checked, which stbi_write_png does not do.
std::vector<unsigned char> png_bytes(const Image& image) {
  const std::vector<unsigned char> pixels = display_bytes(image);
  std::vector<unsigned char> encoded;
  if (!stbi_write_png_to_func(append_bytes, &encoded, image.width, image.height, 3, pixels.data(),
                              3 * image.width))
    throw std::runtime_error("cannot encode PNG image");
  return encoded;
}

void write_jpeg(const Image& image, const fs::path& temp, const fs::path& target) {
  const std::vector<unsigned char> pixels = display_bytes(image);
  std::vector<unsigned char> encoded;
  if (!stbi_write_jpg_to_func(append_bytes, &encoded, image.width, image.height, 3, pixels.data(),
                              95))
    fail_write(target, "cannot encode JPEG image");
  write_bytes(encoded, "JPEG", temp, target);
}

// OpenEXR writing into memory, so that every byte of the file then goes through one checked
// write (OpenEXR reports a failed final flush only from a destructor, where it is lost).
class MemoryStream : public Imf::OStream {
 public:
  MemoryStream() : Imf::OStream("memory") {}
  void write(const char c[], int n) override {
    if (position_ + n > bytes_.size()) bytes_.resize(position_ + n);
    std::memcpy(bytes_.data() + position_, c, static_cast<std::size_t>(n));
    position_ += n;
  }
  std::uint64_t tellp() override { return position_; }
  void seekp(std::uint64_t pos) override { position_ = pos; }
  const std::vector<unsigned char>& bytes() const { return bytes_; }

 private:
  std::vector<unsigned char> bytes_;
  std::uint64_t position_ = 0;
};

void write_exr(const Image& image, const fs::path& temp, const fs::path& target) {
  MemoryStream stream;
  try {
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    const char* names[] = {"R", "G", "B"};
    for (const char* name : names) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    for (const NamedChannel& c : image.channels)
      header.channels().insert(c.name, Imf::Channel(Imf::FLOAT));
    // OpenEXR only reads through these pointers when writing.
    char* base = reinterpret_cast<char*>(const_cast<float*>(image.rgb.data()));
    const std::size_t x_stride = 3 * sizeof(float), y_stride = x_stride * image.width;
    Imf::FrameBuffer frame;
    for (int c = 0; c < 3; ++c)
      frame.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), x_stride, y_stride));
    for (const NamedChannel& c : image.channels) {
      if (c.values.size() != static_cast<std::size_t>(image.width) * image.height)
        throw std::runtime_error("channel " + c.name + " has the wrong size");
      frame.insert(c.name, Imf::Slice(Imf::FLOAT,
                                      reinterpret_cast<char*>(const_cast<float*>(c.values.data())),
                                      sizeof(float), sizeof(float) * image.width));
    }
    Imf::OutputFile out(stream, header);
    out.setFrameBuffer(frame);
    out.writePixels(image.height);
  } catch (const std::exception& e) {
    fail_write(target, fmt::format("cannot write OpenEXR image ({})", e.what()));
  }
  write_bytes(stream.bytes(), "OpenEXR", temp, target);
}

// A short name beside the target (a long target name must not push it past the limit).
fs::path temporary_name(const fs::path& target) {
  static std::atomic<unsigned> counter{0};
  return target.parent_path() / fmt::format(".lightcone-{}-{}.tmp", ::getpid(), counter++);
}

// Where writing `path` must go: a symbolic link's target (the link is kept), else the path.
fs::path write_target(const fs::path& path) {
  std::error_code ec;
  if (fs::is_symlink(path, ec)) {
    const fs::path target = fs::weakly_canonical(path, ec);
    if (!ec) return target;
  }
  return path;
}

}  // namespace

std::shared_ptr<Image> load_image_file(const std::filesystem::path& file) {
  const std::vector<unsigned char> bytes = read_bytes(file);
  if (is_exr(bytes)) return load_exr(file);
  // Only the documented formats reach a decoder: PNG and JPEG by their signatures.
  static constexpr unsigned char kPng[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  static constexpr unsigned char kJpeg[] = {0xff, 0xd8, 0xff};
  const auto starts_with = [&](const auto& signature) {
    return bytes.size() >= sizeof signature &&
           std::equal(std::begin(signature), std::end(signature), bytes.begin());
  };
  if (!starts_with(kPng) && !starts_with(kJpeg)) fail(file, "not a PNG, JPEG or OpenEXR image");
  return load_stb(file, bytes);
}

std::optional<ImageFormat> image_format_of(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".png") return ImageFormat::kPng;
  if (ext == ".jpg" || ext == ".jpeg") return ImageFormat::kJpeg;
  if (ext == ".exr") return ImageFormat::kExr;
  return std::nullopt;
}

std::vector<unsigned char> encode_png(const Image& display) {
  return png_bytes(display);
}

void write_images(const Image& linear, const std::optional<std::filesystem::path>& png,
                  const std::optional<std::filesystem::path>& exr) {
  write_images(linear, linear, png, exr);
}

void write_images(const Image& display, const Image& linear,
                  const std::optional<std::filesystem::path>& png,
                  const std::optional<std::filesystem::path>& exr) {
  std::vector<ImageOutput> outputs;
  if (png) outputs.push_back({*png, ImageFormat::kPng});
  if (exr) outputs.push_back({*exr, ImageFormat::kExr});
  write_images(display, linear, outputs);
}

void write_images(const Image& display, const Image& linear,
                  const std::vector<ImageOutput>& outputs) {
  for (const Image* image : {&display, &linear})
    if (image->width <= 0 || image->height <= 0 || image->width > INT_MAX / 3 ||
        image->rgb.size() != 3 * static_cast<std::size_t>(image->width) * image->height)
      throw std::runtime_error(fmt::format("cannot write a {}x{} image holding {} values",
                                           image->width, image->height, image->rgb.size()));
  struct Pending {
    fs::path target, temp;
    bool renamed = false;
  };
  std::vector<Pending> pending;
  for (const ImageOutput& o : outputs) {
    const fs::path target = write_target(o.path);
    pending.push_back({target, temporary_name(target)});
  }
  try {
    for (std::size_t i = 0; i < outputs.size(); ++i) {
      const fs::path& target = pending[i].target;
      switch (outputs[i].format) {
        case ImageFormat::kPng: {
          std::vector<unsigned char> encoded;
          try {
            encoded = png_bytes(display);
          } catch (const std::runtime_error&) {
            fail_write(target, "cannot encode PNG image");
          }
          write_bytes(encoded, "PNG", pending[i].temp, target);
          break;
        }
        case ImageFormat::kJpeg:
          write_jpeg(display, pending[i].temp, target);
          break;
        case ImageFormat::kExr:
          write_exr(linear, pending[i].temp, target);
          break;
      }
    }
    for (Pending& p : pending) {
      std::error_code ec;
      fs::rename(p.temp, p.target, ec);
      if (ec)
        fail_write(p.target, fmt::format("cannot move the image into place: {}", ec.message()));
      p.renamed = true;
    }
  } catch (...) {
    for (const Pending& p : pending) {
      std::error_code ec;
      if (!p.renamed) fs::remove(p.temp, ec);
    }
    throw;
  }
}

}  // namespace lightcone
