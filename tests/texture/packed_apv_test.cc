#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "texture/packed/apv_file.h"
#include "texture/packed/apv_run_stream.h"
#include "texture/packed/crc32.h"
#include "texture/packed/rgba8_image.h"
#include "texture/packed_test_images.h"

namespace aperture::packed {
namespace {

using testing::RandomIndexedImage;

std::vector<uint8_t> Encoded(const IndexedImage& image, Curve curve,
                             uint16_t version = kApvVersionZstd) {
  auto packed = PackTexture(image, curve);
  EXPECT_TRUE(packed.ok());
  return EncodeApv(packed->view(), ApvWriteOptions{.version = version});
}

// The byte-level checks below read the uncompressed layout (version 1).
std::vector<uint8_t> EncodedPlain(const IndexedImage& image, Curve curve) {
  return Encoded(image, curve, kApvVersionPlain);
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
        for (uint16_t version : {kApvVersionPlain, kApvVersionZstd}) {
          auto back = DecodeApv(EncodeApv(packed->view(), ApvWriteOptions{.version = version}));
          ASSERT_TRUE(back.ok()) << back.status();
          EXPECT_EQ(back->view().curve(), curve);
          EXPECT_EQ(back->view().width(), w);
          EXPECT_EQ(back->view().height(), h);
          EXPECT_TRUE(std::equal(back->bytes().begin(), back->bytes().end(),
                                 packed->bytes().begin(), packed->bytes().end()));
          EXPECT_EQ(UnpackTexture(back->view()).indices, image.indices);
        }
      }
    }
  }
}

TEST(PackedApv, PlainRunLengthsAreSevenBitGroupsWithStopBitOnTheLastByte) {
  // One colour on 256 x 256: a single run of 65536 steps = 4 x 2^14: groups 0, 0, 4.
  const std::vector<uint8_t> bytes =
      EncodedPlain(RandomIndexedImage(256, 256, 1, 1), Curve::kHilbert);
  const size_t runs = kApvHeaderSize + 4;  // one palette entry
  ASSERT_EQ(bytes.size(), runs + 3 + 1 + 4);
  EXPECT_EQ(bytes[runs + 0], 0x00);
  EXPECT_EQ(bytes[runs + 1], 0x00);
  EXPECT_EQ(bytes[runs + 2], 0x80 | 4);
  EXPECT_EQ(bytes[runs + 3], 0);  // palette index
  // A 1 x 1 texture: one run of length 1, one byte.
  const std::vector<uint8_t> tiny = EncodedPlain(RandomIndexedImage(1, 1, 1, 1), Curve::kMorton);
  EXPECT_EQ(tiny[kApvHeaderSize + 4], 0x81);
}

TEST(PackedApv, EveryTruncationIsAClearError) {
  for (uint16_t version : {kApvVersionPlain, kApvVersionZstd}) {
    SCOPED_TRACE(version);
    const std::vector<uint8_t> good =
        Encoded(RandomIndexedImage(40, 30, 5, 9, true), Curve::kHilbert, version);
    for (size_t n = 0; n < good.size(); ++n) {
      std::vector<uint8_t> cut(good.begin(), good.begin() + n);  // own buffer: ASan sees over-reads
      auto t = DecodeApv(cut);
      ASSERT_FALSE(t.ok()) << n;
      if (n >= 8) {
        EXPECT_NE(t.status().message().find("truncated"), std::string::npos) << n;
      }
    }
  }
}

TEST(PackedApv, EveryFlippedBitFailsTheChecksumOrAStructuralCheck) {
  for (uint16_t version : {kApvVersionPlain, kApvVersionZstd}) {
    const std::vector<uint8_t> good =
        Encoded(RandomIndexedImage(40, 30, 5, 9, true), Curve::kMorton, version);
    for (size_t i = 0; i < good.size(); ++i) {
      for (int bit : {0, 7}) {
        std::vector<uint8_t> bad = good;
        bad[i] ^= static_cast<uint8_t>(1 << bit);
        ASSERT_FALSE(DecodeApv(bad).ok())
            << "version " << version << " byte " << i << " bit " << bit;
      }
    }
  }
}

