#define GL_GLEXT_PROTOTYPES 1
#include "scene_gl_peer.h"

#include <GL/gl.h>
#include <GL/glext.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <tuple>

#include "absl/strings/str_cat.h"
#include "gl_texels.h"
#include "osmesa_context.h"
#include "scene/shading.h"

namespace aperture {
namespace {

double NowMs() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// One vertex of the buffer: position relative to the camera, texture coordinates, colour, and
// its depth along the view axis as the fog coordinate. GL's default fog coordinate, |eye z|, is
// not affine where a polygon reaches behind the camera (the ground does), so clipping would
// interpolate it wrongly; the signed depth is, and is clipped exactly.
struct Vertex {
  float x, y, z;
  float u, v;
  float r, g, b, a;
  float depth;
};

// The order batches are drawn in: opaque, then cut-outs, then blended.
int DrawOrder(AlphaMode mode) {
  switch (mode) {
    case AlphaMode::kOpaque:
      return 0;
    case AlphaMode::kMask:
      return 1;
    case AlphaMode::kBlend:
      return 2;
  }
  return 0;
}

}  // namespace

SceneGlPeer::~SceneGlPeer() {
  if (context_ == nullptr) return;
  for (Target* t : {&single_, &multi_, &resolved_}) Free(*t);
  for (UploadedScene& s : scenes_)
    if (s.buffer != 0) glDeleteBuffers(1, &s.buffer);
  for (auto& [id, t] : textures_)
    if (t.name != 0) glDeleteTextures(1, &t.name);
  OSMesaDestroyContext(context_);
}

bool SceneGlPeer::Init() {
  context_ = testing::CreateCurrentOsMesaContext("scene peer", dummy_);
  if (context_ == nullptr) return false;
  return glGetError() == GL_NO_ERROR;
}

std::string SceneGlPeer::Renderer() const {
  return std::string(reinterpret_cast<const char*>(glGetString(GL_RENDERER))) + ", " +
         reinterpret_cast<const char*>(glGetString(GL_VERSION));
}

bool SceneGlPeer::Make(Target& target, int samples, bool depth) {
  glGenFramebuffers(1, &target.fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, target.fbo);
  glGenRenderbuffers(1, &target.color);
  glBindRenderbuffer(GL_RENDERBUFFER, target.color);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width_, height_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, target.color);
  if (depth) {
    glGenRenderbuffers(1, &target.depth);
    glBindRenderbuffer(GL_RENDERBUFFER, target.depth);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, width_,
                                     height_);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, target.depth);
  }
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    std::fprintf(stderr, "scene peer: a framebuffer of %dx%d, %d samples is incomplete\n", width_,
                 height_, samples);
    return false;
  }
  return true;
}

void SceneGlPeer::Free(Target& target) {
  if (target.fbo != 0) glDeleteFramebuffers(1, &target.fbo);
  if (target.color != 0) glDeleteRenderbuffers(1, &target.color);
  if (target.depth != 0) glDeleteRenderbuffers(1, &target.depth);
  target = {};
}

bool SceneGlPeer::Resize(int width, int height) {
  for (Target* t : {&single_, &multi_, &resolved_}) Free(*t);
  last_ = nullptr;
  width_ = width;
  height_ = height;
  return Make(single_, 0, true) && Make(multi_, 4, true) && Make(resolved_, 0, false);
}

unsigned SceneGlPeer::TextureOf(const Scene& scene, int index, Rgba* mean) {
  const SceneTexture& texture = *scene.textures[index];
  auto found = textures_.find(texture.id);
  if (found == textures_.end()) {
    GLint max_side = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_side);
    UploadedTexture uploaded;
    auto texels = GlTexelsOf(texture, std::min<int>(options_.texture_side, max_side));
    if (texels.ok()) {
      glGenTextures(1, &uploaded.name);
      glBindTexture(GL_TEXTURE_2D, uploaded.name);
      glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, texels->width, texels->height, 0, GL_RGBA,
                   GL_UNSIGNED_BYTE, texels->rgba.data());
      glGenerateMipmap(GL_TEXTURE_2D);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
      glBindTexture(GL_TEXTURE_2D, 0);
      notes_.push_back(absl::StrCat(texture.id, ": ", texels->source, ", RGBA8 ", texels->width,
                                    "x", texels->height, " trilinear"));
    } else {
      uploaded.mean = MeanColour(texture);
      notes_.push_back(
          absl::StrCat(texture.id, ": drawn as its mean colour (", texels.status().message(), ")"));
    }
    found = textures_.emplace(texture.id, uploaded).first;
  }
  *mean = found->second.mean;
  return found->second.name;
}

