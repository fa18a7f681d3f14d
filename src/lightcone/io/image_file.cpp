// Images: PNG read through libspng (written by png_encode.cpp), JPEG through libjpeg-turbo and
// EXR through OpenEXR, each both read and written; only those three formats, recognised by their
// signatures, reach a decoder.
#include "lightcone/io/image_file.hpp"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <fcntl.h>
#include <fmt/format.h>
#include <spng.h>
#include <turbojpeg.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "lightcone/io/input_error.hpp"
#include "lightcone/io/input_file.hpp"
#include "lightcone/portable.hpp"

namespace lightcone {

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
    if (const auto* exposure =
            in.header().findTypedAttribute<Imf::DoubleAttribute>(kExrExposureAttribute))
      image->exposure = exposure->value();
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

struct SpngFree {
  void operator()(spng_ctx* ctx) const { spng_ctx_free(ctx); }
};
using SpngContext = std::unique_ptr<spng_ctx, SpngFree>;

// Limits on ancillary chunks: text, ICC profiles and the like are not used here, and a file may
// declare them at any size.
constexpr std::size_t kMaxPngChunkBytes = 1 << 24;
constexpr std::size_t kMaxPngChunkCache = 1 << 26;

// PNG through libspng, row by row, so that memory follows the rows actually decoded rather than
// the size the header declares. Values are sRGB-encoded (8 or 16 bits); alpha is ignored.
std::shared_ptr<Image> load_png(const fs::path& file, const std::vector<unsigned char>& bytes) {
  const SpngContext ctx(spng_ctx_new(0));
  if (!ctx) throw std::bad_alloc();
  const auto check = [&](int error) {
    if (error != 0) fail(file, fmt::format("not a readable PNG image ({})", spng_strerror(error)));
  };
  check(spng_set_chunk_limits(ctx.get(), kMaxPngChunkBytes, kMaxPngChunkCache));
  check(spng_set_png_buffer(ctx.get(), bytes.data(), bytes.size()));
  spng_ihdr header{};
  check(spng_get_ihdr(ctx.get(), &header));
  check_image_size(file, header.width, header.height);
  auto image = std::make_shared<Image>();
  image->source = file.string();
  image->width = static_cast<int>(header.width);
  image->height = static_cast<int>(header.height);
  const bool sixteen_bit = header.bit_depth == 16;
  const int format = sixteen_bit ? SPNG_FMT_RGBA16 : SPNG_FMT_RGB8;
  check(spng_decode_image(ctx.get(), nullptr, 0, format, SPNG_DECODE_PROGRESSIVE));
  std::size_t row_bytes = 0;
  check(spng_decoded_image_size(ctx.get(), format, &row_bytes));
  row_bytes /= header.height;
  std::vector<unsigned char> row(row_bytes);
  const std::size_t width = header.width;
  // An interlaced image arrives in Adam7's seven passes, each giving every dx-th pixel from x0
  // of some rows; the rows of a plain image arrive in order, and memory grows with them.
  static constexpr int kAdam7FirstColumn[7] = {0, 4, 0, 2, 0, 1, 0};
  static constexpr int kAdam7ColumnStep[7] = {8, 8, 4, 4, 2, 2, 1};
  const bool interlaced = header.interlace_method != 0;
  std::vector<float> rgb;
  if (interlaced) rgb.resize(3 * width * header.height);
  const auto& decoded8 = srgb_8bit_decoded();
  bool finished = false;
  while (!finished) {
    spng_row_info info{};
    check(spng_get_row_info(ctx.get(), &info));
    const int error = spng_decode_row(ctx.get(), row.data(), row.size());
    if (error != SPNG_EOI) check(error);
    finished = error == SPNG_EOI;
    const std::size_t first = interlaced ? kAdam7FirstColumn[info.pass] : 0;
    const std::size_t step = interlaced ? kAdam7ColumnStep[info.pass] : 1;
    if (!interlaced) rgb.resize(rgb.size() + 3 * width);
    float* out = rgb.data() + 3 * width * info.row_num;
    for (std::size_t x = first; x < width; x += step)
      for (int c = 0; c < 3; ++c) {
        if (sixteen_bit) {
          std::uint16_t v;
          std::memcpy(&v, row.data() + 2 * (4 * x + c), 2);
          out[3 * x + c] = static_cast<float>(srgb_decode(v / 65535.0));
        } else {
          out[3 * x + c] = decoded8[row[3 * x + c]];
        }
      }
  }
  image->rgb = std::move(rgb);
  return image;
}

struct TurboJpegFree {
  void operator()(void* handle) const { tjDestroy(handle); }
};
using TurboJpegHandle = std::unique_ptr<void, TurboJpegFree>;

// JPEG through libjpeg-turbo's TurboJPEG interface, as 8-bit sRGB RGB.
std::shared_ptr<Image> load_jpeg(const fs::path& file, const std::vector<unsigned char>& bytes) {
  const TurboJpegHandle handle(tjInitDecompress());
  if (!handle) throw std::bad_alloc();
  if (bytes.size() > ULONG_MAX) fail(file, "image file too large");
  const auto reason = [&] { return std::string(tjGetErrorStr2(handle.get())); };
  int width = 0, height = 0, subsampling = 0, colourspace = 0;
  if (tjDecompressHeader3(handle.get(), bytes.data(), static_cast<unsigned long>(bytes.size()),
                          &width, &height, &subsampling, &colourspace) != 0)
    fail(file, fmt::format("not a readable JPEG image ({})", reason()));
  check_image_size(file, width, height);
  std::vector<unsigned char> pixels(3 * static_cast<std::size_t>(width) * height);
  // A progressive file may hold any number of scans: libjpeg-turbo's limit stops a file that
  // would take minutes. A warning (a truncated or corrupt file) is an error too.
  if (tjDecompress2(handle.get(), bytes.data(), static_cast<unsigned long>(bytes.size()),
                    pixels.data(), width, 3 * width, height, TJPF_RGB,
                    TJFLAG_ACCURATEDCT | TJFLAG_LIMITSCANS | TJFLAG_STOPONWARNING) != 0)
    fail(file, fmt::format("not a readable JPEG image ({})", reason()));
  auto image = std::make_shared<Image>();
  image->source = file.string();
  image->width = width;
  image->height = height;
  image->rgb.resize(pixels.size());
  const auto& decoded = srgb_8bit_decoded();
  std::transform(pixels.begin(), pixels.end(), image->rgb.begin(),
                 [&](unsigned char v) { return decoded[v]; });
  return image;
}

[[noreturn]] void fail_write(const fs::path& target, std::string_view what) {
  throw std::runtime_error(fmt::format("{}: {}", target.string(), what));
}

}  // namespace

