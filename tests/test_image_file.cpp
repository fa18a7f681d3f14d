// Image files: the sRGB curves, PNG and EXR round trips, all-or-nothing writing and the error
// messages for unreadable inputs.
#include <gtest/gtest.h>
#include <spng.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include "lightcone/io/image_file.hpp"
#include "lightcone/io/input_error.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;

class ImageFileTest : public test::TempDirTest {
 protected:
  std::vector<std::string> files() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_))
      names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
};

Image make_image(int width, int height, std::vector<float> rgb) {
  Image image;
  image.width = width;
  image.height = height;
  image.rgb = std::move(rgb);
  return image;
}

std::string load_error(const fs::path& path) {
  try {
    load_image_file(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Srgb, KnownValues) {
  EXPECT_EQ(srgb_encode(0), 0);
  EXPECT_NEAR(srgb_encode(1), 1, 1e-15);
  EXPECT_NEAR(srgb_decode(1), 1, 1e-15);
  EXPECT_NEAR(srgb_encode(0.0031308), 0.04045, 1e-6);
  EXPECT_NEAR(srgb_decode(0.04045), 0.0031308, 1e-6);
  EXPECT_NEAR(srgb_encode(0.001), 0.01292, 1e-15);  // the linear segment
  EXPECT_NEAR(srgb_encode(0.5), 0.7353569830524495, 1e-12);
  EXPECT_NEAR(srgb_decode(0.5), 0.21404114048223255, 1e-12);
  for (int i = 0; i <= 1000; ++i) {
    const double x = i / 1000.0;
    EXPECT_NEAR(srgb_decode(srgb_encode(x)), x, 1e-12) << x;
    EXPECT_NEAR(srgb_encode(srgb_decode(x)), x, 1e-12) << x;
  }
}

// display_rgb8 is round(255 srgb_encode(clamp(v, 0, 1))) exactly: at every code boundary (each
// side of it, to the float), at a million random values, and at the odd ones.
TEST(Srgb, EightBitCodesAreTheRoundedEncodingExactly) {
  const auto expected = [](float v) {
    const double clamped = std::isnan(v) ? 0.0 : std::min(1.0, std::max(0.0, double(v)));
    return static_cast<unsigned char>(std::lround(255 * srgb_encode(clamped)));
  };
  std::vector<float> values = {0.0f,
                               -0.0f,
                               -1.0f,
                               1.0f,
                               2.0f,
                               std::numeric_limits<float>::denorm_min(),
                               std::numeric_limits<float>::infinity(),
                               -std::numeric_limits<float>::infinity(),
                               std::numeric_limits<float>::quiet_NaN()};
  for (int k = 0; k < 256; ++k) {
    // Near the value whose encoding is (k + 1/2) / 255: where the code changes.
    const float edge = static_cast<float>(srgb_decode((k + 0.5) / 255));
    float below = edge, above = edge;
    for (int step = 0; step < 4; ++step) {
      values.insert(values.end(), {below, above});
      below = std::nextafter(below, 0.0f);
      above = std::nextafter(above, 2.0f);
    }
  }
  std::uint32_t state = 12345;
  for (int i = 0; i < 1000000; ++i) {
    state = state * 1664525u + 1013904223u;
    values.push_back(static_cast<float>(state) / 4294967296.0f * 1.1f - 0.05f);
  }
  Image image;
  image.width = static_cast<int>(values.size());
  image.height = 1;
  image.rgb.resize(3 * values.size());
  for (std::size_t i = 0; i < values.size(); ++i)
    image.rgb[3 * i] = image.rgb[3 * i + 1] = image.rgb[3 * i + 2] = values[i];
  const std::vector<unsigned char> codes = display_rgb8(image);
  for (std::size_t i = 0; i < values.size(); ++i)
    ASSERT_EQ(codes[3 * i], expected(values[i])) << values[i];
}

// The PNG says its codes are sRGB's (display_rgb8's), and gives the gamma and primaries that go
// with it for decoders that do not read the sRGB chunk: libspng reads them back.
TEST_F(ImageFileTest, PngIsTaggedAsSrgb) {
  const std::vector<unsigned char> png = encode_png(make_image(4, 3, std::vector<float>(36, 0.5f)));
  spng_ctx* ctx = spng_ctx_new(0);
  ASSERT_NE(ctx, nullptr);
  ASSERT_EQ(spng_set_png_buffer(ctx, png.data(), png.size()), 0);
  std::uint8_t intent = 99;
  EXPECT_EQ(spng_get_srgb(ctx, &intent), 0);
  EXPECT_EQ(intent, 0);  // perceptual
  std::uint32_t gamma = 0;
  EXPECT_EQ(spng_get_gama_int(ctx, &gamma), 0);
  EXPECT_EQ(gamma, 45455u);
  spng_chrm_int primaries{};
  EXPECT_EQ(spng_get_chrm_int(ctx, &primaries), 0);
  EXPECT_EQ(primaries.white_point_x, 31270u);
  EXPECT_EQ(primaries.red_x, 64000u);
  EXPECT_EQ(primaries.green_y, 60000u);
  EXPECT_EQ(primaries.blue_y, 6000u);
  spng_ctx_free(ctx);
}

// The parallel encoder's file, read back by libspng, holds exactly display_rgb8's codes, and its
// bytes do not depend on the number of threads: pictures of one strip, of many, with a strip
// of a single row, and of incompressible noise whose stream needs several IDAT chunks.
TEST_F(ImageFileTest, PngEncodedInStripsReadsBackExactlyOnAnyNumberOfThreads) {
  std::uint32_t state = 99;
  const auto noise = [&state] {
    state = state * 1664525u + 1013904223u;
    return static_cast<float>(state >> 8) / 16777216.0f;
  };
  for (const auto& [width, height, smooth] :
       {std::tuple{3, 2, true}, std::tuple{640, 360, true}, std::tuple{50000, 3, true},
        std::tuple{1, 700, true}, std::tuple{800, 700, false}}) {
    std::vector<float> rgb(3 * static_cast<std::size_t>(width) * height);
    for (std::size_t i = 0; i < rgb.size(); ++i)
      rgb[i] = smooth ? 0.5f + 0.5f * std::sin(0.001f * static_cast<float>(i % 9973)) : noise();
    const Image image = make_image(width, height, rgb);
    std::vector<unsigned char> one;
    {
      const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
      one = encode_png(image);
    }
    EXPECT_EQ(encode_png(image), one) << width << "x" << height;
    const fs::path png = dir_ / "strips.png";
    write_images(image, png, std::nullopt);
    const auto loaded = load_image_file(png);
    ASSERT_EQ(loaded->width, width);
    ASSERT_EQ(loaded->height, height);
    const std::vector<unsigned char> codes = display_rgb8(image);
    const std::vector<unsigned char> read = display_rgb8(*loaded);
    ASSERT_EQ(read.size(), codes.size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < codes.size(); ++i) differing += read[i] != codes[i];
    EXPECT_EQ(differing, 0u) << width << "x" << height;
    fs::remove(png);
  }
}

// An image with no pixels (or values that do not fill it) is refused, not written as a broken
// file.
TEST(PngEncode, RefusesAnEmptyImage) {
  EXPECT_THROW(encode_png(make_image(0, 0, {})), std::runtime_error);
  EXPECT_THROW(encode_png(make_image(2, 0, {})), std::runtime_error);
  Image short_of_values = make_image(2, 2, std::vector<float>(12, 0.5f));
  short_of_values.rgb.pop_back();
  EXPECT_THROW(encode_png(short_of_values), std::runtime_error);
}

TEST_F(ImageFileTest, PngRoundTrip) {
  // Exact 8-bit levels come back exactly; other values within one level after encoding.
  std::vector<float> rgb;
  for (int k : {0, 1, 10, 50, 128, 200, 254, 255, 7, 99, 180, 33})
    rgb.push_back(static_cast<float>(srgb_decode(k / 255.0)));
  for (float v : {0.3f, 0.0001f, 0.77f, 0.5f, 0.001f, 0.9999f}) rgb.push_back(v);
  const Image image = make_image(3, 2, rgb);
  const fs::path png = dir_ / "out.png";
  write_images(image, png, std::nullopt);
  EXPECT_EQ(files(), std::vector<std::string>{"out.png"});

  const auto loaded = load_image_file(png);
  ASSERT_EQ(loaded->width, 3);
  ASSERT_EQ(loaded->height, 2);
  ASSERT_EQ(loaded->rgb.size(), rgb.size());
  EXPECT_EQ(loaded->source, png.string());
  for (std::size_t i = 0; i < 12; ++i) EXPECT_NEAR(loaded->rgb[i], rgb[i], 1e-6) << i;
  for (std::size_t i = 12; i < rgb.size(); ++i)
    EXPECT_NEAR(srgb_encode(loaded->rgb[i]), srgb_encode(rgb[i]), 0.5 / 255 + 1e-6) << i;
  // Row-major from the top left: pixel (1, 1) is values 12..14.
  EXPECT_NEAR(loaded->texel(1, 1).g, rgb[13], 1.0 / 255);
}

TEST_F(ImageFileTest, PngClampsAndTreatsNanAsZero) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const Image image = make_image(2, 1, {nan, -1, 5, inf, -inf, 1});
  const fs::path png = dir_ / "clamp.png";
  write_images(image, png, std::nullopt);
  const auto loaded = load_image_file(png);
  EXPECT_EQ(loaded->rgb, (std::vector<float>{0, 0, 1, 1, 0, 1}));
}

TEST_F(ImageFileTest, ExrRoundTripIsExact) {
  const std::vector<float> rgb = {0, 1e-7f, 123.456f, -2, 0.1f, 65504.5f, 1e20f, 0.3333333f, 7};
  const Image image = make_image(1, 3, rgb);
  const fs::path exr = dir_ / "out.exr";
  write_images(image, std::nullopt, exr);
  const auto loaded = load_image_file(exr);
  ASSERT_EQ(loaded->width, 1);
  ASSERT_EQ(loaded->height, 3);
  EXPECT_EQ(loaded->rgb, rgb);
}

// The EV an EXR's pixels were scaled by goes into its header, as the documented attribute (a
// double, so that any OpenEXR reader finds it), and back into Image::exposure; the pixels are
// written as they are.
TEST_F(ImageFileTest, ExrKeepsTheExposureInItsHeader) {
  const std::vector<float> rgb = {0.5f, 2, 7};
  Image image = make_image(1, 1, rgb);
  const double ev = 5.576557517458461;
  image.exposure = ev;
  const fs::path exr = dir_ / "exposed.exr";
  write_images(image, std::nullopt, exr);
  std::string attribute = std::string(kExrExposureAttribute) + '\0' + "double" + '\0';
  const std::uint32_t size = sizeof(double);
  static_assert(std::endian::native == std::endian::little);  // EXR's byte order
  attribute.append(reinterpret_cast<const char*>(&size), sizeof size);
  attribute.append(reinterpret_cast<const char*>(&ev), sizeof ev);
  EXPECT_NE(test::bytes_of(exr).find(attribute), std::string::npos);
  const auto loaded = load_image_file(exr);
  ASSERT_TRUE(loaded->exposure.has_value());
  EXPECT_EQ(*loaded->exposure, ev);
  EXPECT_EQ(loaded->rgb, rgb);
}

// An image of unknown exposure is written without the attribute, and an image file without it
// reads as having none, not as exposure 0.
TEST_F(ImageFileTest, WithoutTheAttributeTheExposureIsUnknown) {
  const Image image = make_image(1, 1, {0.5f, 0.5f, 0.5f});
  write_images(image, dir_ / "plain.png", dir_ / "plain.exr");
  EXPECT_EQ(test::bytes_of(dir_ / "plain.exr").find(kExrExposureAttribute), std::string::npos);
  EXPECT_FALSE(load_image_file(dir_ / "plain.exr")->exposure.has_value());
  EXPECT_FALSE(load_image_file(dir_ / "plain.png")->exposure.has_value());
}

TEST_F(ImageFileTest, WritesBothFilesAndNoTemporaries) {
  const Image image = make_image(2, 2, std::vector<float>(12, 0.25f));
  write_images(image, dir_ / "a.png", dir_ / "a.exr");
  EXPECT_EQ(files(), (std::vector<std::string>{"a.exr", "a.png"}));
}

TEST_F(ImageFileTest, FailureInMissingDirectoryLeavesNothing) {
  const Image image = make_image(1, 1, {0.5f, 0.5f, 0.5f});
  const fs::path png = dir_ / "missing" / "out.png";
  try {
    write_images(image, png, std::nullopt);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(png.string()), std::string::npos) << e.what();
  }
  EXPECT_TRUE(files().empty());
}

