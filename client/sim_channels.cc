#include "sim_channels.h"

#include <google/protobuf/io/tokenizer.h>
#include <google/protobuf/text_format.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <regex>

#include "absl/strings/str_cat.h"

namespace aperture {
namespace {

double Tan(double degrees) { return std::tan(degrees * M_PI / 180); }
double Atan(double tangent) { return std::atan(tangent) * 180 / M_PI; }

constexpr int kMaxChannels = 16;

absl::Status Bad(const std::string& where, const std::string& field, double value,
                 const std::string& range) {
  return absl::InvalidArgumentError(
      absl::StrCat(where, field, " is ", value, "; it must be ", range));
}

// A symmetric field: W degrees wide, V high (0: square pixels at width x height).
v1::Frustum SymmetricFrustum(double horizontal_deg, double vertical_deg, uint32_t width,
                             uint32_t height) {
  const double half_v = vertical_deg > 0
                            ? vertical_deg / 2
                            : Atan(Tan(horizontal_deg / 2) * height / static_cast<double>(width));
  v1::Frustum f;
  f.set_left_deg(-horizontal_deg / 2);
  f.set_right_deg(horizontal_deg / 2);
  f.set_bottom_deg(-half_v);
  f.set_top_deg(half_v);
  return f;
}

// N channels of W degrees (V high) turned around the eye, left to right.
absl::StatusOr<std::vector<SimChannel>> RingChannels(int n, double w, double v, uint32_t width,
                                                     uint32_t height) {
  const std::string where = "--channels ";
  if (n < 1 || n > kMaxChannels)
    return Bad(where, "channel count", n, absl::StrCat("in 1..", kMaxChannels));
  if (!(w > 0 && w < 178)) return Bad(where, "channel width", w, "in (0, 178) degrees");
  if (n * w > 360 + 1e-9) return Bad(where, "total width", n * w, "at most 360 degrees");
  if (!(v >= 0 && v < 178)) return Bad(where, "channel height", v, "in (0, 178) degrees");
  std::vector<SimChannel> channels(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) {
    SimChannel& c = channels[static_cast<size_t>(k)];
    c.name = absl::StrCat("channel ", k);
    // Positive yaw turns left (DESIGN.md): the first channel is the leftmost.
    c.view_offset.set_yaw_deg(((n - 1) / 2.0 - k) * w);
    c.has_frustum = true;
    c.frustum = SymmetricFrustum(w, v, width, height);
    c.width = width, c.height = height;
  }
  return channels;
}

class CollectFirstError : public google::protobuf::io::ErrorCollector {
 public:
  void AddError(int line, int column, const std::string& message) override {
    if (error.empty()) error = absl::StrCat(line + 1, ":", column + 1, ": ", message);
  }
  std::string error;
};

absl::StatusOr<std::vector<SimChannel>> ChannelsFromFile(const std::string& path, uint32_t width,
                                                         uint32_t height) {
  std::ifstream in(path);
  if (!in)
    return absl::InvalidArgumentError(absl::StrCat(
        "--channels ", path, " is neither N, NxW, NxWxV nor a readable channel-set file"));
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  v1::ChannelSet set;
  google::protobuf::TextFormat::Parser parser;
  CollectFirstError errors;
  parser.RecordErrorsTo(&errors);
  if (!parser.ParseFromString(text, &set))
    return absl::InvalidArgumentError(absl::StrCat(path, ":", errors.error));
  return ChannelsFromSet(set, path, width, height);
}

}  // namespace

absl::StatusOr<std::vector<v1::Frustum>> ChannelFrusta(const v1::Camera& base, int channels,
                                                       uint32_t width, uint32_t height) {
  if (channels < 1 || channels > kMaxChannels)
    return absl::InvalidArgumentError(
        absl::StrCat("--channels ", channels, " must be 1..", kMaxChannels));
  // The base view in tangents of the view plane at distance 1.
  double left, right, bottom, top;
  if (base.has_frustum()) {
    left = Tan(base.frustum().left_deg()), right = Tan(base.frustum().right_deg());
    bottom = Tan(base.frustum().bottom_deg()), top = Tan(base.frustum().top_deg());
  } else {
    const double fov = base.vertical_fov_deg() > 0 ? base.vertical_fov_deg() : 60;
    top = Tan(fov / 2), bottom = -top;
    right = top * width / height, left = -right;
  }
  const double w = right - left, centre = (left + right) / 2;
  const double first = centre - channels * w / 2;
  std::vector<v1::Frustum> frusta;
  for (int k = 0; k < channels; ++k) {
    v1::Frustum f;
    f.set_left_deg(Atan(first + k * w));
    f.set_right_deg(Atan(first + (k + 1) * w));
    f.set_bottom_deg(Atan(bottom));
    f.set_top_deg(Atan(top));
    frusta.push_back(f);
  }
  return frusta;
}

absl::StatusOr<std::vector<SimChannel>> ChannelsFromSet(const v1::ChannelSet& set,
                                                        const std::string& source, uint32_t width,
                                                        uint32_t height) {
  const int n = set.channels_size();
  if (n < 1 || n > kMaxChannels)
    return Bad(source + ": ", "the number of channels", n, absl::StrCat("1..", kMaxChannels));
  std::vector<SimChannel> channels;
  for (int k = 0; k < n; ++k) {
    const v1::DisplayChannel& d = set.channels(k);
    const std::string where = absl::StrCat(source, ": channels[", k, "].");
    SimChannel c;
    c.name = d.name().empty() ? absl::StrCat("channel ", k) : d.name();
    c.width = d.width() != 0 ? d.width() : width;
    c.height = d.height() != 0 ? d.height() : height;
    c.server = d.server();
    const v1::ViewOffset& o = d.view_offset();
    for (const auto& [field, value] : {std::pair{"view_offset.yaw_deg", o.yaw_deg()},
                                       std::pair{"view_offset.pitch_deg", o.pitch_deg()},
                                       std::pair{"view_offset.roll_deg", o.roll_deg()}})
      if (!std::isfinite(value)) return Bad(where, field, value, "finite");
    c.view_offset = o;
    if (d.has_frustum() == (d.horizontal_fov_deg() != 0))
      return absl::InvalidArgumentError(
          absl::StrCat(where, "horizontal_fov_deg or frustum: one of them, not both or neither"));
    if (d.has_frustum()) {
      const v1::Frustum& f = d.frustum();
      for (const auto& [field, value] : {std::pair{"frustum.left_deg", f.left_deg()},
                                         std::pair{"frustum.right_deg", f.right_deg()},
                                         std::pair{"frustum.bottom_deg", f.bottom_deg()},
                                         std::pair{"frustum.top_deg", f.top_deg()}})
        if (!(std::abs(value) < 89)) return Bad(where, field, value, "within (-89, 89) degrees");
      if (f.left_deg() >= f.right_deg())
        return Bad(where, "frustum.left_deg", f.left_deg(), "less than frustum.right_deg");
      if (f.bottom_deg() >= f.top_deg())
        return Bad(where, "frustum.bottom_deg", f.bottom_deg(), "less than frustum.top_deg");
      c.frustum = f;
    } else {
      if (!(d.horizontal_fov_deg() > 0 && d.horizontal_fov_deg() < 178))
        return Bad(where, "horizontal_fov_deg", d.horizontal_fov_deg(), "in (0, 178) degrees");
      if (!(d.vertical_fov_deg() >= 0 && d.vertical_fov_deg() < 178))
        return Bad(where, "vertical_fov_deg", d.vertical_fov_deg(),
                   "in (0, 178) degrees (0: square pixels)");
      c.frustum = SymmetricFrustum(d.horizontal_fov_deg(), d.vertical_fov_deg(), c.width, c.height);
    }
    c.has_frustum = true;
    channels.push_back(std::move(c));
  }
  return channels;
}

absl::StatusOr<std::vector<SimChannel>> ParseChannels(const std::string& spec,
                                                      const v1::Camera& base, uint32_t width,
                                                      uint32_t height) {
  static const std::regex planar("[0-9]+");
  static const std::regex ring("([0-9]+)x([0-9.]+)(?:x([0-9.]+))?");
  std::smatch m;
  if (std::regex_match(spec, planar)) {
    const int n = static_cast<int>(std::min<long>(std::stol(spec.substr(0, 6)), 1000));
    auto frusta = ChannelFrusta(base, n, width, height);
    if (!frusta.ok()) return frusta.status();
    std::vector<SimChannel> channels(static_cast<size_t>(n));
    for (int k = 0; k < n; ++k) {
      SimChannel& c = channels[static_cast<size_t>(k)];
      c.name = absl::StrCat("channel ", k);
      // One channel keeps the eye's own view.
      c.has_frustum = n > 1;
      c.frustum = (*frusta)[static_cast<size_t>(k)];
      c.width = width, c.height = height;
    }
    return channels;
  }
  if (std::regex_match(spec, m, ring)) {
    const int n = static_cast<int>(std::min<long>(std::stol(m[1].str().substr(0, 6)), 1000));
    const double w = std::strtod(m[2].str().c_str(), nullptr);
    const double v = m[3].matched ? std::strtod(m[3].str().c_str(), nullptr) : 0;
    if (m[3].matched && !(v > 0)) return Bad("--channels ", "channel height", v, "positive");
    return RingChannels(n, w, v, width, height);
  }
  return ChannelsFromFile(spec, width, height);
}

void AssignServers(std::vector<SimChannel>& channels, const std::vector<std::string>& servers,
                   const std::string& fallback) {
  for (size_t k = 0; k < channels.size(); ++k)
    if (channels[k].server.empty())
      channels[k].server = servers.empty() ? fallback : servers[k % servers.size()];
}

v1::Camera ChannelCamera(const v1::Camera& eye, const SimChannel& channel) {
  v1::Camera camera = eye;
  *camera.mutable_view_offset() = channel.view_offset;
  if (channel.has_frustum) *camera.mutable_frustum() = channel.frustum;
  return camera;
}

}  // namespace aperture
