#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "texture/packed/apv_file.h"
#include "texture/packed/crc32.h"
#include "texture/packed/rgba8_image.h"
#include "texture/packed_test_images.h"

namespace aperture::packed {
namespace {

using testing::RandomIndexedImage;

std::vector<uint8_t> Encoded(const IndexedImage& image, Curve curve) {
  auto packed = PackTexture(image, curve);
  EXPECT_TRUE(packed.ok());
  return EncodeApv(packed->view());
}

// Rewrites the trailing checksum so that a crafted file reaches the structural checks.
std::vector<uint8_t> Resealed(std::vector<uint8_t> bytes) {
  const uint32_t crc = Crc32(std::span<const uint8_t>(bytes).first(bytes.size() - 4));
  for (int i = 0; i < 4; ++i) bytes[bytes.size() - 4 + i] = static_cast<uint8_t>(crc >> (8 * i));
  return bytes;
}

void PutU32(std::vector<uint8_t>& b, size_t at, uint32_t v) {
  for (int i = 0; i < 4; ++i) b[at + i] = static_cast<uint8_t>(v >> (8 * i));
}

std::string ErrorOf(const std::vector<uint8_t>& bytes) {
  auto t = DecodeApv(bytes);
  return t.ok() ? std::string("(accepted)") : std::string(t.status().message());
}

TEST(PackedApv, Crc32KnownValue) {
  const char* text = "123456789";
  EXPECT_EQ(Crc32({reinterpret_cast<const uint8_t*>(text), 9}), 0xCBF43926u);
}

TEST(PackedApv, RoundTripKeepsEveryRun) {
  for (Curve curve : {Curve::kHilbert, Curve::kMorton}) {
    for (auto [w, h] : {std::pair{1u, 1u}, {1u, 77u}, {37u, 91u}, {256u, 256u}}) {
      for (uint32_t colours : {1u, 3u, 256u}) {
        const IndexedImage image = RandomIndexedImage(w, h, colours, w + h + colours, true);
        auto packed = PackTexture(image, curve);
        ASSERT_TRUE(packed.ok());
        auto back = DecodeApv(EncodeApv(packed->view()));
        ASSERT_TRUE(back.ok()) << back.status();
        EXPECT_EQ(back->view().curve(), curve);
        EXPECT_EQ(back->view().width(), w);
        EXPECT_EQ(back->view().height(), h);
        EXPECT_TRUE(std::equal(back->bytes().begin(), back->bytes().end(), packed->bytes().begin(),
                               packed->bytes().end()));
        EXPECT_EQ(UnpackTexture(back->view()).indices, image.indices);
      }
    }
  }
}

TEST(PackedApv, RunLengthsAreSevenBitGroupsWithStopBitOnTheLastByte) {
  // One colour on 256 x 256: a single run of 65536 steps = 4 x 2^14: groups 0, 0, 4.
  const std::vector<uint8_t> bytes = Encoded(RandomIndexedImage(256, 256, 1, 1), Curve::kHilbert);
  const size_t runs = kApvHeaderSize + 4;  // one palette entry
  ASSERT_EQ(bytes.size(), runs + 3 + 1 + 4);
  EXPECT_EQ(bytes[runs + 0], 0x00);
  EXPECT_EQ(bytes[runs + 1], 0x00);
  EXPECT_EQ(bytes[runs + 2], 0x80 | 4);
  EXPECT_EQ(bytes[runs + 3], 0);  // palette index
  // A 1 x 1 texture: one run of length 1, one byte.
  const std::vector<uint8_t> tiny = Encoded(RandomIndexedImage(1, 1, 1, 1), Curve::kMorton);
  EXPECT_EQ(tiny[kApvHeaderSize + 4], 0x81);
}

TEST(PackedApv, EveryTruncationIsAClearError) {
  const std::vector<uint8_t> good =
      Encoded(RandomIndexedImage(40, 30, 5, 9, true), Curve::kHilbert);
  for (size_t n = 0; n < good.size(); ++n) {
    std::vector<uint8_t> cut(good.begin(), good.begin() + n);  // own buffer: ASan sees over-reads
    auto t = DecodeApv(cut);
    ASSERT_FALSE(t.ok()) << n;
    if (n >= 8) {
      EXPECT_NE(t.status().message().find("truncated"), std::string::npos) << n;
    }
  }
}

TEST(PackedApv, EveryFlippedBitFailsTheChecksumOrAStructuralCheck) {
  const std::vector<uint8_t> good = Encoded(RandomIndexedImage(40, 30, 5, 9, true), Curve::kMorton);
  for (size_t i = 0; i < good.size(); ++i) {
    for (int bit : {0, 7}) {
      std::vector<uint8_t> bad = good;
      bad[i] ^= static_cast<uint8_t>(1 << bit);
      ASSERT_FALSE(DecodeApv(bad).ok()) << "byte " << i << " bit " << bit;
    }
  }
}

TEST(PackedApv, HostileFilesWithValidChecksumsAreRejected) {
  const std::vector<uint8_t> good =
      Encoded(RandomIndexedImage(40, 30, 5, 9, true), Curve::kHilbert);
  ASSERT_TRUE(DecodeApv(good).ok());
  auto with = [&](auto change) {
    std::vector<uint8_t> b = good;
    change(b);
    return ErrorOf(Resealed(b));
  };
  EXPECT_NE(with([](auto& b) { b[1] = 'X'; }).find("magic"), std::string::npos);
  EXPECT_NE(with([](auto& b) { b[8] = 2; }).find("version"), std::string::npos);
  EXPECT_NE(with([](auto& b) { b[10] = 7; }).find("curve"), std::string::npos);
  EXPECT_NE(with([](auto& b) { PutU32(b, 12, 70000); }).find("65536"), std::string::npos);
  EXPECT_NE(with([](auto& b) { PutU32(b, 16, 0); }).find("outside"), std::string::npos);
  EXPECT_NE(with([](auto& b) { PutU32(b, 20, 0); }).find("palette size"), std::string::npos);
  EXPECT_NE(with([](auto& b) { PutU32(b, 20, 300); }).find("palette size"), std::string::npos);
  EXPECT_NE(with([](auto& b) { PutU32(b, 24, 0xFFFFFFFFu); }).find("run count"), std::string::npos);
  EXPECT_NE(with([](auto& b) { PutU32(b, 24, 1000); }).find("run count"), std::string::npos);
  const size_t runs = kApvHeaderSize + 4 * 5;
  // First run length 0: steps not increasing.
  EXPECT_NE(with([&](auto& b) { b[runs] = 0x80; }).find("length 0"), std::string::npos);
  // First run's colour out of the palette (the first length is one byte for this image?).
  std::vector<uint8_t> b = good;
  size_t colour_at = runs;
  while (!(b[colour_at] & 0x80)) ++colour_at;
  ++colour_at;
  EXPECT_NE(with([&](auto& c) { c[colour_at] = 5; }).find("palette index"), std::string::npos);
  // A run that overshoots the texture.
  EXPECT_NE(with([&](auto& c) {
              c[runs] = 0x7F;
              c[runs + 1] = 0x7F;
              c[runs + 2] = 0xFF;
            }).find("past the texture"),
            std::string::npos);
  // Six-byte length.
  EXPECT_NE(with([&](auto& c) {
              for (int i = 0; i < 6; ++i) c[runs + i] = 0;
            }).find("longer than 5 bytes"),
            std::string::npos);
  // Runs stopping short: drop the last run (2 bytes) and patch the count and block size.
  {
    std::vector<uint8_t> c = good;
    const uint32_t count = c[24] | (c[25] << 8) | (c[26] << 16) | (uint32_t(c[27]) << 24);
    // Find the start of the last run.
    size_t at = runs, last_start = runs;
    for (uint32_t i = 0; i < count; ++i) {
      last_start = at;
      while (!(c[at] & 0x80)) ++at;
      at += 2;
    }
    c.erase(c.begin() + last_start, c.begin() + at);
    PutU32(c, 24, count - 1);
    PutU32(c, 28, static_cast<uint32_t>(last_start - runs));
    EXPECT_NE(ErrorOf(Resealed(c)).find("runs cover steps up to"), std::string::npos);
  }
  // Trailing garbage after the checksum, and a bad checksum.
  {
    std::vector<uint8_t> c = good;
    c.push_back(0);
    EXPECT_FALSE(DecodeApv(c).ok());
    c = good;
    c.back() ^= 0xFF;
    auto t = DecodeApv(c);
    ASSERT_FALSE(t.ok());
    EXPECT_NE(t.status().message().find("checksum"), std::string::npos);
  }
}

TEST(PackedApv, FilesOnDiskAndMap8192RoundTrip) {
  auto rgba =
      LoadRgba8Image(std::string(APERTURE_SHARED_DATA) + "/vector/osm_eddf_frankfurt_8192.png");
  ASSERT_TRUE(rgba.ok()) << rgba.status();
  auto image = BuildPalette(*rgba);
  ASSERT_TRUE(image.ok());
  rgba->texels = {};
  auto packed = PackTexture(*image, Curve::kHilbert);
  ASSERT_TRUE(packed.ok());
  const std::string path = ::testing::TempDir() + "/frankfurt_8192.apv";
  ASSERT_TRUE(WriteApvFile(path, packed->view()).ok());
  auto back = ReadApvFile(path);
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(UnpackTexture(back->view()).indices, image->indices);
  std::remove(path.c_str());
  auto missing = ReadApvFile(path);
  EXPECT_FALSE(missing.ok());
}

}  // namespace
}  // namespace aperture::packed
