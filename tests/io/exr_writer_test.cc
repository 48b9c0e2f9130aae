#include "io/exr_writer.h"

#include <Imath/half.h>
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <iterator>
#include <map>
#include <random>

#include "io/exr_pack.h"

namespace aperture {
namespace {

Image Gradient(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      img.at(x, y) = {x / float(w), y / float(h), 0.25f + 1e-3f * float(x + y), 1.0f};
  return img;
}

struct ReadBack {
  OIIO::ImageSpec spec;
  std::vector<float> pixels;
};

ReadBack ReadExr(const std::string& path, OIIO::Filesystem::IOProxy* proxy = nullptr) {
  OIIO::ImageSpec config;
  if (proxy != nullptr) {
    void* p = proxy;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &p);
  }
  auto in = OIIO::ImageInput::open(path, &config, proxy);
  EXPECT_TRUE(in) << OIIO::geterror();
  ReadBack r;
  if (!in) return r;
  r.spec = in->spec();
  r.pixels.resize(static_cast<size_t>(r.spec.width) * r.spec.height * r.spec.nchannels);
  EXPECT_TRUE(in->read_image(0, 0, 0, r.spec.nchannels, OIIO::TypeDesc::FLOAT, r.pixels.data()));
  return r;
}

class ExrWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("aperture_exr_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

// A region of a frame is written with its data window at its place inside the whole frame's
// display window, by both encoders; its rows are those of the region.
TEST_F(ExrWriterTest, ARegionLiesAtItsPlaceInTheFrame) {
  const Image img = Gradient(50, 37);  // 37 rows: chunks of 16 (zip) end mid-chunk
  for (ExrCompression c : {ExrCompression::kNone, ExrCompression::kZip, ExrCompression::kPiz,
                           ExrCompression::kDwaa, ExrCompression::kDwab, ExrCompression::kB44a}) {
    ExrOptions options;
    options.compression = c;
    // b44a compresses half channels only.
    options.pixel_type = CompressesHalfOnly(c) ? ExrPixelType::kHalf : ExrPixelType::kFloat;
    options.metadata.x = 30;
    options.metadata.y = 21;  // not a multiple of any chunk height
    options.metadata.frame_width = 100;
    options.metadata.frame_height = 80;
    const std::string path = (dir_ / (std::string(ExrCompressionName(c)) + ".exr")).string();
    ASSERT_TRUE(WriteExrFile(img, options, path).ok()) << ExrCompressionName(c);
    ReadBack r = ReadExr(path);
    EXPECT_EQ(r.spec.x, 30) << ExrCompressionName(c);
    EXPECT_EQ(r.spec.y, 21);
    EXPECT_EQ(r.spec.width, 50);
    EXPECT_EQ(r.spec.height, 37);
    EXPECT_EQ(r.spec.full_x, 0);
    EXPECT_EQ(r.spec.full_y, 0);
    EXPECT_EQ(r.spec.full_width, 100);
    EXPECT_EQ(r.spec.full_height, 80);
    ASSERT_EQ(r.pixels.size(), img.texels().size() * 4);
    float worst = 0;
    for (size_t i = 0; i < r.pixels.size(); ++i)
      worst = std::max(worst, std::abs(r.pixels[i] - (&img.texels()[i / 4].r)[i % 4]));
    EXPECT_LE(worst, c == ExrCompression::kDwaa || c == ExrCompression::kDwab ? 2e-2f
                     : CompressesHalfOnly(c)                                  ? 1e-2f
                                                                              : 0.0f)
        << ExrCompressionName(c);
  }
}

TEST_F(ExrWriterTest, EveryCompressionRoundTripsThroughOpenImageIO) {
  const Image img = Gradient(67, 41);
  for (ExrCompression c : {ExrCompression::kNone, ExrCompression::kRle, ExrCompression::kZips,
                           ExrCompression::kZip, ExrCompression::kPiz, ExrCompression::kDwaa,
                           ExrCompression::kDwab, ExrCompression::kB44, ExrCompression::kB44a}) {
    for (ExrPixelType type : {ExrPixelType::kHalf, ExrPixelType::kFloat}) {
      if (CompressesHalfOnly(c) && type == ExrPixelType::kFloat) continue;  // an error, below
      ExrOptions options;
      options.compression = c;
      options.pixel_type = type;
      options.metadata.scene_name = "gradient";
      options.metadata.camera = "0,1,0,0,-5,0 fov=60";
      options.metadata.mode = "raster";
      options.metadata.setup_ms = 2.5;
      options.metadata.raster_ms = 10;
      const std::string path = (dir_ / (std::string(ExrCompressionName(c)) + ".exr")).string();
      ASSERT_TRUE(WriteExrFile(img, options, path).ok());
      ReadBack r = ReadExr(path);
      ASSERT_EQ(r.spec.width, 67);
      ASSERT_EQ(r.spec.nchannels, 4);
      EXPECT_EQ(r.spec.format,
                type == ExrPixelType::kHalf ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
      EXPECT_EQ(r.spec.get_string_attribute("compression"), ExrCompressionName(c));
      EXPECT_EQ(r.spec.get_string_attribute("aperture:scene"), "gradient");
      EXPECT_EQ(r.spec.get_string_attribute("aperture:camera"), "0,1,0,0,-5,0 fov=60");
      EXPECT_EQ(r.spec.get_string_attribute("aperture:mode"), "raster");
      EXPECT_FLOAT_EQ(r.spec.get_float_attribute("aperture:setup_ms"), 2.5f);
      EXPECT_FLOAT_EQ(r.spec.get_float_attribute("aperture:raster_ms"), 10.0f);
      EXPECT_FLOAT_EQ(r.spec.get_float_attribute("aperture:render_ms"), 12.5f);
      EXPECT_EQ(r.spec.get_string_attribute("Software"), "Aperture " APERTURE_VERSION);
      // A whole frame: the data window is the display window.
      EXPECT_EQ(r.spec.x, 0);
      EXPECT_EQ(r.spec.y, 0);
      EXPECT_EQ(r.spec.full_width, 67);
      EXPECT_EQ(r.spec.full_height, 41);
      // Lossless codecs keep half precision (dwaa, dwab, b44 and b44a are lossy).
      const float tolerance = c == ExrCompression::kDwaa || c == ExrCompression::kDwab ? 2e-2f
                              : CompressesHalfOnly(c)                                  ? 1e-2f
                              : type == ExrPixelType::kHalf                            ? 1e-3f
                                                                                       : 0.0f;
      float worst = 0;
      for (size_t i = 0; i < r.pixels.size(); ++i) {
        const Rgba& t = img.texels()[i / 4];
        const float want = (&t.r)[i % 4];
        worst = std::max(worst, std::abs(r.pixels[i] - want));
      }
      EXPECT_LE(worst, tolerance) << ExrCompressionName(c);
    }
  }
}

// B44 and B44A: 4 x 4 blocks of half values in 14 bytes, and in 3 for a flat block in B44A (an
// opaque frame's alpha, a flat sky); lossy, each value within a fraction of its block's range
// (smooth content loses little; other tests' steeper gradients allow 1e-2). Float
// pixels they would leave uncompressed: an error naming both, never a silent half frame.
TEST_F(ExrWriterTest, B44FramesAreSmallerAndCloseToTheHalfFrame) {
  const Image img = Gradient(128, 64);  // opaque: alpha 1 everywhere
  ExrOptions options;
  options.compression = ExrCompression::kNone;
  auto none = EncodeExr(img, options);
  ASSERT_TRUE(none.ok()) << none.status();
  std::map<ExrCompression, size_t> sizes;
  for (ExrCompression c : {ExrCompression::kB44, ExrCompression::kB44a}) {
    options.compression = c;
    auto bytes = EncodeExr(img, options);
    ASSERT_TRUE(bytes.ok()) << bytes.status();
    sizes[c] = bytes->size();
    OIIO::Filesystem::IOMemReader reader(bytes->data(), bytes->size());
    const ReadBack r = ReadExr("frame.exr", &reader);
    EXPECT_EQ(r.spec.get_string_attribute("compression"), ExrCompressionName(c));
    ASSERT_EQ(r.pixels.size(), img.texels().size() * 4);
    float worst = 0;
    for (size_t i = 0; i < r.pixels.size(); ++i)
      worst = std::max(worst, std::abs(r.pixels[i] - (&img.texels()[i / 4].r)[i % 4]));
    EXPECT_GT(worst, 0.0f) << "lossy: some value differs";
    EXPECT_LE(worst, 2e-3f) << ExrCompressionName(c);
  }
  // RGBA half is 128 bytes a block; b44 stores 4 x 14, b44a 3 x 14 + 3 (the flat alpha).
  EXPECT_LT(sizes[ExrCompression::kB44], none->size() / 2);
  EXPECT_LT(sizes[ExrCompression::kB44a], sizes[ExrCompression::kB44] * 9 / 10);

  options.pixel_type = ExrPixelType::kFloat;
  for (ExrCompression c : {ExrCompression::kB44, ExrCompression::kB44a}) {
    options.compression = c;
    auto refused = EncodeExr(img, options);
    ASSERT_FALSE(refused.ok()) << ExrCompressionName(c);
    EXPECT_TRUE(absl::IsInvalidArgument(refused.status()));
    EXPECT_NE(refused.status().message().find(ExrCompressionName(c)), std::string::npos);
    EXPECT_NE(refused.status().message().find("half"), std::string::npos);
  }
}

// zip and zips go through libdeflate (io/exr_deflate): random float bits do not compress, so
// their chunks are stored raw, which readers must take as they are; a flat image compresses.
// Both read back bit for bit through OpenImageIO (OpenEXR's own zlib decoder).
TEST_F(ExrWriterTest, DeflatedAndIncompressibleChunksReadBackExactly) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> noise(-1000, 1000);
  Image random = Image::Uninitialized(53, 47);
  for (Rgba& t : random.texels()) t = {noise(rng), noise(rng), noise(rng), noise(rng)};
  Image smooth = Image::Uninitialized(53, 47);
  for (Rgba& t : smooth.texels()) t = {0.25f, 0.5f, 0.75f, 1};
  for (ExrCompression c : {ExrCompression::kZip, ExrCompression::kZips}) {
    for (const Image* img :
         {static_cast<const Image*>(&random), static_cast<const Image*>(&smooth)}) {
      ExrOptions options;
      options.compression = c;
      options.pixel_type = ExrPixelType::kFloat;
      const std::string path = (dir_ / "deflate.exr").string();
      ASSERT_TRUE(WriteExrFile(*img, options, path).ok());
      const uintmax_t raw = 53ull * 47 * 4 * sizeof(float);
      if (img == &smooth) {
        EXPECT_LT(std::filesystem::file_size(path), raw / 10);
      } else {
        EXPECT_GE(std::filesystem::file_size(path), raw);  // stored raw, chunk by chunk
      }
      ReadBack r = ReadExr(path);
      ASSERT_EQ(r.pixels.size(), 53u * 47 * 4);
      size_t differing = 0;
      for (size_t i = 0; i < r.pixels.size(); ++i)
        differing += r.pixels[i] != (&img->texels()[i / 4].r)[i % 4];
      EXPECT_EQ(differing, 0u) << ExrCompressionName(c);
    }
  }
}

// The writer converts to half itself; OpenImageIO's own float-to-half conversion, asked to write
// the same floats into a half file, must give the same values, special ones included.
TEST_F(ExrWriterTest, HalfPixelsEqualOpenImageIOsOwnConversion) {
  Image img = Gradient(37, 29);
  const float specials[] = {1.0f / 3, 65519.0f, 65520.0f, 7e4f,     -7e4f, 1e-6f, 6e-8f,
                            2.9e-8f,  -0.0f,    1e-30f,   INFINITY, NAN,   -NAN,  0.1f};
  for (size_t i = 0; i < std::size(specials); ++i)
    img.texels()[i * 3] = {specials[i], -1.5f, 2.0f, 0.5f};
  const std::string ours = (dir_ / "ours.exr").string(), theirs = (dir_ / "theirs.exr").string();
  ASSERT_TRUE(WriteExrFile(img, ExrOptions{}, ours).ok());
  {
    auto out = OIIO::ImageOutput::create(theirs);
    ASSERT_TRUE(out);
    OIIO::ImageSpec spec(37, 29, 4, OIIO::TypeDesc::HALF);
    ASSERT_TRUE(out->open(theirs, spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, img.texels().data()));
    ASSERT_TRUE(out->close());
  }
  const ReadBack a = ReadExr(ours), b = ReadExr(theirs);
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  ASSERT_EQ(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)), 0);
  EXPECT_TRUE(std::isinf(a.pixels[4 * 3 * 3]));  // 7e4 is beyond half's range
  EXPECT_TRUE(std::isnan(a.pixels[4 * 3 * 11]));
}

