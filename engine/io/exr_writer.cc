#include "io/exr_writer.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>

#include "absl/strings/str_cat.h"
#include "io/exr_chunk_encoder.h"

namespace aperture {
namespace {

// dwaa and dwab only: OpenEXR 3.1's core library cannot write them, OpenImageIO's C++ path can. No
// OpenEXR pool ("exr_threads" -1): a server's two concurrent frames waiting on OpenEXR 3.1's one
// global pool once left a request waiting forever in OutputFile::writePixels.
absl::Status EncodeThroughOpenImageIO(const Image& image, const ExrOptions& options,
                                      std::string* bytes) {
  std::vector<unsigned char> buffer;
  OIIO::Filesystem::IOVecOutput proxy(buffer);
  auto out = OIIO::ImageOutput::create("frame.exr", &proxy);
  if (!out) return absl::InternalError("OpenImageIO has no EXR writer");
  OIIO::attribute("exr_threads", -1);
  OIIO::ImageSpec spec(
      image.width(), image.height(), 4,
      options.pixel_type == ExrPixelType::kHalf ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
  spec.attribute("compression", ExrCompressionName(options.compression));
  const ExrMetadata& m = options.metadata;
  if (m.frame_width > 0) {  // the data window inside the whole frame's display window
    spec.x = m.x;
    spec.y = m.y;
    spec.full_x = spec.full_y = 0;
    spec.full_width = m.frame_width;
    spec.full_height = m.frame_height;
  }
  for (const ExrAttribute& a : HeaderAttributes(m)) {
    if (a.is_number)
      spec.attribute(a.name, a.number);
    else
      spec.attribute(a.name, a.text);
  }
  void* p = &proxy;
  spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &p);
  if (!out->open("frame.exr", spec) ||
      !out->write_image(OIIO::TypeDesc::FLOAT, image.texels().data()) || !out->close())
    return absl::InternalError(absl::StrCat("cannot write EXR: ", out->geterror()));
  bytes->assign(buffer.begin(), buffer.end());
  return absl::OkStatus();
}

}  // namespace

const char* ExrCompressionName(ExrCompression c) {
  switch (c) {
    case ExrCompression::kNone:
      return "none";
    case ExrCompression::kRle:
      return "rle";
    case ExrCompression::kZips:
      return "zips";
    case ExrCompression::kZip:
      return "zip";
    case ExrCompression::kPiz:
      return "piz";
    case ExrCompression::kDwaa:
      return "dwaa";
    case ExrCompression::kB44:
      return "b44";
    case ExrCompression::kB44a:
      return "b44a";
    case ExrCompression::kDwab:
      return "dwab";
  }
  return "zip";
}

bool CompressesHalfOnly(ExrCompression c) {
  return c == ExrCompression::kB44 || c == ExrCompression::kB44a;
}

absl::StatusOr<std::string> EncodeExr(const Image& image, const ExrOptions& options) {
  if (CompressesHalfOnly(options.compression) && options.pixel_type != ExrPixelType::kHalf)
    return absl::InvalidArgumentError(
        absl::StrCat(ExrCompressionName(options.compression),
                     " compresses half channels only; float pixels need another compression"));
  std::string bytes;
  const absl::Status status = CoreEncoderSupports(options.compression)
                                  ? EncodeExrChunks(image, options, &bytes)
                                  : EncodeThroughOpenImageIO(image, options, &bytes);
  if (!status.ok()) return status;
  return bytes;
}

absl::Status WriteExrFile(const Image& image, const ExrOptions& options, const std::string& path) {
  auto bytes = EncodeExr(image, options);
  if (!bytes.ok()) return bytes.status();
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (file) file.write(bytes->data(), static_cast<std::streamsize>(bytes->size()));
  if (file) file.close();
  if (!file)
    return absl::InternalError(
        absl::StrCat("cannot write EXR '", path, "': ", std::strerror(errno)));
  return absl::OkStatus();
}

absl::Status WritePngPreview(const Image& image, const std::string& path) {
  std::vector<uint8_t> pixels(static_cast<size_t>(image.width()) * image.height() * 3);
  auto encode = [](float v) {
    v = std::clamp(v, 0.0f, 1.0f);
    const float s = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
    return static_cast<uint8_t>(std::lround(s * 255.0f));
  };
  size_t k = 0;
  for (const Rgba& t : image.texels()) {
    pixels[k++] = encode(t.r);
    pixels[k++] = encode(t.g);
    pixels[k++] = encode(t.b);
  }
  auto out = OIIO::ImageOutput::create(path);
  if (!out) return absl::InternalError(absl::StrCat("cannot create PNG writer for '", path, "'"));
  OIIO::ImageSpec spec(image.width(), image.height(), 3, OIIO::TypeDesc::UINT8);
  if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) ||
      !out->close())
    return absl::InternalError(absl::StrCat("cannot write PNG '", path, "': ", out->geterror()));
  return absl::OkStatus();
}

}  // namespace aperture
