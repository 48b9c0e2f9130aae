#define GL_GLEXT_PROTOTYPES 1
#include "light_point_peer.h"

#include <GL/gl.h>
#include <GL/glext.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "osmesa_context.h"

namespace aperture {

std::vector<SizedPoint> OsgSimPointSizes(double pixel_size, double min_size, double max_size) {
  const double raw = pixel_size;
  double size = std::max(pixel_size, min_size);
  if (size < 1) return {{1, size}};
  if (size >= max_size) return {{static_cast<int>(max_size), 1}};
  const int lower = static_cast<int>(size);
  const double f = size - lower, remainder = f * f;
  // The dimming osgSim applies where the minimum size raised the point.
  const double alpha = raw < min_size ? 2.0 / 3.0 + std::sqrt(raw / size) / 3.0 : 1.0;
  std::vector<SizedPoint> points;
  if (remainder < 1) points.push_back({lower, alpha * (1 - remainder)});
  if (remainder > 0) points.push_back({lower + 1, alpha * remainder});
  return points;
}

double NominalArea(const std::vector<SizedPoint>& points) {
  double area = 0;
  for (const SizedPoint& p : points) area += p.alpha * M_PI * p.size * p.size / 4;
  return area;
}

LightPointPeer::~LightPointPeer() {
  if (context_ != nullptr) {
    for (Target* t : {&single_, &multi_, &resolved_}) Free(*t);
    OSMesaDestroyContext(context_);
  }
}

bool LightPointPeer::Init() {
  context_ = testing::CreateCurrentOsMesaContext("light peer", dummy_);
  if (context_ == nullptr) return false;
  // Proof that the buffers hold what is blended: a large point of colour 0.5 reads back as 0.5.
  if (!Resize(16, 16)) return false;
  Camera camera;
  SetCamera(camera);
  for (bool msaa : {false, true}) {
    Begin(msaa);
    DrawPoints({{{0, 0, -10}, 0.5f, 0.5f, 0.5f, {8, 1}}});
    End();
    float pixel[4] = {0, 0, 0, 0};
    glBindFramebuffer(GL_READ_FRAMEBUFFER, read_->fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glReadPixels(8, 8, 1, 1, GL_RGBA, GL_FLOAT, pixel);
    if (!(std::abs(pixel[0] - 0.5f) < 1e-3f)) {
      std::fprintf(stderr, "light peer: a point of colour 0.5 reads back as %g (%s)\n", pixel[0],
                   msaa ? "4x MSAA" : "1x");
      return false;
    }
  }
  return glGetError() == GL_NO_ERROR;
}

std::string LightPointPeer::Renderer() const {
  return std::string(reinterpret_cast<const char*>(glGetString(GL_RENDERER))) + ", " +
         reinterpret_cast<const char*>(glGetString(GL_VERSION));
}

bool LightPointPeer::Make(Target& target, unsigned format, int samples, bool depth) {
  glGenFramebuffers(1, &target.fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, target.fbo);
  glGenRenderbuffers(1, &target.color);
  glBindRenderbuffer(GL_RENDERBUFFER, target.color);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, format, width_, height_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, target.color);
  if (depth) {
    glGenRenderbuffers(1, &target.depth);
    glBindRenderbuffer(GL_RENDERBUFFER, target.depth);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, width_,
                                     height_);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, target.depth);
  }
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    std::fprintf(stderr,
                 "light peer: a framebuffer of %dx%d, format 0x%x, %d samples is incomplete\n",
                 width_, height_, format, samples);
    return false;
  }
  return true;
}

void LightPointPeer::Free(Target& target) {
  if (target.fbo != 0) glDeleteFramebuffers(1, &target.fbo);
  if (target.color != 0) glDeleteRenderbuffers(1, &target.color);
  if (target.depth != 0) glDeleteRenderbuffers(1, &target.depth);
  target = {};
}

bool LightPointPeer::Resize(int width, int height) {
  for (Target* t : {&single_, &multi_, &resolved_}) Free(*t);
  width_ = width;
  height_ = height;
  return Make(single_, GL_RGBA16, 0, true) && Make(multi_, GL_RGBA32F, 4, true) &&
         Make(resolved_, GL_RGBA32F, 0, false);
}