TEST_F(ExrWriterTest, InMemoryBytesEqualTheFile) {
  const Image img = Gradient(33, 20);
  ExrOptions options;
  auto bytes = EncodeExr(img, options);
  ASSERT_TRUE(bytes.ok()) << bytes.status();
  ASSERT_GT(bytes->size(), 100u);
  OIIO::Filesystem::IOMemReader reader(bytes->data(), bytes->size());
  ReadBack from_memory = ReadExr("frame.exr", &reader);
  const std::string path = (dir_ / "f.exr").string();
  ASSERT_TRUE(WriteExrFile(img, options, path).ok());
  ReadBack from_file = ReadExr(path);
  ASSERT_EQ(from_memory.pixels.size(), from_file.pixels.size());
  EXPECT_EQ(from_memory.pixels, from_file.pixels);
}

// Blocks of scanlines are compressed in parallel and written in order: the bytes must not depend
// on the thread count, and every line (a height that is no multiple of any codec's chunk) must
// come back exactly.
TEST_F(ExrWriterTest, ParallelEncodingGivesTheSerialBytes) {
  const Image img = Gradient(640, 333);
  for (ExrCompression c :
       {ExrCompression::kNone, ExrCompression::kRle, ExrCompression::kZips, ExrCompression::kZip,
        ExrCompression::kPiz, ExrCompression::kB44, ExrCompression::kB44a}) {
    ExrOptions options;
    options.compression = c;
    options.threads = 1;
    auto serial = EncodeExr(img, options);
    options.threads = 4;
    auto parallel = EncodeExr(img, options);
    ASSERT_TRUE(serial.ok() && parallel.ok()) << ExrCompressionName(c);
    EXPECT_EQ(*serial, *parallel) << ExrCompressionName(c);
    OIIO::Filesystem::IOMemReader reader(parallel->data(), parallel->size());
    const ReadBack r = ReadExr("frame.exr", &reader);
    ASSERT_EQ(r.spec.height, 333);
    float worst = 0;
    for (size_t i = 0; i < r.pixels.size(); ++i)
      worst = std::max(worst, std::abs(r.pixels[i] - (&img.texels()[i / 4].r)[i % 4]));
    EXPECT_LE(worst, CompressesHalfOnly(c) ? 1e-2f : 1e-3f) << ExrCompressionName(c);
  }
}