TEST(PackedApv, HostilePlainFilesWithValidChecksumsAreRejected) {
  const std::vector<uint8_t> good =
      EncodedPlain(RandomIndexedImage(40, 30, 5, 9, true), Curve::kHilbert);
  ASSERT_TRUE(DecodeApv(good).ok());
  auto with = [&](auto change) {
    std::vector<uint8_t> b = good;
    change(b);
    return ErrorOf(Resealed(b));
  };
  EXPECT_NE(with([](auto& b) { b[1] = 'X'; }).find("magic"), std::string::npos);
  EXPECT_NE(with([](auto& b) { b[8] = 3; }).find("version"), std::string::npos);
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

uint64_t GetU64(const std::vector<uint8_t>& b, size_t at) {
  uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | b[at + i];
  return v;
}
void PutU64(std::vector<uint8_t>& b, size_t at, uint64_t v) {
  for (int i = 0; i < 8; ++i) b[at + i] = static_cast<uint8_t>(v >> (8 * i));
}

// A version 2 file with its run block replaced by `block` (compressed) declaring `decoded` bytes.
std::vector<uint8_t> WithRunBlock(const std::vector<uint8_t>& good, size_t palette_size,
                                  std::span<const uint8_t> block, uint64_t decoded) {
  const size_t runs = kApvZstdHeaderSize + 4 * palette_size;
  std::vector<uint8_t> b(good.begin(), good.begin() + runs);
  b.insert(b.end(), block.begin(), block.end());
  b.resize(b.size() + 4);
  PutU64(b, 28, block.size());
  PutU64(b, 36, decoded);
  return Resealed(b);
}

TEST(PackedApv, ZstdHeaderDeclaresTheCompressedAndDecompressedRunBlock) {
  const IndexedImage image = RandomIndexedImage(64, 48, 4, 3, true);
  const std::vector<uint8_t> plain = EncodedPlain(image, Curve::kHilbert);
  const std::vector<uint8_t> zstd = Encoded(image, Curve::kHilbert);
  EXPECT_EQ(ApvVersionOf(zstd), kApvVersionZstd);
  EXPECT_EQ(ApvVersionOf(plain), kApvVersionPlain);
  EXPECT_EQ(zstd[11], kApvCoderZstd);
  // The decompressed block holds the same bytes as the plain one, lengths and indices apart.
  EXPECT_EQ(GetU64(zstd, 36), GetU64(plain, 28));
  EXPECT_EQ(zstd.size(), kApvZstdHeaderSize + 4 * 4 + GetU64(zstd, 28) + 4);
  // The frame starts with zstd's magic number 28 B5 2F FD.
  const size_t runs = kApvZstdHeaderSize + 4 * 4;
  EXPECT_EQ(zstd[runs], 0x28);
  EXPECT_EQ(zstd[runs + 3], 0xFD);
}

TEST(PackedApv, ZstdFilesOfAirportMapsAreSmallerThanTheirPng) {
  // Schiphol at 2048: 42,683 bytes of optimised PNG (docs/BENCHMARKS.md), 108,703 as version 1.
  auto rgba =
      LoadRgba8Image(std::string(APERTURE_SHARED_DATA) + "/vector/osm_eham_schiphol_2048.png");
  ASSERT_TRUE(rgba.ok()) << rgba.status();
  auto image = BuildPalette(*rgba);
  ASSERT_TRUE(image.ok());
  const std::vector<uint8_t> zstd = Encoded(*image, Curve::kHilbert);
  EXPECT_LE(zstd.size(), 42683u);
  EXPECT_LT(zstd.size() * 3, EncodedPlain(*image, Curve::kHilbert).size());
  auto back = DecodeApv(zstd);
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(UnpackTexture(back->view()).indices, image->indices);
}

TEST(PackedApv, OlderPlainFilesStillLoad) {
  // Written by the version 1 writer before version 2 existed (also a fuzzer seed).
  auto old = ReadFileBytes(std::string(APERTURE_TEST_DATA) + "/packed/helsinki30x17_morton_v1.apv");
  ASSERT_TRUE(old.ok()) << old.status();
  ASSERT_EQ(ApvVersionOf(*old), kApvVersionPlain);
  auto texture = DecodeApv(*old);
  ASSERT_TRUE(texture.ok()) << texture.status();
  EXPECT_EQ(texture->view().width(), 30u);
  EXPECT_EQ(texture->view().height(), 17u);
  EXPECT_EQ(texture->view().curve(), Curve::kMorton);
  // The version 1 writer still writes it byte for byte; as version 2 it holds the same texture.
  EXPECT_EQ(EncodeApv(texture->view(), ApvWriteOptions{.version = kApvVersionPlain}), *old);
  auto again = DecodeApv(EncodeApv(texture->view()));
  ASSERT_TRUE(again.ok()) << again.status();
  EXPECT_TRUE(std::equal(again->bytes().begin(), again->bytes().end(), texture->bytes().begin(),
                         texture->bytes().end()));
}

TEST(PackedApv, CorruptOrTruncatedZstdStreamsAreClearErrors) {
  const IndexedImage image = RandomIndexedImage(40, 30, 5, 9, true);
  const std::vector<uint8_t> good = Encoded(image, Curve::kHilbert);
  ASSERT_TRUE(DecodeApv(good).ok());
  const size_t runs = kApvZstdHeaderSize + 4 * 5;
  const std::span<const uint8_t> frame(good.data() + runs, GetU64(good, 28));
  const uint64_t decoded = GetU64(good, 36);
  // The frame cut short, its sizes patched and the file resealed: only the stream tells.
  for (size_t cut : {size_t{1}, size_t{5}, frame.size() / 2, frame.size() - 1}) {
    const std::string error =
        ErrorOf(WithRunBlock(good, 5, frame.first(frame.size() - cut), decoded));
    EXPECT_NE(error.find("run block"), std::string::npos) << cut << ": " << error;
    EXPECT_TRUE(error.find("truncated") != std::string::npos ||
                error.find("corrupt zstd stream") != std::string::npos)
        << cut << ": " << error;
  }
  // Not a zstd frame at all.
  std::vector<uint8_t> garbage(frame.begin(), frame.end());
  garbage[0] ^= 0xFF;
  EXPECT_NE(ErrorOf(WithRunBlock(good, 5, garbage, decoded)).find("corrupt zstd stream"),
            std::string::npos);
  // Sizes that disagree with the frame.
  EXPECT_NE(ErrorOf(WithRunBlock(good, 5, frame, decoded + 1)).find("the header declares"),
            std::string::npos);
  EXPECT_NE(ErrorOf(WithRunBlock(good, 5, frame, decoded - 1)).find("more than the"),
            std::string::npos);
  // Bytes after the frame.
  std::vector<uint8_t> longer(frame.begin(), frame.end());
  longer.push_back(0);
  EXPECT_NE(ErrorOf(WithRunBlock(good, 5, longer, decoded)).find("after the zstd frame"),
            std::string::npos);
  // A well-formed frame whose runs are wrong: a length of 0, then too few bytes for the indices.
  std::vector<uint8_t> zero_length(decoded, 0x81);
  zero_length[0] = 0x80;
  EXPECT_NE(
      ErrorOf(WithRunBlock(good, 5, ZstdCompressFrame(zero_length, 3), decoded)).find("length 0"),
      std::string::npos);
  const std::vector<uint8_t> short_block(decoded - 10, 0x81);
  EXPECT_NE(ErrorOf(WithRunBlock(good, 5, ZstdCompressFrame(short_block, 3), decoded - 10))
                .find("run block"),
            std::string::npos);
  // An unknown coder, and a decompressed size no run count can take.
  std::vector<uint8_t> coder = good;
  coder[11] = 2;
  EXPECT_NE(ErrorOf(Resealed(coder)).find("unknown run coder 2"), std::string::npos);
  EXPECT_NE(ErrorOf(WithRunBlock(good, 5, frame, 1u << 30)).find("more than the"),
            std::string::npos);
  // A header claiming many more runs than its frame holds: refused, memory bounded by the frame.
  std::vector<uint8_t> many = good;
  PutU32(many, 24, 40 * 30);
  PutU64(many, 36, 40 * 30 * 2);
  const std::string many_error = ErrorOf(Resealed(many));
  EXPECT_EQ(many_error.rfind(".apv: run", 0), 0u) << many_error;
}

TEST(PackedApv, DecodedSizeEstimateCountsTheRuns) {
  const IndexedImage image = RandomIndexedImage(64, 48, 4, 3, true);
  auto packed = PackTexture(image, Curve::kHilbert);
  ASSERT_TRUE(packed.ok());
  const std::vector<uint8_t> zstd = EncodeApv(packed->view());
  EXPECT_GE(ApvDecodedBytesEstimate(zstd), packed->view().byte_size());
  EXPECT_LT(ApvDecodedBytesEstimate(zstd), packed->view().byte_size() + 64);
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
