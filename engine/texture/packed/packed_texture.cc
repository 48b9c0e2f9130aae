#include "texture/packed/packed_texture.h"

#include <algorithm>
#include <cstring>

#include "absl/strings/str_cat.h"
#include "texture/packed/curve_walk.h"

namespace aperture::packed {
namespace {

uint64_t AlignUp(uint64_t n, uint64_t a) { return (n + a - 1) / a * a; }

bool RangeInside(uint64_t offset, uint64_t length, uint64_t total) {
  return offset <= total && length <= total - offset;
}

}  // namespace

absl::StatusOr<PackedTextureView> PackedTextureView::FromBytes(std::span<const uint8_t> bytes) {
  PackedHeader h;
  if (bytes.size() < sizeof(h))
    return absl::InvalidArgumentError(
        absl::StrCat("packed texture: ", bytes.size(), " bytes, shorter than its 56-byte header"));
  std::memcpy(&h, bytes.data(), sizeof(h));
  if (h.magic != kPackedMagic)
    return absl::InvalidArgumentError("packed texture: wrong magic (not an in-memory APVM block)");
  if (h.version != kPackedVersion)
    return absl::InvalidArgumentError(absl::StrCat("packed texture: version ", h.version,
                                                   ", this reader knows ", kPackedVersion));
  if (h.curve > static_cast<uint8_t>(Curve::kMorton))
    return absl::InvalidArgumentError(absl::StrCat("packed texture: unknown curve ", h.curve));
  if (h.width == 0 || h.height == 0 || h.width > kMaxTextureSide || h.height > kMaxTextureSide)
    return absl::InvalidArgumentError(absl::StrCat("packed texture: size ", h.width, "x", h.height,
                                                   " outside 1..65536 per side"));
  if (h.order != CurveOrder(h.width, h.height))
    return absl::InvalidArgumentError("packed texture: curve order does not match the size");
  if (h.palette_size == 0 || h.palette_size > kMaxPaletteSize)
    return absl::InvalidArgumentError(
        absl::StrCat("packed texture: palette size ", h.palette_size, " outside 1..256"));
  if (h.run_count == 0 || uint64_t{h.run_count} > uint64_t{h.width} * h.height)
    return absl::InvalidArgumentError(
        absl::StrCat("packed texture: run count ", h.run_count, " outside 1..width*height"));
  if (h.total_size > bytes.size())
    return absl::InvalidArgumentError(absl::StrCat("packed texture: header says ", h.total_size,
                                                   " bytes, only ", bytes.size(), " present"));
  if (!RangeInside(h.palette_offset, uint64_t{h.palette_size} * 4, h.total_size) ||
      !RangeInside(h.steps_offset, uint64_t{h.run_count} * 4, h.total_size) ||
      !RangeInside(h.indices_offset, h.run_count, h.total_size) || h.palette_offset < sizeof(h) ||
      h.steps_offset < sizeof(h) || h.indices_offset < sizeof(h))
    return absl::InvalidArgumentError("packed texture: a section lies outside the bytes");
  const uint8_t* base = bytes.data();
  if (reinterpret_cast<uintptr_t>(base + h.palette_offset) % alignof(uint32_t) != 0 ||
      reinterpret_cast<uintptr_t>(base + h.steps_offset) % alignof(uint32_t) != 0)
    return absl::InvalidArgumentError(
        "packed texture: palette or steps not 4-byte aligned in memory (copy the bytes to an "
        "aligned buffer)");
  PackedTextureView view;
  view.header_ = h;
  view.palette_ = {reinterpret_cast<const uint32_t*>(base + h.palette_offset), h.palette_size};
  view.steps_ = {reinterpret_cast<const uint32_t*>(base + h.steps_offset), h.run_count};
  view.indices_ = {base + h.indices_offset, h.run_count};
  // seed 001, section 2.3: "S_i > S_{i-1}" is what makes binary search valid.
  for (size_t i = 1; i < view.steps_.size(); ++i)
    if (view.steps_[i] <= view.steps_[i - 1])
      return absl::InvalidArgumentError(
          absl::StrCat("packed texture: run ", i, " does not end after run ", i - 1));
  const uint32_t last = LastStepInside(view.curve(), h.width, h.height);
  if (view.steps_.back() != last)
    return absl::InvalidArgumentError(absl::StrCat("packed texture: runs end at step ",
                                                   view.steps_.back(),
                                                   ", the texture's last texel is step ", last));
  for (size_t i = 0; i < view.indices_.size(); ++i)
    if (view.indices_[i] >= h.palette_size)
      return absl::InvalidArgumentError(absl::StrCat("packed texture: run ", i,
                                                     " has palette index ", view.indices_[i],
                                                     ", palette has ", h.palette_size));
  return view;
}

size_t PackedTextureView::RunOfStep(uint32_t step) const {
  return static_cast<size_t>(std::lower_bound(steps_.begin(), steps_.end(), step) - steps_.begin());
}

absl::StatusOr<PackedTexture> PackedTexture::FromBytes(std::span<const uint8_t> bytes) {
  PackedTexture t;
  t.storage_.resize((bytes.size() + 7) / 8);
  if (!bytes.empty()) std::memcpy(t.storage_.data(), bytes.data(), bytes.size());
  auto view = PackedTextureView::FromBytes(
      {reinterpret_cast<const uint8_t*>(t.storage_.data()), bytes.size()});
  if (!view.ok()) return view.status();
  t.view_ = *view;
  return t;
}

absl::StatusOr<PackedTexture> PackedTexture::Assemble(uint32_t width, uint32_t height, Curve curve,
                                                      std::span<const uint32_t> palette,
                                                      std::span<const uint32_t> steps,
                                                      std::span<const uint8_t> indices) {
  if (steps.size() != indices.size())
    return absl::InvalidArgumentError("packed texture: steps and indices differ in count");
  if (width == 0 || height == 0 || width > kMaxTextureSide || height > kMaxTextureSide)
    return absl::InvalidArgumentError(
        absl::StrCat("packed texture: size ", width, "x", height, " outside 1..65536 per side"));
  PackedHeader h{};
  h.magic = kPackedMagic;
  h.version = kPackedVersion;
  h.curve = static_cast<uint8_t>(curve);
  h.order = static_cast<uint8_t>(CurveOrder(width, height));
  h.width = width;
  h.height = height;
  h.palette_size = static_cast<uint32_t>(palette.size());
  h.run_count = static_cast<uint32_t>(steps.size());
  h.palette_offset = sizeof(PackedHeader);
  h.steps_offset = AlignUp(h.palette_offset + 4 * palette.size(), 8);
  h.indices_offset = h.steps_offset + 4 * steps.size();
  h.total_size = h.indices_offset + indices.size();
  std::vector<uint8_t> bytes(h.total_size, 0);
  std::memcpy(bytes.data(), &h, sizeof(h));
  if (!palette.empty())
    std::memcpy(bytes.data() + h.palette_offset, palette.data(), 4 * palette.size());
  if (!steps.empty()) std::memcpy(bytes.data() + h.steps_offset, steps.data(), 4 * steps.size());
  if (!indices.empty())
    std::memcpy(bytes.data() + h.indices_offset, indices.data(), indices.size());
  return FromBytes(bytes);
}

absl::StatusOr<PackedTexture> PackTexture(const IndexedImage& image, Curve curve) {
  if (image.width == 0 || image.height == 0 || image.width > kMaxTextureSide ||
      image.height > kMaxTextureSide)
    return absl::InvalidArgumentError(absl::StrCat("cannot pack a ", image.width, "x", image.height,
                                                   " texture: sides must be 1..65536"));
  if (image.indices.size() != size_t{image.width} * image.height)
    return absl::InvalidArgumentError("cannot pack: index count does not match the size");
  if (image.palette.empty() || image.palette.size() > kMaxPaletteSize)
    return absl::InvalidArgumentError("cannot pack: palette must have 1..256 colours");
  std::vector<uint32_t> steps;
  std::vector<uint8_t> indices;
  // seed 001, section 2.2 (Convert): a run closes when the colour changes; S_i is the step of
  // its last texel. (The paper's pseudocode records the step of the next run's first texel; its
  // definition and table 3 record the last texel's, which we follow.)
  uint8_t current = image.indices[0];
  uint32_t last_step = 0;
  WalkCurve(curve, image.width, image.height, [&](uint32_t step, uint32_t x, uint32_t y) {
    const uint8_t next = image.indices[size_t{y} * image.width + x];
    if (next != current) {
      steps.push_back(last_step);
      indices.push_back(current);
      current = next;
    }
    last_step = step;
  });
  steps.push_back(last_step);
  indices.push_back(current);
  for (uint8_t p : indices)
    if (p >= image.palette.size())
      return absl::InvalidArgumentError("cannot pack: a palette index is out of range");
  return PackedTexture::Assemble(image.width, image.height, curve, image.palette, steps, indices);
}

IndexedImage UnpackTexture(const PackedTextureView& texture) {
  IndexedImage image;
  image.width = texture.width();
  image.height = texture.height();
  image.palette.assign(texture.palette().begin(), texture.palette().end());
  image.indices.resize(size_t{image.width} * image.height);
  const std::span<const uint32_t> steps = texture.steps();
  const std::span<const uint8_t> indices = texture.indices();
  size_t run = 0;
  WalkCurve(texture.curve(), image.width, image.height, [&](uint32_t step, uint32_t x, uint32_t y) {
    while (steps[run] < step) ++run;
    image.indices[size_t{y} * image.width + x] = indices[run];
  });
  return image;
}

}  // namespace aperture::packed
