#include "testing/random_image.h"

#include <random>

namespace aperture {

Image RandomImage(int width, int height, uint32_t seed, bool random_alpha) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> value(0, 1);
  Image image(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      Rgba& t = image.at(x, y);
      t.r = value(rng), t.g = value(rng), t.b = value(rng);
      t.a = random_alpha ? value(rng) : 1.0f;
    }
  return image;
}

}  // namespace aperture