TEST_F(ImageFileTest, FailedExrLeavesNoPng) {
  const Image image = make_image(1, 1, {0.5f, 0.5f, 0.5f});
  const fs::path png = dir_ / "out.png", exr = dir_ / "missing" / "out.exr";
  try {
    write_images(image, png, exr);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(exr.string()), std::string::npos) << e.what();
  }
  EXPECT_TRUE(files().empty());
  EXPECT_FALSE(fs::exists(png));
}

TEST_F(ImageFileTest, RejectsInconsistentImage) {
  const Image image = make_image(2, 2, {0, 0, 0});
  EXPECT_THROW(write_images(image, dir_ / "x.png", std::nullopt), std::runtime_error);
  EXPECT_TRUE(files().empty());
}

// A PNG written by hand with an uncompressed ("stored") zlib stream, so that no encoder is
// needed: `samples` holds each pixel's samples (of `channels` per pixel, 8 or 16 bits), row-major;
// `palette` (RGB triples) makes it an indexed image; `interlaced` stores it in Adam7's passes.
struct HandPng {
  int width = 0, height = 0, bit_depth = 8, colour_type = 2, channels = 3;
  std::vector<std::uint16_t> samples;
  std::vector<std::uint8_t> palette;
  bool interlaced = false;
};

std::string encode_by_hand(const HandPng& png) {
  const auto be32 = [](std::uint32_t v) {
    return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
  };
  const auto crc32 = [](const std::string& bytes) {
    std::uint32_t c = 0xffffffff;
    for (unsigned char b : bytes) {
      c ^= b;
      for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320 & (0 - (c & 1)));
    }
    return ~c;
  };
  const auto chunk = [&](const std::string& type, const std::string& data) {
    return be32(std::uint32_t(data.size())) + type + data + be32(crc32(type + data));
  };
  struct Pass {
    int x0, y0, dx, dy;
  };
  const std::vector<Pass> passes =
      png.interlaced ? std::vector<Pass>{{0, 0, 8, 8}, {4, 0, 8, 8}, {0, 4, 4, 8}, {2, 0, 4, 4},
                                         {0, 2, 2, 4}, {1, 0, 2, 2}, {0, 1, 1, 2}}
                     : std::vector<Pass>{{0, 0, 1, 1}};
  std::string raw;  // each row of each pass: filter type 0, then big-endian samples
  for (const Pass& pass : passes) {
    if (pass.x0 >= png.width) continue;
    for (int y = pass.y0; y < png.height; y += pass.dy) {
      raw += '\0';
      for (int x = pass.x0; x < png.width; x += pass.dx)
        for (int c = 0; c < png.channels; ++c) {
          const std::uint16_t v = png.samples[(std::size_t(y) * png.width + x) * png.channels + c];
          if (png.bit_depth == 16) raw += char(v >> 8);
          raw += char(v & 0xff);
        }
    }
  }
  std::uint32_t a = 1, b = 0;
  for (unsigned char c : raw) a = (a + c) % 65521, b = (b + a) % 65521;
  const auto len = std::uint16_t(raw.size()), nlen = std::uint16_t(~len);
  const std::string zlib =
      std::string{char(0x78),     char(0x01),        char(0x01),     char(len & 0xff),
                  char(len >> 8), char(nlen & 0xff), char(nlen >> 8)} +
      raw + be32((b << 16) | a);
  const std::string ihdr =
      be32(png.width) + be32(png.height) +
      std::string{char(png.bit_depth), char(png.colour_type), 0, 0, char(png.interlaced ? 1 : 0)};
  const std::string plte(png.palette.begin(), png.palette.end());
  return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) +
         (plte.empty() ? "" : chunk("PLTE", plte)) + chunk("IDAT", zlib) + chunk("IEND", "");
}

