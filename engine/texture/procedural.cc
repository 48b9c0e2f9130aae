#include "texture/procedural.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>

namespace aperture {
namespace {

uint32_t Hash(uint32_t x, uint32_t y, uint32_t seed) {
  uint32_t h = x * 374761393u + y * 668265263u + seed * 2246822519u;
  h = (h ^ (h >> 13)) * 1274126177u;
  return h ^ (h >> 16);
}

float Lattice(int x, int y, int period, uint32_t seed) {
  const uint32_t px = static_cast<uint32_t>(((x % period) + period) % period);
  const uint32_t py = static_cast<uint32_t>(((y % period) + period) % period);
  return static_cast<float>(Hash(px, py, seed) & 0xffff) / 65535.0f;
}

}  // namespace

Image MakeNoiseTexture(int size, uint32_t seed, Rgba dark, Rgba light) {
  Image image(size, size);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      float value = 0, amplitude = 0.5f, norm = 0;
      for (int octave = 0, period = 8; octave < 6 && period <= size; ++octave, period *= 2) {
        const float fx = static_cast<float>(x) * period / size,
                    fy = static_cast<float>(y) * period / size;
        const int ix = static_cast<int>(fx), iy = static_cast<int>(fy);
        const float tx = fx - ix, ty = fy - iy;
        const float sx = tx * tx * (3 - 2 * tx), sy = ty * ty * (3 - 2 * ty);
        const uint32_t s = seed + static_cast<uint32_t>(octave) * 7919u;
        const float a = Lattice(ix, iy, period, s), b = Lattice(ix + 1, iy, period, s);
        const float c = Lattice(ix, iy + 1, period, s), d = Lattice(ix + 1, iy + 1, period, s);
        value += amplitude * ((a * (1 - sx) + b * sx) * (1 - sy) + (c * (1 - sx) + d * sx) * sy);
        norm += amplitude;
        amplitude *= 0.6f;
      }
      const float t = std::clamp(value / norm, 0.0f, 1.0f);
      image.at(x, y) = dark * (1 - t) + light * t;
      image.at(x, y).a = 1;
    }
  }
  return image;
}

absl::StatusOr<std::vector<uint8_t>> EncodePng(const Image& image, int zlib_level) {
  bool alpha = false;
  for (const Rgba& t : image.texels()) alpha = alpha || t.a < 1.0f;
  const int channels = alpha ? 4 : 3;
  std::vector<uint8_t> pixels(static_cast<size_t>(image.width()) * image.height() * channels);
  size_t k = 0;
  for (const Rgba& t : image.texels())
    for (int c = 0; c < channels; ++c) {
      const float v = c == 0 ? t.r : c == 1 ? t.g : c == 2 ? t.b : t.a;
      pixels[k++] = static_cast<uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
    }
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput proxy(bytes);
  auto out = OIIO::ImageOutput::create("texture.png", &proxy);
  if (!out) return absl::InternalError("OpenImageIO has no PNG writer");
  OIIO::ImageSpec spec(image.width(), image.height(), channels, OIIO::TypeDesc::UINT8);
  spec.attribute("png:compressionLevel", zlib_level);
  // The texels are written as they are: with alpha, PNG's unassociated colours (which decoding
  // premultiplies again, as for any PNG).
  if (alpha) spec.attribute("oiio:UnassociatedAlpha", 1);
  if (!out->open("texture.png", spec) || !out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) ||
      !out->close())
    return absl::InternalError("cannot encode PNG: " + out->geterror());
  return std::vector<uint8_t>(bytes.begin(), bytes.end());
}

}  // namespace aperture