absl::StatusOr<int> SceneGlPeer::AddScene(const Scene& scene, const Camera& camera) {
  UploadedScene uploaded;
  uploaded.camera = camera;
  uploaded.sky = scene.sky;
  uploaded.fog_color = scene.fog_color;
  uploaded.fog_density = scene.fog_density;
  // Each material state's triangles, in the order they are drawn.
  using Key = std::tuple<int, unsigned, float, bool>;  // order, texture, cutoff, culled
  std::map<Key, std::vector<Vertex>> by_state;
  const Vec3 eye = camera.position;
  const Mat3 orientation = camera.Orientation();  // columns right, up, back
  const Vec3 back{orientation.m[0][2], orientation.m[1][2], orientation.m[2][2]};
  for (const ScenePolygon& polygon : scene.polygons) {
    if (polygon.vertices.size() < 3) continue;
    const Material& material = scene.materials[polygon.material];
    Rgba mean{1, 1, 1, 1};
    const unsigned texture = material.texture >= 0 ? TextureOf(scene, material.texture, &mean) : 0;
    // The polygon's constant light on the side the camera sees.
    const Vec3 facing = Dot(polygon.normal, eye - polygon.vertices[0]) >= 0 ? polygon.normal
                                                                            : polygon.normal * -1.0;
    const Rgba light = SurfaceLight(scene, material, facing);
    const Rgba base = material.base_color;
    const Rgba colour{base.r * light.r * mean.r, base.g * light.g * mean.g,
                      base.b * light.b * mean.b, base.a};
    // Texture coordinates moved by whole periods near 0, where floats are precise.
    const TextureMapping& m = polygon.mapping;
    const double u_shift = std::floor(Dot(m.su, polygon.vertices[0]) + m.u0);
    const double v_shift = std::floor(Dot(m.sv, polygon.vertices[0]) + m.v0);
    auto vertex = [&](const Vec3& p) {
      const Vec3 d = p - eye;
      return Vertex{static_cast<float>(d.x),
                    static_cast<float>(d.y),
                    static_cast<float>(d.z),
                    static_cast<float>(Dot(m.su, p) + m.u0 - u_shift),
                    static_cast<float>(Dot(m.sv, p) + m.v0 - v_shift),
                    colour.r,
                    colour.g,
                    colour.b,
                    colour.a,
                    static_cast<float>(-Dot(d, back))};
    };
    std::vector<Vertex>& out = by_state[Key{DrawOrder(material.alpha_mode), texture,
                                            material.alpha_cutoff, material.single_sided}];
    // A fan, each triangle wound counter-clockwise about the polygon's normal (GL's front face).
    const std::vector<Vec3>& v = polygon.vertices;
    for (size_t i = 1; i + 1 < v.size(); ++i) {
      const bool along = Dot(Cross(v[i] - v[0], v[i + 1] - v[0]), polygon.normal) >= 0;
      out.push_back(vertex(v[0]));
      out.push_back(vertex(along ? v[i] : v[i + 1]));
      out.push_back(vertex(along ? v[i + 1] : v[i]));
    }
  }
  std::vector<Vertex> all;
  double farthest = 0;
  for (const auto& [key, vertices] : by_state)
    for (const Vertex& v : vertices) farthest = std::max(farthest, static_cast<double>(v.depth));
  uploaded.far = camera.far > 0 ? camera.far : std::max(farthest * 1.01, 2 * camera.near);
  uploaded.near =
      options_.near > 0
          ? options_.near
          : std::min(std::max(camera.near, kOsgNearFarRatio * uploaded.far), uploaded.far / 2);
  for (const auto& [key, vertices] : by_state) {
    Batch batch;
    const auto& [order, texture, cutoff, culled] = key;
    batch.texture = texture;
    batch.alpha = order == 0   ? AlphaMode::kOpaque
                  : order == 1 ? AlphaMode::kMask
                               : AlphaMode::kBlend;
    batch.cutoff = cutoff;
    batch.cull_back = culled;
    batch.first = static_cast<int>(all.size());
    batch.count = static_cast<int>(vertices.size());
    all.insert(all.end(), vertices.begin(), vertices.end());
    uploaded.batches.push_back(batch);
  }
  uploaded.triangles = all.size() / 3;
  glGenBuffers(1, &uploaded.buffer);
  glBindBuffer(GL_ARRAY_BUFFER, uploaded.buffer);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(all.size() * sizeof(Vertex)), all.data(),
               GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  if (const GLenum error = glGetError(); error != GL_NO_ERROR)
    return absl::InternalError(
        absl::StrCat("scene peer: GL error 0x", absl::Hex(error), " uploading ", scene.name));
  scenes_.push_back(std::move(uploaded));
  return static_cast<int>(scenes_.size()) - 1;
}