// A 16-bit greyscale PNG.
std::string grey16_png(int width, int height, const std::vector<std::uint16_t>& values) {
  HandPng png;
  png.width = width;
  png.height = height;
  png.bit_depth = 16;
  png.colour_type = 0;
  png.channels = 1;
  png.samples = values;
  return encode_by_hand(png);
}

// The decoded value of every 8-bit sample, as the loader must give it.
float decoded8(int level) {
  return static_cast<float>(srgb_decode(level / 255.0));
}

TEST_F(ImageFileTest, PalettedInterlacedAnd16BitRgbaPngsDecodeExactly) {
  // 9 x 7 pixels: every Adam7 pass holds some of them.
  const int width = 9, height = 7;
  std::vector<std::uint8_t> palette;
  for (int k = 0; k < 16; ++k)
    palette.insert(palette.end(),
                   {std::uint8_t(16 * k), std::uint8_t(255 - 9 * k), std::uint8_t(k * k)});
  HandPng indexed{width, height, 8, 3, 1, {}, palette, false};
  HandPng rgba16{width, height, 16, 6, 4, {}, {}, false};
  std::vector<float> expected_indexed, expected_rgba16;
  for (int i = 0; i < width * height; ++i) {
    const int k = (i * 7) % 16;
    indexed.samples.push_back(std::uint16_t(k));
    for (int c = 0; c < 3; ++c) expected_indexed.push_back(decoded8(palette[3 * k + c]));
    const std::uint16_t rgba[4] = {std::uint16_t(1000 * i), std::uint16_t(65535 - 977 * i),
                                   std::uint16_t(i * i), std::uint16_t(i)};
    rgba16.samples.insert(rgba16.samples.end(), rgba, rgba + 4);
    for (int c = 0; c < 3; ++c)
      expected_rgba16.push_back(static_cast<float>(srgb_decode(rgba[c] / 65535.0)));
  }
  for (bool interlaced : {false, true}) {
    indexed.interlaced = rgba16.interlaced = interlaced;
    const std::string suffix = interlaced ? "-adam7.png" : ".png";
    const auto a = load_image_file(write("indexed" + suffix, encode_by_hand(indexed)));
    EXPECT_EQ(a->rgb, expected_indexed) << suffix;
    const auto b = load_image_file(write("rgba16" + suffix, encode_by_hand(rgba16)));
    EXPECT_EQ(b->rgb, expected_rgba16) << suffix;
    EXPECT_EQ(b->width, width);
    EXPECT_EQ(b->height, height);
  }
}

