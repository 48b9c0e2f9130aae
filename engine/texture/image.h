// A linear-float RGBA image: the in-memory form of every raster texture before prefiltering.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/statusor.h"

namespace aperture {

struct Rgba {
  float r = 0, g = 0, b = 0, a = 0;

  Rgba operator+(const Rgba& o) const { return {r + o.r, g + o.g, b + o.b, a + o.a}; }
  Rgba operator*(float s) const { return {r * s, g * s, b * s, a * s}; }
  Rgba operator*(const Rgba& o) const { return {r * o.r, g * o.g, b * o.b, a * o.a}; }
  bool operator==(const Rgba&) const = default;
};

// Leaves elements unconstructed when no value is given, so that a frame buffer is first touched
// (and its pages faulted in) by the parallel workers that write it, not serially up front.
template <typename T>
struct UninitializedAllocator : std::allocator<T> {
  template <typename U>
  struct rebind {
    using other = UninitializedAllocator<U>;
  };
  template <typename U>
  void construct(U*) noexcept {}
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

class Image {
 public:
  Image() = default;
  Image(int width, int height, Rgba fill = {});
  // Every texel must be written before it is read.
  static Image Uninitialized(int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }
  bool empty() const { return width_ == 0 || height_ == 0; }

  Rgba& at(int x, int y) { return texels_[static_cast<size_t>(y) * width_ + x]; }
  const Rgba& at(int x, int y) const { return texels_[static_cast<size_t>(y) * width_ + x]; }
  std::span<const Rgba> texels() const { return texels_; }
  std::span<Rgba> texels() { return texels_; }

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<Rgba, UninitializedAllocator<Rgba>> texels_;
};

// The largest raster texture: 8192 x 8192 texels (1 GiB as float RGBA; its seed 000 table is
// 4.6 GB). Larger palette maps go in as packed vector textures (.apv, up to 65536 x 65536).
inline constexpr int64_t kMaxImageTexels = int64_t{8192} * 8192;

// Reads an image file through OpenImageIO. 8-bit values are taken as linear (value / 255).
// Greyscale becomes grey RGB, missing alpha becomes 1. Images of more than kMaxImageTexels
// texels are refused before their pixels are read.
absl::StatusOr<Image> LoadImageFile(const std::string& path);
// The same for an encoded image held in memory (PNG, JPEG, EXR, TIFF, ...).
absl::StatusOr<Image> DecodeImage(std::span<const uint8_t> bytes);

struct ImageHeader {
  int width = 0, height = 0, channels = 0;
  std::string format;  // OpenImageIO's name: "png", "openexr", ...
};
// The header of an encoded image, read without its pixels, with DecodeImage's checks (a known
// format, pixels present, at most kMaxImageTexels): what an upload or a scene's memory estimate
// needs to know before anything is decoded.
absl::StatusOr<ImageHeader> ReadImageHeader(std::span<const uint8_t> bytes);

// `cells` x `cells` squares on a `size` x `size` image; the top-left square has colour `a`.
Image MakeCheckerboard(int size, int cells, Rgba a, Rgba b);

// Resamples to the next power of two per side (OpenImageIO's default resize filter) when needed;
// returns the image unchanged otherwise.
Image ResizeToPowerOfTwo(const Image& image);

bool IsPowerOfTwo(int n);

}  // namespace aperture
