#include "texture/image_file.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include "absl/strings/str_cat.h"

namespace aperture {
namespace {

// OpenImageIO picks a reader by file name; for bytes in memory we name the format by its magic.
const char* FormatNameForMagic(std::span<const uint8_t> b) {
  auto starts = [&](std::initializer_list<uint8_t> magic) {
    if (b.size() < magic.size()) return false;
    return std::equal(magic.begin(), magic.end(), b.begin());
  };
  if (starts({0x89, 'P', 'N', 'G'})) return "memory.png";
  if (starts({0x76, 0x2f, 0x31, 0x01})) return "memory.exr";
  if (starts({0xff, 0xd8, 0xff})) return "memory.jpg";
  if (starts({'I', 'I', 42, 0}) || starts({'M', 'M', 0, 42})) return "memory.tif";
  return nullptr;
}

absl::Status CheckSpec(const OIIO::ImageSpec& spec, const std::string& what) {
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    return absl::InvalidArgumentError(absl::StrCat(what, ": image has no pixels"));
  if (int64_t{spec.width} * spec.height > kMaxImageTexels)
    return absl::InvalidArgumentError(absl::StrCat(
        what, ": image is ", spec.width, "x", spec.height, ", above the limit of ", kMaxImageTexels,
        " texels (8192 x 8192) for a raster texture; pack palette maps as .apv"));
  return absl::OkStatus();
}

// OpenEXR's C++ header reader allocates what an attribute's size field says: a 100-byte file can
// ask for 1.9 GB (found by tests/fuzz/engine/upload_fuzzer). So before OpenImageIO sees an EXR,
// its header is walked the way that reader tokenizes it (Header::readFrom: a name and a type,
// each read up to its NUL or Name::MAX_LENGTH + 1 = 256 characters, whatever the long-names flag;
// an int32 size; the value; an empty name ends a header, an empty header the parts of a
// multi-part file), and every size must fit in the bytes that follow.
absl::Status CheckExrAttributeSizes(std::span<const uint8_t> b) {
  auto fail = [](const std::string& why) {
    return absl::InvalidArgumentError(absl::StrCat("EXR header: ", why));
  };
  if (b.size() < 8) return fail("truncated");
  const uint32_t version = b[4] | (b[5] << 8) | (b[6] << 16) | (uint32_t{b[7]} << 24);
  constexpr size_t max_name = 255;
  const bool multipart = (version & 0x1000) != 0;
  size_t pos = 8;
  auto token = [&](std::string* out) {
    for (size_t k = 0; k <= max_name; ++k) {
      if (pos >= b.size()) return false;
      const char c = static_cast<char>(b[pos++]);
      if (c == 0) return true;
      *out += c;
    }
    return true;
  };
  for (int part = 0;; ++part) {
    for (int attribute = 0;; ++attribute) {
      if (pos >= b.size()) return fail("truncated");
      if (b[pos] == 0) {
        ++pos;
        break;
      }
      std::string name, type;
      if (!token(&name) || !token(&type) || pos + 4 > b.size()) return fail("truncated");
      const int32_t size = static_cast<int32_t>(b[pos] | (b[pos + 1] << 8) | (b[pos + 2] << 16) |
                                                (uint32_t{b[pos + 3]} << 24));
      pos += 4;
      if (size < 0 || static_cast<uint64_t>(size) > b.size() - pos)
        return fail(absl::StrCat("attribute ", attribute, " of part ", part, " declares ", size,
                                 " bytes, more than the file holds"));
      pos += static_cast<size_t>(size);
    }
    if (!multipart) return absl::OkStatus();
    if (pos >= b.size()) return fail("truncated");
    if (b[pos] == 0) return absl::OkStatus();  // the empty header after the last part
  }
}

// OpenImageIO 2.4's memory reader reads at whatever offset it is given: an EXR whose chunk table
// points before the start of the bytes made it read outside them (the upload fuzz target found
// it). This one reads nothing there, and the decoder then reports a truncated file.
class BoundedMemReader final : public OIIO::Filesystem::IOMemReader {
 public:
  explicit BoundedMemReader(std::span<const uint8_t> bytes)
      : IOMemReader(bytes.data(), bytes.size()) {}
  size_t pread(void* buf, size_t size, int64_t offset) override {
    const int64_t end = static_cast<int64_t>(m_buf.size());
    if (offset < 0 || offset > end) return 0;
    return IOMemReader::pread(buf, std::min(size, static_cast<size_t>(end - offset)), offset);
  }
  size_t read(void* buf, size_t size) override {
    const size_t n = pread(buf, size, m_pos);
    m_pos += static_cast<int64_t>(n);
    return n;
  }
};

// An encoded image in memory opened for reading (its header read), or why not.
absl::StatusOr<std::unique_ptr<OIIO::ImageInput>> OpenInMemory(
    std::span<const uint8_t> bytes, OIIO::Filesystem::IOMemReader& reader) {
  const char* name = FormatNameForMagic(bytes);
  if (name == nullptr)
    return absl::InvalidArgumentError(
        "encoded texture is not PNG, JPEG, EXR or TIFF (unknown magic bytes)");
  if (std::strcmp(name, "memory.exr") == 0)
    if (auto header = CheckExrAttributeSizes(bytes); !header.ok()) return header;
  OIIO::ImageSpec config;
  void* proxy = &reader;
  config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  config.attribute("oiio:UnassociatedAlpha", 1);  // premultiplied in float by ReadFrom
  auto in = OIIO::ImageInput::open(name, &config, &reader);
  if (!in)
    return absl::InvalidArgumentError(
        absl::StrCat("cannot decode encoded texture: ", OIIO::geterror()));
  return in;
}

absl::StatusOr<Image> ReadFrom(OIIO::ImageInput* in, const std::string& what) {
  const OIIO::ImageSpec& spec = in->spec();
  if (auto s = CheckSpec(spec, what); !s.ok()) return s;
  const int channels = spec.nchannels;
  // Texels carry associated (premultiplied) alpha, the convention of EXR and of OpenImageIO. A
  // format that stores unassociated alpha (PNG) is read as it is and premultiplied here in float:
  // OpenImageIO's own premultiplication happens in the file's 8 bits and loses the colour of
  // faint texels.
  const bool unassociated =
      (channels == 2 || channels >= 4) && spec.get_int_attribute("oiio:UnassociatedAlpha", 0) != 0;
  std::vector<float> pixels(static_cast<size_t>(spec.width) * spec.height * channels);
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels.data()))
    return absl::InvalidArgumentError(absl::StrCat(what, ": ", in->geterror()));
  Image image(spec.width, spec.height);
  for (int y = 0; y < spec.height; ++y) {
    for (int x = 0; x < spec.width; ++x) {
      const float* p = &pixels[(static_cast<size_t>(y) * spec.width + x) * channels];
      Rgba& t = image.at(x, y);
      if (channels >= 3) {
        t = {p[0], p[1], p[2], channels >= 4 ? p[3] : 1.0f};
      } else {
        t = {p[0], p[0], p[0], channels == 2 ? p[1] : 1.0f};
      }
      if (unassociated) t.r *= t.a, t.g *= t.a, t.b *= t.a;
    }
  }
  return image;
}

}  // namespace