double SceneGlPeer::Draw(int index, bool msaa, const std::vector<PeerPoint>* points) {
  const UploadedScene& s = scenes_[index];
  const double start = NowMs();
  const Target& drawn = msaa ? multi_ : single_;
  glBindFramebuffer(GL_FRAMEBUFFER, drawn.fbo);
  glViewport(0, 0, width_, height_);
  glDisable(GL_SCISSOR_TEST);
  glClearColor(s.sky.r, s.sky.g, s.sky.b, 1);
  glDepthMask(GL_TRUE);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (msaa)
    glEnable(GL_MULTISAMPLE);
  else
    glDisable(GL_MULTISAMPLE);

  // The camera: its frustum, and its orientation (the vertices are relative to its position).
  const double near = s.near, far = s.far;
  const FrustumTangents t = ResolveFrustum(s.camera, width_, height_);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glFrustum(t.left * near, t.right * near, t.bottom * near, t.top * near, near, far);
  const Mat3 to_camera = s.camera.Orientation().Transposed();
  double m[16] = {0};
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) m[col * 4 + row] = to_camera.m[row][col];
  m[15] = 1;
  glMatrixMode(GL_MODELVIEW);
  glLoadMatrixd(m);

  if (s.fog_density > 0) {
    const float colour[4] = {s.fog_color.r, s.fog_color.g, s.fog_color.b, 1};
    glEnable(GL_FOG);
    glFogi(GL_FOG_MODE, GL_EXP);
    glFogf(GL_FOG_DENSITY, static_cast<float>(s.fog_density));
    glFogfv(GL_FOG_COLOR, colour);
    glFogi(GL_FOG_COORD_SRC, GL_FOG_COORD);
  } else {
    glDisable(GL_FOG);
  }

  // The polygons, batch by batch.
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glFrontFace(GL_CCW);
  glCullFace(GL_BACK);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
  glBindBuffer(GL_ARRAY_BUFFER, s.buffer);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_TEXTURE_COORD_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glEnableClientState(GL_FOG_COORD_ARRAY);
  glVertexPointer(3, GL_FLOAT, sizeof(Vertex), reinterpret_cast<const void*>(offsetof(Vertex, x)));
  glFogCoordPointer(GL_FLOAT, sizeof(Vertex),
                    reinterpret_cast<const void*>(offsetof(Vertex, depth)));
  glTexCoordPointer(2, GL_FLOAT, sizeof(Vertex),
                    reinterpret_cast<const void*>(offsetof(Vertex, u)));
  glColorPointer(4, GL_FLOAT, sizeof(Vertex), reinterpret_cast<const void*>(offsetof(Vertex, r)));
  for (const Batch& b : s.batches) {
    if (b.texture != 0) {
      glEnable(GL_TEXTURE_2D);
      glBindTexture(GL_TEXTURE_2D, b.texture);
    } else {
      glDisable(GL_TEXTURE_2D);
    }
    if (b.cull_back)
      glEnable(GL_CULL_FACE);
    else
      glDisable(GL_CULL_FACE);
    switch (b.alpha) {
      case AlphaMode::kOpaque:
        glDisable(GL_BLEND);
        glDisable(GL_ALPHA_TEST);
        glDepthMask(GL_TRUE);
        break;
      case AlphaMode::kMask:
        glDisable(GL_BLEND);
        glEnable(GL_ALPHA_TEST);
        glAlphaFunc(GL_GEQUAL, b.cutoff);
        glDepthMask(GL_TRUE);
        break;
      case AlphaMode::kBlend:
        glDisable(GL_ALPHA_TEST);
        glEnable(GL_BLEND);
        glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
        glDepthMask(GL_FALSE);
        break;
    }
    glDrawArrays(GL_TRIANGLES, b.first, b.count);
  }
  glDisableClientState(GL_FOG_COORD_ARRAY);
  glDisableClientState(GL_COLOR_ARRAY);
  glDisableClientState(GL_TEXTURE_COORD_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glFogi(GL_FOG_COORD_SRC, GL_FRAGMENT_DEPTH);  // the points' own depth
  glDisable(GL_TEXTURE_2D);
  glDisable(GL_CULL_FACE);
  glDisable(GL_ALPHA_TEST);
  glDepthMask(GL_TRUE);

  if (points != nullptr) DrawOsgSimPoints(*points);
  glDisable(GL_BLEND);
  glDisable(GL_POINT_SMOOTH);

  if (msaa) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, multi_.fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolved_.fbo);
    glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT,
                      GL_NEAREST);
  }
  glFinish();
  last_ = msaa ? &resolved_ : &single_;
  return NowMs() - start;
}

Image SceneGlPeer::Read() const {
  Image image(width_, height_);
  if (last_ == nullptr) return image;
  std::vector<uint8_t> rgba(static_cast<size_t>(width_) * height_ * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, last_->fbo);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  // GL's rows run bottom to top.
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      const uint8_t* p = &rgba[(static_cast<size_t>(height_ - 1 - y) * width_ + x) * 4];
      image.at(x, y) = {p[0] / 255.0f, p[1] / 255.0f, p[2] / 255.0f, 1};
    }
  return image;
}

}  // namespace aperture
