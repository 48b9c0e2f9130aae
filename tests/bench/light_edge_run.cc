#include "light_edge_run.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "light_measure.h"
#include "scene/scene_builder.h"
#include "support/footprint_clip.h"

namespace aperture {
namespace {

constexpr double kLightDepth = 1000, kWallDepth = 100, kEye = 2, kSlopeDeg = 20;
// The light's energy (white: its luminance) at the first camera: below the bloom, so the
// footprint keeps its least size, 1.5 px.
constexpr double kWantedEnergy = 1.5;

v1::Vec3 ProtoVec(const Vec3& v) {
  v1::Vec3 out;
  out.set_x(v.x);
  out.set_y(v.y);
  out.set_z(v.z);
  return out;
}

// The screen polygon of a quad wholly in front of the camera.
std::vector<Vec2> ProjectQuad(const Vec3 (&corners)[4], const FrameView& v) {
  std::vector<Vec2> out;
  for (const Vec3& c : corners) {
    const Vec3 p = v.to_camera * (c - v.camera.position);
    out.push_back({(p.x / -p.z - v.t.left) / v.sx, (v.t.top - p.y / -p.z) / v.sy});
  }
  return out;
}

double LargestStep(const std::vector<double>& e) {
  double s = 0;
  for (size_t k = 1; k < e.size(); ++k) s = std::max(s, std::abs(e[k] - e[k - 1]));
  return s;
}

}  // namespace

absl::Status RunEdge(LightPointPeer& peer, const EdgeRunOptions& o, bool* passed) {
  const int width = o.width, height = o.height;
  const double f = height / 2.0 / std::tan(Radians(30));  // pixels per unit tangent (60 degrees)
  // The camera's step: the wall's parallax against the light's moves the edge step_px a frame.
  const double dx = o.step_px / (f * (1 / kWallDepth - 1 / kLightDepth));
  const Vec3 light_at{0.37, kEye + 0.13, -kLightDepth};
  // The wall's edge crosses the light's line of sight halfway through the run: at the first
  // frame it is half the travel right of the light.
  const double row_y = kEye + 0.13 * kWallDepth / kLightDepth;
  const double travel = o.step_px * o.frames;
  const double tan_slope = std::tan(Radians(kSlopeDeg));
  const double xe =
      kWallDepth * (light_at.x / kLightDepth + 0.5 * travel / f) - (row_y - kEye) * tan_slope;
  // The wall: its slanted left edge, 15 m of wall to the right of it, 10 m high around the eye.
  const Vec3 wall[4] = {{xe - 5 * tan_slope, kEye - 5, -kWallDepth},
                        {xe + 15, kEye - 5, -kWallDepth},
                        {xe + 15, kEye + 5, -kWallDepth},
                        {xe + 5 * tan_slope, kEye + 5, -kWallDepth}};
  v1::Scene proto;
  proto.set_name("light behind an edge");
  v1::Material& grey = *proto.add_materials();
  grey.set_id("wall");
  grey.set_unlit(true);
  grey.mutable_base_color()->set_r(0.2f);
  grey.mutable_base_color()->set_g(0.2f);
  grey.mutable_base_color()->set_b(0.2f);
  v1::Mesh& mesh = *proto.add_meshes();
  mesh.set_id("wall");
  mesh.set_material_id("wall");
  v1::Polygon& quad = *mesh.add_polygons();
  for (const Vec3& c : wall) *quad.add_vertices() = ProtoVec(c);
  Camera camera;
  camera.position = {0, kEye, 0};
  {
    // The intensity that gives kWantedEnergy at the first camera.
    v1::Scene probe = proto;
    v1::LightPoint& lp = *probe.add_lights();
    *lp.mutable_position() = ProtoVec(light_at);
    lp.set_intensity_cd(1000);
    auto built = BuildScene(probe);
    if (!built.ok()) return built.status();
    const LightView lv =
        LookAt(*built, built->lights.lights.front(), FrameView(camera, width, height));
    v1::LightPoint& light = *proto.add_lights();
    *light.mutable_position() = ProtoVec(light_at);
    light.set_intensity_cd(1000 * kWantedEnergy / lv.energy);
  }
  auto scene = BuildScene(proto);
  if (!scene.ok()) return scene.status();
  Scene dark = *scene;
  dark.lights.lights.clear();
  const PointLight light = scene->lights.lights.front();
  if (!peer.Resize(width, height))
    return absl::InternalError(absl::StrCat("llvmpipe's buffers of ", width, "x", height));
  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.aa = o.aa;
  settings.threads = 1;
  ApertureLightProbe probe(*scene, dark, settings);

  std::printf(
      "\nedge, %dx%d: a light 1 km away (S = %.2f, footprint 1.5 px) behind the edge of a wall "
      "100 m away, slanted %g degrees, the edge moving %.3g px a frame across it for %d frames; "
      "energy / analytic per frame%s\n\n| frame | visible share (analytic) | Aperture %s | "
      "llvmpipe 1x | llvmpipe 4x MSAA |\n|---:|---:|---:|---:|---:|\n",
      width, height, kWantedEnergy, kSlopeDeg, o.step_px, o.frames,
      o.print_every > 1 ? absl::StrCat(", every ", o.print_every, "th frame shown").c_str() : "",
      AntiAliasingName(o.aa));
  std::vector<double> share, aperture, gl1, gl4;
  for (int k = 0; k < o.frames; ++k) {
    camera.position = {k * dx, kEye, 0};
    const FrameView view(camera, width, height);
    const LightView lv = LookAt(*scene, light, view, 2.5);
    if (!lv.inside || lv.footprint_px != 0.75)
      return absl::InternalError(
          absl::StrCat("the edge light left the frame or bloomed at frame ", k));
    share.push_back(
        testing::VisibleFootprintShare(lv.x, lv.y, lv.footprint_px, ProjectQuad(wall, view)));
    auto sample = probe.Measure(light, camera, lv.window, true);
    if (!sample.ok()) return sample.status();
    aperture.push_back(sample->image.sum / (lv.energy * Luminance(light.color)));
    // llvmpipe: the wall, then the points depth tested against it; less the wall alone.
    peer.SetCamera(camera);
    for (bool msaa : {false, true}) {
      peer.Begin(msaa, lv.window);
      peer.DrawQuad(wall, 0.2f);
      peer.End(lv.window);
      const std::vector<double> without = peer.WindowLuminance(lv.window);
      const PeerLight pl = PeerLightOf(light, lv, camera.position, o.peer_min_size);
      peer.Begin(msaa, lv.window);
      peer.DrawQuad(wall, 0.2f);
      peer.DrawPoints(pl.points);
      peer.End(lv.window);
      std::vector<double> with = peer.WindowLuminance(lv.window);
      for (size_t p = 0; p < with.size(); ++p) with[p] -= without[p];
      (msaa ? gl4 : gl1).push_back(ImageOf(with, lv.window).sum / pl.nominal);
    }
    if (o.print_every > 0 && (k % o.print_every == 0 || k == o.frames - 1))
      std::printf("| %d | %.5f | %.5f | %.5f | %.5f |\n", k, share.back(), aperture.back(),
                  gl1.back(), gl4.back());
  }
  // Aperture: monotone, each step within the share's own change.
  double worst_error = 0, worst_excess = 0, largest_share_step = 0;
  int rises = 0;
  for (size_t k = 0; k < share.size(); ++k) {
    worst_error = std::max(worst_error, std::abs(aperture[k] - share[k]));
    if (k == 0) continue;
    const double step = aperture[k] - aperture[k - 1], want = share[k] - share[k - 1];
    largest_share_step = std::max(largest_share_step, std::abs(want));
    rises += step > o.tolerance;
    worst_excess = std::max(worst_excess, std::abs(step - want));
  }
  // llvmpipe's frames: how many of them its energy rose in, and its largest step.
  auto rising = [&](const std::vector<double>& e) {
    int n = 0;
    for (size_t k = 1; k < e.size(); ++k) n += e[k] > e[k - 1] + o.tolerance;
    return n;
  };
  const bool ok = rises == 0 && worst_excess <= o.tolerance;
  std::printf(
      "\nAperture %s: %s (%d rising steps), share from %.4f to %.4f; largest step %.5f against "
      "the covered area's largest change %.5f; worst |step - the covered area's change| %.2e, "
      "worst |energy - share| %.2e (tolerance %.0e): %s\n"
      "llvmpipe 1x: largest step %.5f (%.1fx the covered area's), %d rising steps; 4x MSAA: "
      "largest step %.5f (%.1fx), %d rising steps\n",
      AntiAliasingName(o.aa), rises == 0 ? "monotone" : "NOT monotone", rises, share.front(),
      share.back(), LargestStep(aperture), largest_share_step, worst_excess, worst_error,
      o.tolerance, ok ? "PASS" : "FAIL", LargestStep(gl1), LargestStep(gl1) / largest_share_step,
      rising(gl1), LargestStep(gl4), LargestStep(gl4) / largest_share_step, rising(gl4));
  std::fflush(stdout);
  if (passed != nullptr) *passed = ok;
  return absl::OkStatus();
}

}  // namespace aperture