// zip_level reaches zlib: a higher level gives a smaller file of the same pixels.
TEST_F(ExrWriterTest, ZipLevelIsApplied) {
  Image img(256, 256);
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x)
      img.at(x, y) = {float((x * 7 + y * 3) % 17) / 17, float((x ^ y) & 31) / 31, 0.5f, 1.0f};
  ExrOptions fast, small;
  fast.zip_level = 1;
  small.zip_level = 9;
  auto a = EncodeExr(img, fast), b = EncodeExr(img, small);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_LT(b->size(), a->size());
}

TEST_F(ExrWriterTest, UnwritablePathIsAnError) {
  auto status = WriteExrFile(Gradient(4, 4), {}, (dir_ / "no/such/dir/x.exr").string());
  EXPECT_FALSE(status.ok());
}

// The encoder's chunk packing (io/exr_pack: F16C conversion and a transpose, when the processor
// has them) against an independent conversion: every value read back by OpenImageIO equals
// Imath::half of the frame's float (round to nearest even), bit for bit, or the float itself;
// over widths that leave every tail length of the eight-pixel groups, and values at the edges of
// half's range: subnormals, ties, the largest half, overflow to infinity, signed zeros.
Image Awkward(int w, int h, uint32_t seed) {
  const float specials[] = {
      0.0f,     -0.0f,   1.0f,           -1.0f,           65504.0f,  65519.99f,
      65520.0f, 1e6f,    -1e6f,          6.0e-8f,         5.96e-8f,  2.98e-8f,
      1e-5f,    6.1e-5f, 1.00048828125f, 1.000732421875f, 0.333333f, 1e-30f};
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> any(-4, 4);
  std::uniform_int_distribution<int> pick(0, 3 * static_cast<int>(std::size(specials)));
  Image img(w, h);
  for (Rgba& t : img.texels()) {
    float* v = &t.r;
    for (int c = 0; c < 4; ++c) {
      const int k = pick(rng);
      v[c] = k < static_cast<int>(std::size(specials)) ? specials[k] : any(rng);
    }
  }
  return img;
}

