#include "texture/packed/rgba8_image.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>

#include "absl/strings/str_cat.h"
#include "texture/packed/space_filling_curve.h"

namespace aperture::packed {

absl::StatusOr<Rgba8Image> LoadRgba8Image(const std::string& path) {
  if (!OIIO::Filesystem::exists(path))
    return absl::NotFoundError(absl::StrCat("image file '", path, "' does not exist"));
  auto in = OIIO::ImageInput::open(path);
  if (!in)
    return absl::InvalidArgumentError(
        absl::StrCat("cannot read image file '", path, "': ", OIIO::geterror()));
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    return absl::InvalidArgumentError(absl::StrCat("image file '", path, "' has no pixels"));
  if (static_cast<uint32_t>(spec.width) > kMaxTextureSide ||
      static_cast<uint32_t>(spec.height) > kMaxTextureSide)
    return absl::InvalidArgumentError(absl::StrCat("image file '", path, "' is ", spec.width, "x",
                                                   spec.height, ", above 65536 per side"));
  const int channels = spec.nchannels;
  std::vector<uint8_t> pixels(size_t(spec.width) * spec.height * channels);
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, pixels.data()))
    return absl::InvalidArgumentError(absl::StrCat("image file '", path, "': ", in->geterror()));
  Rgba8Image image;
  image.width = static_cast<uint32_t>(spec.width);
  image.height = static_cast<uint32_t>(spec.height);
  image.texels.resize(size_t{image.width} * image.height);
  for (size_t i = 0; i < image.texels.size(); ++i) {
    const uint8_t* p = &pixels[i * channels];
    image.texels[i] = channels >= 3 ? PackRgba8(p[0], p[1], p[2], channels >= 4 ? p[3] : 255)
                                    : PackRgba8(p[0], p[0], p[0], channels == 2 ? p[1] : 255);
  }
  return image;
}

absl::Status WriteRgba8Image(const Rgba8Image& image, const std::string& path) {
  const bool opaque = std::all_of(image.texels.begin(), image.texels.end(),
                                  [](uint32_t t) { return Channel(t, 3) == 255; });
  const int channels = opaque ? 3 : 4;
  std::vector<uint8_t> pixels(image.texels.size() * channels);
  for (size_t i = 0; i < image.texels.size(); ++i)
    for (int c = 0; c < channels; ++c) pixels[i * channels + c] = Channel(image.texels[i], c);
  auto out = OIIO::ImageOutput::create(path);
  if (!out)
    return absl::InvalidArgumentError(
        absl::StrCat("cannot write image file '", path, "': ", OIIO::geterror()));
  OIIO::ImageSpec spec(static_cast<int>(image.width), static_cast<int>(image.height), channels,
                       OIIO::TypeDesc::UINT8);
  if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) ||
      !out->close())
    return absl::InternalError(absl::StrCat("writing '", path, "': ", out->geterror()));
  return absl::OkStatus();
}

}  // namespace aperture::packed
