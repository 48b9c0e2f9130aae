// The geometry of a channel set around the eye, as a simulator's visual system is checked: a dome
// of black and white 5-degree squares around the eye, seen through the 180 x 40 degree set of
// docs/examples/wrap-180x40.txtpb (three channels turned 60 degrees apart), projected and
// rendered by the engine as the server would (the channel's camera in its proto form).
//  - Every square's corner lands where its analytic direction says: the pixel position the
//    engine projects it to, turned back into a direction by the channel's own definition (its
//    yaw and frustum, in closed form, after the eye's yaw and pitch), is the corner's direction;
//    errors printed in degrees. Also for five 36-degree channels, and for an eye turned and
//    pitched, whose channels turn with it (the view offset applies after the eye's orientation).
//  - Neighbouring channels meet with neither gap nor overlap: the directions through the last
//    pixel column of one channel and the first of the next are the two half pixels apart that
//    meet at the shared frustum side, row by row; and rendered with the 2 x 2 box filter, the
//    two columns at a seam (which lies on a square's edge) are each three quarters their own
//    square and one quarter the next one's beyond the seam: the squares continue across it, and
//    a seam off the square's edge by a hundredth of a pixel either way would show.
//  - A set of planar off-axis tiles (--channels N) is one wide render, cut.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <utility>

#include "frame/camera_proto.h"
#include "raster/projection.h"
#include "render/frame_renderer.h"
#include "scene/scene_builder.h"
#include "scene/shading.h"
#include "sim_channels.h"
#include "support/checker_dome.h"

