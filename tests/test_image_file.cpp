// Image files: the sRGB curves, PNG and EXR round trips, all-or-nothing writing and the error
// messages for unreadable inputs.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <string>
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

// A 16-bit greyscale PNG with an uncompressed ("stored") zlib stream, so no encoder is needed.
std::string grey16_png(int width, int height, const std::vector<std::uint16_t>& values) {
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
  std::string raw;  // each row: filter type 0, then big-endian samples
  for (int y = 0; y < height; ++y) {
    raw += '\0';
    for (int x = 0; x < width; ++x) {
      const std::uint16_t v = values[std::size_t(y) * width + x];
      raw += char(v >> 8);
      raw += char(v & 0xff);
    }
  }
  std::uint32_t a = 1, b = 0;
  for (unsigned char c : raw) a = (a + c) % 65521, b = (b + a) % 65521;
  const auto len = std::uint16_t(raw.size()), nlen = std::uint16_t(~len);
  const std::string zlib =
      std::string{char(0x78),     char(0x01),        char(0x01),     char(len & 0xff),
                  char(len >> 8), char(nlen & 0xff), char(nlen >> 8)} +
      raw + be32((b << 16) | a);
  const std::string ihdr = be32(width) + be32(height) + std::string{char(16), 0, 0, 0, 0};
  return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) + chunk("IDAT", zlib) +
         chunk("IEND", "");
}

TEST_F(ImageFileTest, OnlyPngJpegAndExrAreDecoded) {
  // stb_image would read these; only the documented formats reach a decoder.
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
