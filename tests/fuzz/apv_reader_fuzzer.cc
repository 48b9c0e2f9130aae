// libFuzzer target for the .apv reader: any bytes must give a texture or a clear error,
// never a crash, an over-read (ASan) or undefined behaviour (UBSan). A texture that is accepted
// must also be safe to use: unpacking, plain and indexed lookups, area integrals, re-encoding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <vector>

#include "texture/packed/apv_file.h"
#include "texture/packed/area_integral.h"
#include "texture/packed/run_index.h"

namespace {

using namespace aperture::packed;

void Exercise(const PackedTexture& texture) {
  const PackedTextureView& v = texture.view();
  const RunIndex index(v);
  const uint64_t texels = uint64_t{v.width()} * v.height();
  // Every texel of small textures, a diagonal of large ones.
  const uint32_t stride = texels <= 65536 ? 1 : 1 + v.width() / 64;
  std::vector<uint32_t> xs, ys;
  for (uint32_t y = 0; y < v.height(); y += stride) {
    for (uint32_t x = 0; x < v.width(); x += stride) {
      if (index.ColorAt(x, y) != v.ColorAt(x, y)) std::abort();
      xs.push_back(x);
      ys.push_back(y);
    }
  }
  std::vector<uint32_t> batch(xs.size());
  index.ColorsAt(xs, ys, batch);
  for (size_t i = 0; i < xs.size(); ++i)
    if (batch[i] != v.ColorAt(xs[i], ys[i])) std::abort();
  if (texels <= 65536) {
    const IndexedImage image = UnpackTexture(v);
    const AreaIntegrator area(v);
    const auto sum = area.SumTexels(0, 0, v.width(), v.height());
    uint64_t red = 0;
    for (uint8_t p : image.indices) red += Channel(image.palette[p], 0);
    if (sum[0] != red) std::abort();
    area.Integrate(-0.5, 0.25, v.width() * 1.5, v.height() + 0.75);
  }
  auto again = DecodeApv(EncodeApv(v));
  if (!again.ok() || again->view().run_count() != v.run_count()) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::span<const uint8_t> bytes(data, size);
  if (auto t = DecodeApv(bytes); t.ok()) Exercise(*t);
  // Without the checksum the structural checks see the mutations too.
  if (auto t = DecodeApv(bytes, ApvReadOptions{.verify_checksum = false}); t.ok()) Exercise(*t);
  return 0;
}
