#include "contact_sheet.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "absl/strings/str_cat.h"

namespace aperture {
namespace {

// Digits 0-9 as 3 x 5 bitmaps, one row per 3 bits (most significant bit on the left).
constexpr std::array<std::array<uint8_t, 5>, 10> kDigits = {{
    {7, 5, 5, 5, 7},
    {2, 6, 2, 2, 7},
    {7, 1, 7, 4, 7},
    {7, 1, 7, 1, 7},
    {5, 5, 7, 1, 1},
    {7, 4, 7, 1, 7},
    {7, 4, 7, 5, 7},
    {7, 1, 1, 1, 1},
    {7, 5, 7, 5, 7},
    {7, 5, 7, 1, 7},
}};
constexpr int kScale = 2;  // font pixels per bitmap pixel

uint8_t ToSrgb8(float linear) {
  const float v = std::clamp(linear, 0.0f, 1.0f);
  const float s = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1 / 2.4f) - 0.055f;
  return static_cast<uint8_t>(std::lround(s * 255));
}

class Sheet {
 public:
  Sheet(int width, int height) : width_(width), height_(height), rgb_(size_t(width) * height * 3) {}
  void Set(int x, int y, uint8_t r, uint8_t g, uint8_t b) {
    if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
    uint8_t* p = &rgb_[(size_t(y) * width_ + x) * 3];
    p[0] = r, p[1] = g, p[2] = b;
  }
  // The number in white on a black box, at the top left corner (x, y).
  void Number(size_t n, int x, int y) {
    const std::string text = absl::StrCat(n);
    const int w = static_cast<int>(text.size()) * 4 * kScale + kScale, h = 7 * kScale;
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) Set(x + i, y + j, 0, 0, 0);
    for (size_t c = 0; c < text.size(); ++c) {
      const auto& glyph = kDigits[text[c] - '0'];
      for (int row = 0; row < 5; ++row)
        for (int col = 0; col < 3; ++col)
          if (glyph[row] & (4 >> col))
            for (int j = 0; j < kScale; ++j)
              for (int i = 0; i < kScale; ++i)
                Set(x + kScale + (int(c) * 4 + col) * kScale + i, y + kScale + row * kScale + j,
                    255, 255, 255);
    }
  }
  const uint8_t* data() const { return rgb_.data(); }

 private:
  int width_, height_;
  std::vector<uint8_t> rgb_;
};

}  // namespace

absl::Status WriteContactSheet(const std::vector<std::pair<size_t, std::string>>& frames,
                               const std::string& png_path, int thumbnail_width) {
  if (frames.empty()) return absl::InvalidArgumentError("no frames for a contact sheet");
  // Evenly spaced through the job when there are more than the sheet shows.
  std::vector<std::pair<size_t, std::string>> shown;
  const size_t count = std::min(frames.size(), kMaxThumbnails);
  for (size_t k = 0; k < count; ++k) shown.push_back(frames[k * frames.size() / count]);

  // The first frame that opens gives the thumbnails' aspect.
  int tw = thumbnail_width, th = thumbnail_width * 9 / 16;
  for (const auto& [n, path] : shown) {
    if (auto in = OIIO::ImageInput::open(path)) {
      const OIIO::ImageSpec& spec = in->spec();
      th = std::max(1, static_cast<int>(std::lround(double(tw) * spec.height / spec.width)));
      break;
    }
  }
  const int gap = 4;
  const int columns = std::min<int>(static_cast<int>(shown.size()), 10);
  const int rows = (static_cast<int>(shown.size()) + columns - 1) / columns;
  const int width = columns * (tw + gap) + gap, height = rows * (th + gap) + gap;
  Sheet sheet(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) sheet.Set(x, y, 24, 24, 24);

  for (size_t k = 0; k < shown.size(); ++k) {
    const int x0 = gap + static_cast<int>(k % columns) * (tw + gap);
    const int y0 = gap + static_cast<int>(k / columns) * (th + gap);
    OIIO::ImageBuf frame(shown[k].second);
    OIIO::ImageBuf thumb;
    const bool ok = frame.read(0, 0, true, OIIO::TypeDesc::FLOAT) &&
                    OIIO::ImageBufAlgo::resize(thumb, frame, "box", 0, OIIO::ROI(0, tw, 0, th));
    std::vector<float> pixels(size_t(tw) * th * 3, 0.08f);
    if (ok)
      thumb.get_pixels(OIIO::ROI(0, tw, 0, th, 0, 1, 0, 3), OIIO::TypeDesc::FLOAT, pixels.data());
    for (int y = 0; y < th; ++y)
      for (int x = 0; x < tw; ++x) {
        const float* p = &pixels[(size_t(y) * tw + x) * 3];
        sheet.Set(x0 + x, y0 + y, ToSrgb8(p[0]), ToSrgb8(p[1]), ToSrgb8(p[2]));
      }
    sheet.Number(shown[k].first, x0, y0);
  }

  auto out = OIIO::ImageOutput::create(png_path);
  if (!out) return absl::InternalError(absl::StrCat("cannot write PNG ", png_path));
  const OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
  if (!out->open(png_path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, sheet.data()) ||
      !out->close())
    return absl::InternalError(absl::StrCat("cannot write ", png_path, ": ", out->geterror()));
  return absl::OkStatus();
}

}  // namespace aperture