TEST_F(ImageFileTest, TruncatedPngAndJpegAreErrorsNamingTheFile) {
  HandPng png{9, 7, 8, 2, 3, std::vector<std::uint16_t>(9 * 7 * 3, 200), {}, false};
  const std::string whole = encode_by_hand(png);
  const auto cut = write("cut.png", whole.substr(0, whole.size() - 40));
  EXPECT_EQ(load_error(cut).rfind(cut.string() + ": not a readable PNG image (", 0), 0u)
      << load_error(cut);

  std::vector<float> rgb;
  for (int i = 0; i < 32 * 16; ++i) rgb.insert(rgb.end(), {0.2f, float(i % 32) / 32, 0.7f});
  const fs::path jpeg = dir_ / "whole.jpg";
  write_images(make_image(32, 16, rgb), make_image(32, 16, rgb), {{jpeg, ImageFormat::kJpeg}});
  std::ifstream in(jpeg, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), {});
  const auto cut_jpeg = write("cut.jpg", bytes.substr(0, bytes.size() / 2));
  EXPECT_EQ(load_error(cut_jpeg).rfind(cut_jpeg.string() + ": not a readable JPEG image (", 0), 0u)
      << load_error(cut_jpeg);
}

TEST_F(ImageFileTest, JpegRoundTripIsCloseInEveryChannel) {
  // Quality 95 without chroma subsampling: a smooth image comes back within a few levels.
  const int width = 40, height = 24;
  std::vector<float> rgb;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      rgb.insert(rgb.end(), {decoded8(40 + 4 * x), decoded8(200 - 6 * y), decoded8(128)});
  const fs::path jpeg = dir_ / "round.jpeg";
  write_images(make_image(width, height, rgb), make_image(width, height, rgb),
               {{jpeg, ImageFormat::kJpeg}});
  EXPECT_EQ(files(), std::vector<std::string>{"round.jpeg"});
  const auto loaded = load_image_file(jpeg);
  ASSERT_EQ(loaded->width, width);
  ASSERT_EQ(loaded->height, height);
  double worst = 0;
  for (std::size_t i = 0; i < rgb.size(); ++i)
    worst = std::max(worst, std::abs(255 * (srgb_encode(loaded->rgb[i]) - srgb_encode(rgb[i]))));
  EXPECT_LE(worst, 3.0);
  EXPECT_GT(worst, 0.0);  // it did go through the lossy codec
}