namespace aperture {
namespace {

using testing::AngleBetweenDeg;
using testing::ChannelView;
using testing::DomeAngles;
using testing::DomeDirection;
using testing::DomeWhite;
using testing::InsideSquare;
using testing::kDomeSquareDeg;

double Deg(double radians) { return radians * 180 / M_PI; }

// The channel's closed-form mapping from its definition and the eye's yaw and pitch.
ChannelView ViewOf(const SimChannel& c, const v1::Camera& eye = v1::Camera()) {
  ChannelView view(c.view_offset.yaw_deg(), c.frustum, static_cast<int>(c.width),
                   static_cast<int>(c.height));
  view.eye_yaw_deg = eye.yaw_deg();
  view.eye_pitch_deg = eye.pitch_deg();
  return view;
}

// The engine's camera of a channel, as the server builds it from the request's camera.
Camera CameraOf(const SimChannel& channel, const v1::Camera& eye = v1::Camera()) {
  auto camera = CameraFromProto(ChannelCamera(eye, channel));
  EXPECT_TRUE(camera.ok()) << camera.status();
  return *camera;
}

// A channel set seen from an eye.
struct SetCase {
  std::string name;
  std::vector<SimChannel> channels;
  v1::Camera eye;  // at the origin, its yaw and pitch
};

class ChannelGeometry : public ::testing::Test {
 protected:
  void SetUp() override {
    auto channels = ParseChannels(APERTURE_EXAMPLES_DIR "/wrap-180x40.txtpb", v1::Camera(), 0, 0);
    ASSERT_TRUE(channels.ok()) << channels.status();
    channels_ = *channels;
    auto scene = BuildScene(testing::CheckerDome());
    ASSERT_TRUE(scene.ok()) << scene.status();
    scene_ = std::move(*scene);
  }
  Camera ChannelCameraK(size_t k) const { return CameraOf(channels_[k]); }
  // The example file's set; five 36-degree channels 42 high at their centres (20 degrees up at
  // their sides), whose seams at +-18 and +-54 degrees fall inside squares; and the example set
  // on an eye turned 5 degrees right and pitched 7 up, whose channels turn with it.
  std::vector<SetCase> Sets() const {
    auto five = ParseChannels("5x36x42", v1::Camera(), 400, 500);
    EXPECT_TRUE(five.ok()) << five.status();
    v1::Camera turned;
    turned.set_yaw_deg(-5);
    turned.set_pitch_deg(7);
    return {{"wrap-180x40.txtpb", channels_, v1::Camera()},
            {"5x36x42 at 400x500", *five, v1::Camera()},
            {"wrap-180x40.txtpb, eye yaw -5 pitch 7", channels_, turned}};
  }
  std::vector<SimChannel> channels_;
  Scene scene_;
};

TEST_F(ChannelGeometry, EverySquaresCornersLandOnTheirAnalyticDirections) {
  for (const auto& [set_name, channels, eye] : Sets()) {
    std::set<std::pair<int, int>> found;     // corners (azimuth, elevation) in units of 5 degrees
    std::set<std::pair<int, int>> expected;  // those whose direction lies inside a frame
    double worst = 0;
    size_t corners = 0;
    for (size_t k = 0; k < channels.size(); ++k) {
      const ChannelView map = ViewOf(channels[k], eye);
      const FrameGeometry geo =
          ProjectScene(scene_, CameraOf(channels[k], eye), map.width, map.height, /*margin=*/0);
      for (int i = -19; i <= 19; ++i)
        for (int j = -6; j <= 6; ++j) {
          double x, y;
          const double eps = 1e-6;  // pixels: a corner on the frame's side may go either way
          if (map.FramePoint(DomeDirection(i * kDomeSquareDeg, j * kDomeSquareDeg), &x, &y) &&
              x > eps && x < map.width - eps && y > eps && y < map.height - eps)
            expected.insert({i, j});
        }
      for (const ScreenPolygon& sp : geo.polygons)
        for (const Vec2& v : sp.vertices) {
          const Vec3 d = map.At(v.x, v.y);
          const auto [a, e] = DomeAngles(d);
          const int i = static_cast<int>(std::lround(a / kDomeSquareDeg));
          const int j = static_cast<int>(std::lround(e / kDomeSquareDeg));
          const double error =
              AngleBetweenDeg(d, DomeDirection(i * kDomeSquareDeg, j * kDomeSquareDeg));
          // Far below the rule's degree; a vertex where the frame's side cuts a square's edge can
          // lie a few thousandths of a degree from a corner just outside the frame.
          if (error < 1e-6) {
            worst = std::max(worst, error);
            ++corners;
            found.insert({i, j});
          } else {
            // Not a corner: where the frame's sides cut a square.
            const double to_side =
                std::min(std::min(v.x, map.width - v.x), std::min(v.y, map.height - v.y));
            EXPECT_LT(std::abs(to_side), 1e-6)
                << set_name << " channel " << k << " at " << v.x << "," << v.y;
          }
        }
    }
    // Every corner inside a frame was found there; looking ahead, the whole 180 x 40 field is.
    for (const auto& [i, j] : expected)
      EXPECT_TRUE(found.count({i, j})) << set_name << ": " << i * 5 << "," << j * 5;
    if (eye.yaw_deg() == 0 && eye.pitch_deg() == 0) {
      for (int i = -18; i <= 18; ++i)
        for (int j = -4; j <= 4; ++j) {
          EXPECT_TRUE(found.count({i, j})) << set_name << ": " << i * 5 << "," << j * 5;
        }
    }
    EXPECT_GT(expected.size(), 250u) << set_name;
    std::printf(
        "%s: corner vertices %zu (%zu distinct corners), largest error %.3g degrees (the "
        "rule: +-1)\n",
        set_name.c_str(), corners, found.size(), worst);
  }
}

TEST_F(ChannelGeometry, NeighbouringChannelsMeetWithNeitherGapNorOverlap) {
  for (const auto& [set_name, channels, eye] : Sets()) {
    double worst = 0, pixel_deg = 0;
    for (size_t k = 0; k + 1 < channels.size(); ++k) {
      const Camera left = CameraOf(channels[k], eye), right = CameraOf(channels[k + 1], eye);
      const int w = static_cast<int>(channels[k].width), h = static_cast<int>(channels[k].height);
      ASSERT_EQ(channels[k + 1].height, channels[k].height);
      const FrustumTangents fl = ResolveFrustum(left, w, h), fr = ResolveFrustum(right, w, h);
      const double dx = (fl.right - fl.left) / w;
      for (int y = 0; y < h; ++y) {
        // The engine's rays through the last column of channel k and the first of channel k + 1.
        const Vec3 last = Normalize(left.Orientation() * CameraRay(fl, w, h, w - 0.5, y + 0.5));
        const Vec3 first = Normalize(right.Orientation() * CameraRay(fr, w, h, 0.5, y + 0.5));
        // Each is half a pixel from the shared side plane x + r z = 0 (normal (1, 0, r)): together
        // one edge pixel's angle, measured across the seam.
        const Vec3 p{fl.right - dx / 2, fl.top - (fl.top - fl.bottom) * (y + 0.5) / h, -1};
        const double half = Deg(std::asin(dx / 2 / (Length(p) * std::hypot(1.0, fl.right))));
        worst = std::max(worst, std::abs(AngleBetweenDeg(last, first) - 2 * half));
        pixel_deg = 2 * half;
      }
    }
    std::printf("%s: seam columns one pixel's angle (%.5f degrees) apart within %.3g degrees\n",
                set_name.c_str(), pixel_deg, worst);
    EXPECT_LT(worst, 1e-9) << set_name;
  }
}

TEST_F(ChannelGeometry, RenderedSquaresContinueAcrossTheSeams) {
  RenderSettings settings;
  settings.aa = AntiAliasing::kBox2;  // reaches half a pixel past the frame's sides
  std::vector<Image> frames;
  for (size_t k = 0; k < channels_.size(); ++k) {
    settings.width = static_cast<int>(channels_[k].width);
    settings.height = static_cast<int>(channels_[k].height);
    auto frame = RenderFrame(scene_, ChannelCameraK(k), settings);
    ASSERT_TRUE(frame.ok()) << frame.status();
    frames.push_back(std::move(frame->image));
  }
  // Pixels whose centre is well inside a square (a quarter degree from its edges, about two
  // pixels; the sides of constant elevation are chords, at most 0.02 degrees off the parallels)
  // show that square's colour.
  auto inside = [](double degrees) { return InsideSquare(degrees, 0.25); };
  size_t checked = 0, wrong = 0;
  for (size_t k = 0; k < channels_.size(); ++k) {
    const ChannelView map = ViewOf(channels_[k]);
    for (int y = 0; y < map.height; ++y)
      for (int x = 0; x < map.width; ++x) {
        const auto [a, e] = DomeAngles(map.At(x + 0.5, y + 0.5));
        if (!inside(a) || !inside(e)) continue;
        ++checked;
        const float expected = DomeWhite(a, e) ? 1.0f : 0.0f;
        wrong += std::abs(frames[k].at(x, y).r - expected) > 1e-4f;
      }
  }
  EXPECT_EQ(wrong, 0u) << "of " << checked;
  // At each seam (azimuth +-30, a square's edge, and the meridian plane the two channels' sides
  // share) the 2 x 2 box of the last column reaches half a pixel into the next square: 3/4 its
  // own square's colour, 1/4 the next one's; the first column of the next channel likewise.
  double worst = 0;
  size_t rows = 0;
  for (size_t k = 0; k + 1 < channels_.size(); ++k) {
    const ChannelView map = ViewOf(channels_[k]);
    for (int y = 0; y < map.height; ++y) {
      const auto [a, e] = DomeAngles(map.At(map.width, y + 0.5));
      if (!inside(e)) continue;
      ++rows;
      const float left = frames[k].at(map.width - 1, y).r, right = frames[k + 1].at(0, y).r;
      const double own = DomeWhite(a + 1, e) ? 1 : 0, next = 1 - own;
      worst = std::max({worst, std::abs(left - (0.75 * own + 0.25 * next)),
                        std::abs(right - (0.75 * next + 0.25 * own))});
    }
  }
  std::printf("seam columns: %zu rows, largest departure from 3/4 own square, 1/4 the next %.3g\n",
              rows, worst);
  EXPECT_GT(rows, 400u);
  EXPECT_LT(worst, 1e-4);
}

TEST_F(ChannelGeometry, PlanarTilesAreOneWideRenderCut) {
  v1::Camera eye;
  eye.set_vertical_fov_deg(40);
  eye.set_pitch_deg(3);
  const int w = 96, h = 64, n = 3;
  auto tiles = ParseChannels("3", eye, w, h);
  ASSERT_TRUE(tiles.ok()) << tiles.status();
  RenderSettings settings;
  settings.width = w, settings.height = h;
  // The one wide view: three tiles' width, the same height.
  v1::Camera wide = eye;
  const double half_h = std::tan(20 * M_PI / 180), half_w = n * half_h * w / h;
  wide.mutable_frustum()->set_left_deg(-Deg(std::atan(half_w)));
  wide.mutable_frustum()->set_right_deg(Deg(std::atan(half_w)));
  wide.mutable_frustum()->set_bottom_deg(-20);
  wide.mutable_frustum()->set_top_deg(20);
  RenderSettings wide_settings = settings;
  wide_settings.width = n * w;
  auto wide_camera = CameraFromProto(wide);
  ASSERT_TRUE(wide_camera.ok());
  auto whole = RenderFrame(scene_, *wide_camera, wide_settings);
  ASSERT_TRUE(whole.ok()) << whole.status();
  double worst = 0;
  for (int k = 0; k < n; ++k) {
    auto camera = CameraFromProto(ChannelCamera(eye, (*tiles)[static_cast<size_t>(k)]));
    ASSERT_TRUE(camera.ok()) << camera.status();
    auto part = RenderFrame(scene_, *camera, settings);
    ASSERT_TRUE(part.ok()) << part.status();
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const Rgba a = part->image.at(x, y), b = whole->image.at(k * w + x, y);
        worst = std::max({worst, std::abs(a.r - b.r) + 0.0, std::abs(a.a - b.a) + 0.0});
      }
  }
  std::printf("planar tiles against one wide render: largest difference %.3g\n", worst);
  EXPECT_LT(worst, 1e-4);
}

}  // namespace
}  // namespace aperture