void LightPointPeer::SetCamera(const Camera& camera, double near, double far) {
  const FrustumTangents t = ResolveFrustum(camera, width_, height_);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glFrustum(t.left * near, t.right * near, t.bottom * near, t.top * near, near, far);
  // World to camera: the transpose of the camera's orientation (columns right, up, back).
  const Mat3 to_camera = camera.Orientation().Transposed();
  double m[16] = {0};
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) m[col * 4 + row] = to_camera.m[row][col];
  m[15] = 1;
  glMatrixMode(GL_MODELVIEW);
  glLoadMatrixd(m);
  eye_ = camera.position;
}

PixelRect LightPointPeer::GlRect(const PixelRect& window) const {
  if (window.pixels() <= 0) return {0, 0, width_, height_};
  return {window.x0, height_ - window.y1, window.x1, height_ - window.y0};
}

void LightPointPeer::Begin(bool msaa, const PixelRect& window) {
  drawn_ = msaa ? &multi_ : &single_;
  resolve_to_ = msaa ? &resolved_ : nullptr;
  read_ = msaa ? &resolved_ : &single_;
  glBindFramebuffer(GL_FRAMEBUFFER, drawn_->fbo);
  glViewport(0, 0, width_, height_);
  const PixelRect r = GlRect(window);
  glEnable(GL_SCISSOR_TEST);
  glScissor(r.x0, r.y0, r.width(), r.height());
  glClearColor(0, 0, 0, 0);
  glDepthMask(GL_TRUE);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (msaa)
    glEnable(GL_MULTISAMPLE);
  else
    glDisable(GL_MULTISAMPLE);
}

void LightPointPeer::DrawQuad(const Vec3 corners[4], float grey) {
  glDisable(GL_BLEND);
  glDisable(GL_POINT_SMOOTH);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glColor4f(grey, grey, grey, 1);
  glBegin(GL_QUADS);
  for (int k = 0; k < 4; ++k) {
    const Vec3 v = corners[k] - eye_;
    glVertex3d(v.x, v.y, v.z);
  }
  glEnd();
}

void DrawOsgSimPoints(const std::vector<PeerPoint>& points) {
  // LightPointDrawable's state for additive light points.
  glEnable(GL_POINT_SMOOTH);
  glHint(GL_POINT_SMOOTH_HINT, GL_NICEST);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_FALSE);
  glDisable(GL_TEXTURE_2D);
  glDisable(GL_ALPHA_TEST);
  // Each size's points as one array of positions and one of colours.
  struct Arrays {
    std::vector<double> xyz;
    std::vector<float> rgba;
  };
  std::map<int, Arrays> by_size;
  for (const PeerPoint& p : points) {
    Arrays& a = by_size[p.point.size];
    a.xyz.insert(a.xyz.end(), {p.offset.x, p.offset.y, p.offset.z});
    a.rgba.insert(a.rgba.end(), {p.r, p.g, p.b, static_cast<float>(p.point.alpha)});
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);  // client arrays
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  for (const auto& [size, a] : by_size) {
    glPointSize(static_cast<float>(size));
    glVertexPointer(3, GL_DOUBLE, 0, a.xyz.data());
    glColorPointer(4, GL_FLOAT, 0, a.rgba.data());
    glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(a.xyz.size() / 3));
  }
  glDisableClientState(GL_COLOR_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
  glDepthMask(GL_TRUE);
}

void LightPointPeer::End(const PixelRect& window) {
  if (resolve_to_ != nullptr) {
    const PixelRect r = GlRect(window);
    glDisable(GL_SCISSOR_TEST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, drawn_->fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_to_->fbo);
    glBlitFramebuffer(r.x0, r.y0, r.x1, r.y1, r.x0, r.y0, r.x1, r.y1, GL_COLOR_BUFFER_BIT,
                      GL_NEAREST);
  }
  glFinish();
}

std::vector<double> LightPointPeer::WindowLuminance(const PixelRect& window) {
  const PixelRect r = GlRect(window);
  std::vector<double> out(static_cast<size_t>(r.pixels()), 0.0);
  readback_.resize(static_cast<size_t>(r.pixels()) * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, read_->fbo);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glReadPixels(r.x0, r.y0, r.width(), r.height(), GL_RGBA, GL_FLOAT, readback_.data());
  // GL's rows run bottom to top.
  for (int j = 0; j < r.height(); ++j)
    for (int i = 0; i < r.width(); ++i) {
      const float* p = &readback_[(static_cast<size_t>(j) * r.width() + i) * 4];
      out[static_cast<size_t>(r.height() - 1 - j) * r.width() + i] =
          0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    }
  return out;
}

}  // namespace aperture