namespace {

// The 8-bit code of a display value: round(255 srgb_encode(clamp(v, 0, 1))), NaN as 0.
unsigned char encoded_8bit(float v) {
  const double clamped = std::isnan(v) ? 0.0 : std::clamp<double>(v, 0.0, 1.0);
  return static_cast<unsigned char>(std::lround(255 * srgb_encode(clamped)));
}

// For each code k = 1..255, the smallest float in [0, 1] whose code is at least k, found by
// bisection over the ordered bit patterns of non-negative floats with encoded_8bit itself: the
// code of any value is then the number of thresholds at or below it, exactly encoded_8bit's
// (which is monotonic), without a pow per value. A 256th threshold, infinity, ends the list.
const std::array<float, 256>& code_thresholds() {
  static const std::array<float, 256> thresholds = [] {
    std::array<float, 256> t{};
    t[255] = std::numeric_limits<float>::infinity();
    const auto bits = [](float f) {
      std::uint32_t b;
      std::memcpy(&b, &f, sizeof b);
      return b;
    };
    const auto value = [](std::uint32_t b) {
      float f;
      std::memcpy(&f, &b, sizeof f);
      return f;
    };
    for (int k = 1; k <= 255; ++k) {
      std::uint32_t lo = bits(0.0f), hi = bits(1.0f);  // code(lo) < k <= code(hi)
      while (hi - lo > 1) {
        const std::uint32_t mid = lo + (hi - lo) / 2;
        (encoded_8bit(value(mid)) >= k ? hi : lo) = mid;
      }
      t[static_cast<std::size_t>(k - 1)] = value(hi);
    }
    return t;
  }();
  return thresholds;
}

// The code at the start of each run of 2^16 float bit patterns in [0, 1], from which the code
// of any value in the run is at most one step up the thresholds.
const std::array<unsigned char, 0x3F81>& run_codes() {
  static const std::array<unsigned char, 0x3F81> codes = [] {
    const std::array<float, 256>& thresholds = code_thresholds();
    std::array<unsigned char, 0x3F81> c{};
    for (std::uint32_t run = 0; run < c.size(); ++run) {
      float first;
      const std::uint32_t bits = run << 16;
      std::memcpy(&first, &bits, sizeof first);
      c[run] = static_cast<unsigned char>(
          std::upper_bound(thresholds.begin(), thresholds.end(), first) - thresholds.begin());
    }
    return c;
  }();
  return codes;
}

}  // namespace

