// The in-memory packed vector texture (seed 001, section 2.1): header, palette, data block of runs
// D_i = <S_i, P_i>, S_i the curve step of the i-th run's last texel, P_i its palette index.
//
// The bytes hold no pointers, only offsets from the start of the header, so the same bytes work in
// place from a file, shared memory or a gRPC message. Layout (little-endian, version 1):
//
//   PackedHeader                          56 bytes
//   palette   palette_size x uint32       RGBA8, r in the low byte      at palette_offset
//   steps     run_count x uint32          S_i, strictly increasing      at steps_offset (4-aligned)
//   indices   run_count x uint8           P_i < palette_size            at indices_offset
//
// Steps are 0-based (the paper's step number minus 1, see space_filling_curve.h); the last run ends
// at the last texel inside the texture. Steps and indices are kept in two arrays rather than as
// 5-byte tuples so the binary search touches only steps.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "texture/packed/palette.h"
#include "texture/packed/space_filling_curve.h"

namespace aperture::packed {

inline constexpr uint32_t kPackedMagic = 0x4D565041;  // "APVM" in memory order
inline constexpr uint16_t kPackedVersion = 1;

struct PackedHeader {
  uint32_t magic;
  uint16_t version;
  uint8_t curve;  // Curve
  uint8_t order;  // the curve covers 2^order x 2^order
  uint32_t width, height;
  uint32_t palette_size;  // 1..256
  uint32_t run_count;     // 1..width*height
  uint64_t palette_offset, steps_offset, indices_offset;
  uint64_t total_size;  // bytes of header + palette + runs
};
static_assert(sizeof(PackedHeader) == 56);

// A validated, read-only view of packed bytes; does not own them. Texel access by the paper's
// plain binary search (section 2.3); run_index.h has the faster indexed search.
class PackedTextureView {
 public:
  PackedTextureView() = default;
  // Checks everything a reader relies on: magic, version, sizes, offsets inside `bytes`, alignment,
  // steps strictly increasing and ending on the texture's last texel, indices < palette size.
  static absl::StatusOr<PackedTextureView> FromBytes(std::span<const uint8_t> bytes);

  uint32_t width() const { return header_.width; }
  uint32_t height() const { return header_.height; }
  Curve curve() const { return static_cast<Curve>(header_.curve); }
  int order() const { return header_.order; }
  std::span<const uint32_t> palette() const { return palette_; }
  std::span<const uint32_t> steps() const { return steps_; }
  std::span<const uint8_t> indices() const { return indices_; }
  size_t run_count() const { return steps_.size(); }
  size_t byte_size() const { return header_.total_size; }

  uint32_t StepOf(uint32_t x, uint32_t y) const { return CurveStep(curve(), order(), x, y); }
  // Index of the run holding `step`: the first i with S_i >= step (seed 001, section 2.3).
  size_t RunOfStep(uint32_t step) const;
  // Palette index and colour of texel (x, y); x < width, y < height.
  uint8_t PaletteIndexAt(uint32_t x, uint32_t y) const { return indices_[RunOfStep(StepOf(x, y))]; }
  uint32_t ColorAt(uint32_t x, uint32_t y) const { return palette_[PaletteIndexAt(x, y)]; }

 private:
  PackedHeader header_{};
  std::span<const uint32_t> palette_;
  std::span<const uint32_t> steps_;
  std::span<const uint8_t> indices_;
};

// Owns packed bytes (8-byte aligned) and a view of them.
class PackedTexture {
 public:
  PackedTexture() = default;
  PackedTexture(PackedTexture&&) = default;
  PackedTexture& operator=(PackedTexture&&) = default;
  PackedTexture(const PackedTexture&) = delete;
  PackedTexture& operator=(const PackedTexture&) = delete;

  // Takes a copy of `bytes` and validates it.
  static absl::StatusOr<PackedTexture> FromBytes(std::span<const uint8_t> bytes);
  // Lays out the format from its parts; validates.
  static absl::StatusOr<PackedTexture> Assemble(uint32_t width, uint32_t height, Curve curve,
                                                std::span<const uint32_t> palette,
                                                std::span<const uint32_t> steps,
                                                std::span<const uint8_t> indices);

  const PackedTextureView& view() const { return view_; }
  std::span<const uint8_t> bytes() const {
    return {reinterpret_cast<const uint8_t*>(storage_.data()), view_.byte_size()};
  }

 private:
  std::vector<uint64_t> storage_;
  PackedTextureView view_;
};

// The packer (seed 001, section 2.2): scans along the curve, one run per maximal sequence of equal
// palette indices; steps outside a non-square texture are skipped but counted.
absl::StatusOr<PackedTexture> PackTexture(const IndexedImage& image, Curve curve);

// Every texel back, by walking the runs along the curve.
IndexedImage UnpackTexture(const PackedTextureView& texture);

}  // namespace aperture::packed
