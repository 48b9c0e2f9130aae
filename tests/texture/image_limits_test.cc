// Raster textures beyond kMaxImageTexels are refused from their header, before any pixel is
// read or allocated, with a message naming the size; tables are refused before resampling.
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "io/exr_writer.h"
#include "texture/image_file.h"
#include "texture/prefiltered_table_builder.h"

namespace aperture {
namespace {

uint32_t Crc32(const uint8_t* data, size_t size) {
  uint32_t crc = 0xffffffffu;
  for (size_t i = 0; i < size; ++i) {
    crc ^= data[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void AppendChunk(std::vector<uint8_t>& png, const char* type, const std::vector<uint8_t>& data) {
  auto be32 = [&](uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) png.push_back(uint8_t(v >> shift));
  };
  be32(static_cast<uint32_t>(data.size()));
  const size_t start = png.size();
  png.insert(png.end(), type, type + 4);
  png.insert(png.end(), data.begin(), data.end());
  be32(Crc32(png.data() + start, png.size() - start));
}

// A PNG whose header says width x height (8-bit grey) and whose pixel data is a few bytes: a
// decompression bomb's shape, small on the wire.
std::vector<uint8_t> PngHeaderOnly(uint32_t width, uint32_t height) {
  std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a};
  std::vector<uint8_t> ihdr;
  for (uint32_t v : {width, height})
    for (int shift = 24; shift >= 0; shift -= 8) ihdr.push_back(uint8_t(v >> shift));
  ihdr.insert(ihdr.end(), {8, 0, 0, 0, 0});  // 8-bit, grey, deflate, no filter, no interlace
  AppendChunk(png, "IHDR", ihdr);
  AppendChunk(png, "IDAT", {0x78, 0x9c, 0x03, 0x00, 0x00, 0x00, 0x00, 0x01});
  AppendChunk(png, "IEND", {});
  return png;
}

TEST(ImageLimits, OversizedEncodedImageIsRefusedFromItsHeader) {
  for (auto [w, h] :
       {std::pair{60000u, 60000u}, std::pair{8193u, 8192u}, std::pair{65536u, 2048u}}) {
    const std::vector<uint8_t> png = PngHeaderOnly(w, h);
    auto image = DecodeImage(png);
    ASSERT_FALSE(image.ok()) << w << "x" << h;
    EXPECT_EQ(image.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_NE(
        std::string(image.status().message()).find(std::to_string(w) + "x" + std::to_string(h)),
        std::string::npos)
        << image.status();
    EXPECT_NE(std::string(image.status().message()).find("above the limit"), std::string::npos);
  }
}

TEST(ImageLimits, TableOfAnImageBeyondTheLimitIsRefusedBeforeResampling) {
  // 1 x 16384 would be resampled to 16384 x 16384 (4 GiB as floats) before the old check.
  auto block = BuildPrefilteredTable(Image(1, 16384, {0.5f, 0.5f, 0.5f, 1}));
  ASSERT_FALSE(block.ok());
  EXPECT_NE(std::string(block.status().message()).find("1x16384"), std::string::npos)
      << block.status();
}

// An EXR whose chunk table points before the start of its bytes (found by the upload fuzz
// target: OpenImageIO's memory reader read outside them) is refused with an error. The over-read
// itself shows only under ASan: the upload fuzz test replays this input from its corpus.
TEST(ImageLimits, AnExrChunkBeforeTheStartOfTheBytesIsAnError) {
  std::ifstream in(std::string(APERTURE_TEST_DATA) +
                       "/../fuzz/corpus/upload/exr-chunk-offset-before-start.exr-bytes",
                   std::ios::binary);
  ASSERT_TRUE(in);
  const std::string exr((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto image = DecodeImage(std::span(reinterpret_cast<const uint8_t*>(exr.data()), exr.size()));
  ASSERT_FALSE(image.ok());
  EXPECT_EQ(image.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_FALSE(image.status().message().empty());
}

}  // namespace
}  // namespace aperture

namespace aperture {
namespace {

// OpenEXR's header reader allocates
// what an attribute's size says. A 40-byte EXR that declares a 2 GiB attribute is refused before
// OpenImageIO opens it; a real EXR still opens.
TEST(ImageLimits, AnExrAttributeLargerThanTheFileIsRefusedBeforeOpenExrReadsIt) {
  std::string exr("v/1\x01\x02\x00\x00\x00", 8);
  exr += std::string("comment\0opaqueType\0", 19);
  exr += std::string("\xff\xff\xff\x7f", 4);  // 2^31 - 1 bytes
  exr += "a few bytes";
  auto header =
      ReadImageHeader(std::span(reinterpret_cast<const uint8_t*>(exr.data()), exr.size()));
  ASSERT_FALSE(header.ok());
  EXPECT_NE(header.status().message().find("declares 2147483647 bytes, more than the file holds"),
            std::string::npos)
      << header.status();

  auto bytes = EncodeExr(Image(3, 5, Rgba{0.25f, 0.5f, 1.0f, 1.0f}), ExrOptions{});
  ASSERT_TRUE(bytes.ok()) << bytes.status();
  auto real =
      ReadImageHeader(std::span(reinterpret_cast<const uint8_t*>(bytes->data()), bytes->size()));
  ASSERT_TRUE(real.ok()) << real.status();
  EXPECT_EQ(real->width, 3);
  EXPECT_EQ(real->height, 5);
}

}  // namespace
}  // namespace aperture