absl::StatusOr<Image> LoadImageFile(const std::string& path) {
  if (!OIIO::Filesystem::exists(path))
    return absl::NotFoundError(absl::StrCat("texture file '", path, "' does not exist"));
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);  // premultiplied in float by ReadFrom
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in)
    return absl::InvalidArgumentError(
        absl::StrCat("cannot read texture file '", path, "': ", OIIO::geterror()));
  return ReadFrom(in.get(), absl::StrCat("texture file '", path, "'"));
}

absl::StatusOr<Image> DecodeImage(std::span<const uint8_t> bytes) {
  BoundedMemReader reader(bytes);
  auto in = OpenInMemory(bytes, reader);
  if (!in.ok()) return in.status();
  return ReadFrom(in->get(), "encoded texture");
}

absl::StatusOr<ImageHeader> ReadImageHeader(std::span<const uint8_t> bytes) {
  BoundedMemReader reader(bytes);
  auto in = OpenInMemory(bytes, reader);
  if (!in.ok()) return in.status();
  const OIIO::ImageSpec& spec = (*in)->spec();
  if (auto s = CheckSpec(spec, "encoded texture"); !s.ok()) return s;
  return ImageHeader{spec.width, spec.height, spec.nchannels, (*in)->format_name()};
}

Image ResizeToPowerOfTwo(const Image& image) {
  if (IsPowerOfTwo(image.width()) && IsPowerOfTwo(image.height())) return image;
  auto next = [](int n) {
    int p = 1;
    while (p < n) p *= 2;
    return p;
  };
  OIIO::ImageSpec src_spec(image.width(), image.height(), 4, OIIO::TypeDesc::FLOAT);
  OIIO::ImageBuf src(src_spec, const_cast<Rgba*>(image.texels().data()));
  OIIO::ROI roi(0, next(image.width()), 0, next(image.height()), 0, 1, 0, 4);
  OIIO::ImageBuf dst = OIIO::ImageBufAlgo::resize(src, "", 0.0f, roi);
  Image out(roi.width(), roi.height());
  dst.get_pixels(roi, OIIO::TypeDesc::FLOAT, out.texels().data());
  return out;
}

}  // namespace aperture