std::vector<unsigned char> display_rgb8(const Image& image) {
  std::vector<unsigned char> pixels(image.rgb.size());
  display_rgb8(image, pixels.data());
  return pixels;
}

void display_rgb8(const Image& image, unsigned char* pixels) {
  parallel_for_pieces(std::size_t{0}, image.rgb.size(), std::size_t{1} << 16,
                      [&](std::size_t begin, std::size_t end) {
                        display_rgb8_values(&image.rgb[begin], end - begin, &pixels[begin]);
                      });
}

void display_rgb8_values(const float* values, std::size_t count, unsigned char* codes) {
  const std::array<float, 256>& thresholds = code_thresholds();
  const std::array<unsigned char, 0x3F81>& runs = run_codes();
  for (std::size_t i = 0; i < count; ++i) {
    const float v = std::min(values[i] > 0 ? values[i] : 0.0f, 1.0f);
    std::uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    // A run of 2^16 bit patterns spans less than one code (two thirds of one at most, just
    // above 0.5), so one step up the thresholds suffices (tested at every code boundary);
    // without a branch, as the step is not predictable.
    unsigned code = runs[bits >> 16];
    code += v >= thresholds[code];
    codes[i] = static_cast<unsigned char>(code);
  }
}

namespace {

void write_bytes(const std::vector<unsigned char>& encoded, const char* kind, const fs::path& temp,
                 const fs::path& target) {
  const auto failed = [&](int error) {
    fail_write(target, fmt::format("cannot write {} image: {}", kind, std::strerror(error)));
  };
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) failed(errno);
  // Every byte written and on the disk (fsync) before the file may replace its target.
  std::size_t done = 0;
  int error = 0;
  while (done < encoded.size()) {
    const ssize_t n = ::write(fd, encoded.data() + done, encoded.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      error = n < 0 ? errno : EIO;
      break;
    }
    done += static_cast<std::size_t>(n);
  }
  if (error == 0 && ::fsync(fd) != 0) error = errno;
  if (::close(fd) != 0 && error == 0) error = errno;
  if (error != 0) failed(error);
}

void write_jpeg(const Image& image, const fs::path& temp, const fs::path& target) {
  const std::vector<unsigned char> pixels = display_rgb8(image);
  const TurboJpegHandle handle(tjInitCompress());
  if (!handle) throw std::bad_alloc();
  unsigned char* buffer = nullptr;
  unsigned long size = 0;
  const int status =
      tjCompress2(handle.get(), pixels.data(), image.width, 3 * image.width, image.height, TJPF_RGB,
                  &buffer, &size, TJSAMP_444, 95, TJFLAG_ACCURATEDCT);
  const std::unique_ptr<unsigned char, decltype(&tjFree)> owned(buffer, &tjFree);
  if (status != 0)
    fail_write(target, fmt::format("cannot encode JPEG image ({})", tjGetErrorStr2(handle.get())));
  write_bytes({buffer, buffer + size}, "JPEG", temp, target);
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
    // Without it, a reader cannot tell a scaled picture from the radiance itself.
    if (image.exposure) header.insert(kExrExposureAttribute, Imf::DoubleAttribute(*image.exposure));
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
  return starts_with(kPng) ? load_png(file, bytes) : load_jpeg(file, bytes);
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
            encoded = encode_png(display);
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