TEST_F(ImageFileTest, OnlyPngJpegAndExrAreDecoded) {
  // Formats that a general image library would read: only the documented ones reach a decoder.
  for (const auto& [name, bytes] :
       {std::pair{"grey.pgm", std::string("P5\n2 1\n255\n") + char(0) + char(128)},
        std::pair{"tiny.gif", std::string("GIF89a\x01\x00\x01\x00\x00\x00\x00", 13)},
        std::pair{"sky.hdr", std::string("#?RADIANCE\n")}}) {
    const auto path = write(name, bytes);
    EXPECT_EQ(load_error(path), path.string() + ": not a PNG, JPEG or OpenEXR image");
  }
}

TEST_F(ImageFileTest, ImagesDeclaringTooManyPixelsAreRefusedBeforeDecoding) {
  // A PNG header of 9000 x 9000 pixels (and no data): refused from the header alone.
  std::string png("\x89PNG\r\n\x1a\n", 8);
  const auto be32 = [](std::uint32_t v) {
    return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
  };
  png += be32(13) + "IHDR" + be32(9000) + be32(9000) + std::string("\x08\x02\0\0\0", 5) + be32(0);
  const auto path = write("huge.png", png);
  EXPECT_EQ(load_error(path).rfind(path.string() + ": 9000x9000 pixels: more than the limit", 0),
            0u)
      << load_error(path);
}