std::vector<uint8_t> ReadRaw(const std::string& bytes, OIIO::TypeDesc type, OIIO::ImageSpec* spec) {
  OIIO::Filesystem::IOMemReader reader(bytes.data(), bytes.size());
  OIIO::ImageSpec config;
  void* p = &reader;
  config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &p);
  auto in = OIIO::ImageInput::open("frame.exr", &config, &reader);
  EXPECT_TRUE(in) << OIIO::geterror();
  if (!in) return {};
  *spec = in->spec();
  std::vector<uint8_t> out(static_cast<size_t>(spec->width) * spec->height * spec->nchannels *
                           type.size());
  EXPECT_TRUE(in->read_image(0, 0, 0, spec->nchannels, type, out.data()));
  return out;
}

TEST(ExrPack, EveryValueIsImathsHalfOrTheFloat) {
  std::printf("packing: %s\n", FastRgbaPack() ? "F16C" : "OpenEXR core's own");
  for (int width : {1, 7, 8, 9, 15, 16, 17, 1283})
    for (ExrCompression compression : {ExrCompression::kNone, ExrCompression::kZip})
      for (ExrPixelType type : {ExrPixelType::kHalf, ExrPixelType::kFloat}) {
        const Image img = Awkward(width, 37, static_cast<uint32_t>(width));
        ExrOptions options;
        options.compression = compression;
        options.pixel_type = type;
        auto bytes = EncodeExr(img, options);
        ASSERT_TRUE(bytes.ok()) << bytes.status();
        OIIO::ImageSpec spec;
        const bool half = type == ExrPixelType::kHalf;
        const auto raw =
            ReadRaw(*bytes, half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT, &spec);
        ASSERT_EQ(spec.nchannels, 4);
        ASSERT_EQ(spec.width, width);
        // OpenImageIO returns the channels as R, G, B, A.
        size_t mismatches = 0;
        for (size_t i = 0; i < img.texels().size(); ++i)
          for (int c = 0; c < 4; ++c) {
            const float v = (&img.texels()[i].r)[c];
            const size_t at = 4 * i + c;
            if (half) {
              const uint16_t want = Imath::half(v).bits();
              uint16_t got;
              std::memcpy(&got, raw.data() + 2 * at, 2);
              mismatches += got != want;
            } else {
              mismatches += std::memcmp(raw.data() + 4 * at, &v, 4) != 0;
            }
          }
        EXPECT_EQ(mismatches, 0u) << "width " << width << " " << ExrCompressionName(compression)
                                  << (half ? " half" : " float");
      }
}

}  // namespace
}  // namespace aperture