TEST_F(ImageFileTest, ExrDeclaringTooManyPixelsIsRefusedBeforeAllocating) {
  // A valid 4 x 2 OpenEXR file whose data window is then made 20000 x 20000.
  const fs::path small = dir_ / "small.exr";
  write_images(make_image(4, 2, std::vector<float>(24, 0.5f)), std::nullopt, small);
  std::ifstream in(small, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), {});
  const std::string attribute("dataWindow\0box2i\0", 17);
  const std::size_t at = bytes.find(attribute);
  ASSERT_NE(at, std::string::npos);
  const std::int32_t window[4] = {0, 0, 19999, 19999};
  bytes.replace(at + attribute.size() + 4, sizeof window,
                std::string(reinterpret_cast<const char*>(window), sizeof window));
  // Room for the table of line offsets the header now implies, so that OpenEXR reads the header
  // through and the size itself is what is refused.
  bytes += std::string(20000 * 8, '\0');
  const auto huge = write("huge.exr", bytes);
  EXPECT_EQ(load_error(huge).rfind(huge.string() + ": 20000x20000 pixels: more than the limit", 0),
            0u)
      << load_error(huge);
}

TEST_F(ImageFileTest, GreyImagesAreReplicated) {
  const auto grey16 = write("grey16.png", grey16_png(2, 1, {0x8000, 0xffff}));
  const auto image16 = load_image_file(grey16);
  ASSERT_EQ(image16->width, 2);
  ASSERT_EQ(image16->height, 1);
  const float mid16 = static_cast<float>(srgb_decode(0x8000 / 65535.0));
  EXPECT_EQ(image16->rgb, (std::vector<float>{mid16, mid16, mid16, 1, 1, 1}));
}

TEST_F(ImageFileTest, MissingOrGarbageFileNamesIt) {
  const fs::path missing = dir_ / "missing.png";
  EXPECT_EQ(load_error(missing),
            missing.string() + ": cannot read image: No such file or directory");
  const auto garbage = write("garbage.png", "this is not an image");
  const std::string error = load_error(garbage);
  EXPECT_EQ(error.rfind(garbage.string() + ": not a PNG, JPEG or OpenEXR image", 0), 0u) << error;
  const auto bad_exr = write("bad.exr", std::string("\x76\x2f\x31\x01garbage", 11));
  const std::string exr_error = load_error(bad_exr);
  EXPECT_EQ(exr_error.rfind(bad_exr.string() + ": cannot read OpenEXR image (", 0), 0u)
      << exr_error;
}

}  // namespace
}  // namespace lightcone
