// The peer benchmark: Mesa llvmpipe (through OSMesa) against Aperture on the same frames,
// timed interleaved in one run, each image scored against a dense box reference.
//
//   tris-N   N flat triangles (engine/scene/benchmark_scenes.h, MakeTrisScene), painted in order:
//            llvmpipe 1x and 4x MSAA against Aperture box1 and box2 edges.
//   plane-T  DESIGN.md's grazing plane pitched down T degrees, 1024^2 checkerboard of 8 x 8
//            cells repeated every 4 m: llvmpipe trilinear against Aperture trilinear and aniso.
//
//   filter   with --filter_yaws: aperture-bench filter's plane at each --filter_pitch (default 5)
//   turned
//            by each yaw, from --positions camera positions (default 1), on each of
//            --filter_textures (the checkerboard, or images by name in --data, as aperture-bench
//            filter loads them), llvmpipe trilinear and anisotropic 16 against Aperture's filters
//            and OpenImageIO (its defaults, and anisotropic 16 with bilinear texels), PSNR against
//            the box.
//   flicker  with --flicker_frames N: aperture-bench flicker's turning fly-over with llvmpipe in
//   the run
//            (the first of --filter_textures).
//   memory   with --memory N,N,...: the peak resident memory of a tris-N frame, llvmpipe 4x MSAA
//            and Aperture box2, each in a child process of its own holding its input as it
//            draws it (OpenGL's vertex arrays; Aperture's scene).
//
// Usage: peer_bench [--rounds R] [--tris N,N,...] [--planes T,T,...] [--psnr_pixels P]
//                   [--filter_yaws Y,Y,... [--filter_pitch T,T,...] [--positions P]
//                   [--cache DIR]] [--flicker_frames N] [--filter_textures checker,NAME,...]
//                   [--data DIR] [--memory N,N,...]
// (scripts/bench-peers.sh builds and runs it with LP_NUM_THREADS=2; docs/BENCHMARKS.md.)
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>
#include <malloc.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "absl/strings/str_cat.h"
#include "bench/bench_inputs.h"
#include "large_buffers.h"
#include "osmesa_context.h"
#include "raster/projection.h"
#include "render/frame_renderer.h"
#include "scene/benchmark_scenes.h"
#include "scene/scene_builder.h"
#include "support/reference_render.h"
#include "support/test_scenes.h"
#include "testing/grazing_plane.h"
#include "texture/aniso_sampler.h"
#include "texture/mip_pyramid.h"
#include "texture/oiio_sampler.h"
#include "texture/prefiltered_table_builder.h"

namespace aperture {
namespace {

constexpr int kWidth = 1920, kHeight = 1080;
constexpr double kFovDeg = 60;

double Now() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

// The OSMesa context (llvmpipe), with a 4x multisampled framebuffer object for MSAA.
class Peer {
 public:
  bool Init(bool quiet = false) {
    context_ = testing::CreateOsMesaContext();
    if (context_ == nullptr) return false;
    pixels_.resize(static_cast<size_t>(kWidth) * kHeight);
    if (!OSMesaMakeCurrent(context_, pixels_.data(), GL_UNSIGNED_BYTE, kWidth, kHeight))
      return false;
    if (!quiet)
      std::printf("peer: %s, %s\n", reinterpret_cast<const char*>(glGetString(GL_RENDERER)),
                  reinterpret_cast<const char*>(glGetString(GL_VERSION)));
    glGenFramebuffers(1, &msaa_fbo_);
    glBindFramebuffer(GL_FRAMEBUFFER, msaa_fbo_);
    GLuint buffers[2];
    glGenRenderbuffers(2, buffers);
    glBindRenderbuffer(GL_RENDERBUFFER, buffers[0]);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, 4, GL_RGBA8, kWidth, kHeight);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, buffers[0]);
    glBindRenderbuffer(GL_RENDERBUFFER, buffers[1]);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, 4, GL_DEPTH_COMPONENT24, kWidth, kHeight);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, buffers[1]);
    const bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return complete;
  }
  ~Peer() {
    if (context_ != nullptr) OSMesaDestroyContext(context_);
  }

  // Draws with `draw` into the window (1x) or the 4x MSAA buffer resolved into the window;
  // returns milliseconds from clear to glFinish.
  // `width` x `height`: the lower-left part of the window only (the filter views' 1024 x 768).
  double Frame(bool msaa, const std::function<void()>& draw, int width = kWidth,
               int height = kHeight) {
    const double start = Now();
    glBindFramebuffer(GL_FRAMEBUFFER, msaa ? msaa_fbo_ : 0);
    glViewport(0, 0, width, height);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    draw();
    if (msaa) {
      glBindFramebuffer(GL_READ_FRAMEBUFFER, msaa_fbo_);
      glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
      glBlitFramebuffer(0, 0, kWidth, kHeight, 0, 0, kWidth, kHeight, GL_COLOR_BUFFER_BIT,
                        GL_NEAREST);
      glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
    glFinish();
    return Now() - start;
  }

  // The window (or its lower-left width x height) as linear RGB floats, row 0 at the top
  // (OpenGL's row 0 is the bottom).
  Image Read(int width = kWidth, int height = kHeight) const {
    Image image = Image::Uninitialized(width, height);
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        const uint32_t p = pixels_[static_cast<size_t>(height - 1 - y) * kWidth + x];
        image.at(x, y) = {(p & 0xff) / 255.0f, ((p >> 8) & 0xff) / 255.0f,
                          ((p >> 16) & 0xff) / 255.0f, 1};
      }
    }
    return image;
  }

 private:
  OSMesaContext context_ = nullptr;
  std::vector<uint32_t> pixels_;
  GLuint msaa_fbo_ = 0;
};

// The same perspective as Aperture's camera: 60 degrees vertical, near 0.1 (as Camera's).
void LoadProjection(double near, double far, double aspect = double(kWidth) / kHeight) {
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  const double top = near * std::tan(kFovDeg * M_PI / 360), right = top * aspect;
  glFrustum(-right, right, -top, top, near, far);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
}

// PSNR (peak 1, RGB) of `image` against `reference` colours of the chosen pixels.
double Psnr(const Image& image, const std::vector<std::pair<int, int>>& pixels,
            const std::vector<Rgba>& reference) {
  double sum = 0;
  for (size_t i = 0; i < pixels.size(); ++i) {
    const Rgba& a = image.at(pixels[i].first, pixels[i].second);
    const Rgba& b = reference[i];
    sum += (a.r - b.r) * (a.r - b.r) + (a.g - b.g) * (a.g - b.g) + (a.b - b.b) * (a.b - b.b);
  }
  const double mse = sum / (3.0 * pixels.size());
  return mse > 0 ? 10 * std::log10(1 / mse) : 99;
}

struct Options {
  int rounds = 5;
  std::vector<int> tris = {10000, 100000};
  std::vector<double> planes = {5, 20, 60};
  int psnr_pixels = 3000;
  std::vector<double> filter_yaws;  // empty: no filter-quality table
  std::vector<double> filter_pitches = {5};
  int positions = 1;  // aperture-bench filter's --positions
  std::string cache_dir =
      "out/bench-filter/cache";  // aperture-bench filter's default reference cache
  int flicker_frames = 0;        // 0: no flicker table
  std::string filter_textures = "checker";
  std::string data_dir = "../shared/data/raster";
  std::vector<int> memory;  // tris-N counts for the memory table
};

double AperturePlaneOrTrisMs(const Scene& scene, const Camera& camera, RenderSettings settings,
                             Image* out) {
  const double start = Now();
  auto frame = RenderFrame(scene, camera, settings);
  const double ms = Now() - start;
  if (!frame.ok()) {
    std::fprintf(stderr, "render failed: %s\n", std::string(frame.status().message()).c_str());
    std::exit(1);
  }
  if (out != nullptr) *out = std::move(frame->image);
  return ms;
}

// A tris-N scene as OpenGL draws it: vertex and colour arrays, in order.
struct TrisArrays {
  std::vector<float> xyz, rgb;
};

TrisArrays TrisArraysOf(const Scene& scene) {
  TrisArrays arrays;
  for (const ScenePolygon& p : scene.polygons) {
    const Rgba c = scene.materials[p.material].base_color;
    for (const Vec3& v : p.vertices) {
      arrays.xyz.insert(arrays.xyz.end(), {float(v.x), float(v.y), float(v.z)});
      arrays.rgb.insert(arrays.rgb.end(), {c.r, c.g, c.b});
    }
  }
  return arrays;
}

// No depth test: each later triangle is in front.
void DrawTris(const TrisArrays& arrays) {
  LoadProjection(1, 1000);
  glDisable(GL_DEPTH_TEST);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, arrays.xyz.data());
  glColorPointer(3, GL_FLOAT, 0, arrays.rgb.data());
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(arrays.xyz.size() / 3));
}

void RunTris(Peer& peer, int count, const Options& o) {
  auto scene = BuildScene(MakeTrisScene(count));
  if (!scene.ok()) std::exit(1);
  const Camera camera;  // at the origin looking along -z, 60 degrees
  // The same triangles for OpenGL, in order; no depth test: each later one is in front.
  const TrisArrays arrays = TrisArraysOf(*scene);
  auto draw = [&] { DrawTris(arrays); };
  RenderSettings box1, box2;
  box1.aa = AntiAliasing::kBox1;
  box2.aa = AntiAliasing::kBox2;
  box1.threads = box2.threads = 2;
  std::vector<double> gl1, gl4, ap1, ap2;
  Image gl1_image, gl4_image, ap1_image, ap2_image;
  // A round not counted: llvmpipe compiles its shaders, the allocators warm up.
  peer.Frame(false, draw);
  peer.Frame(true, draw);
  AperturePlaneOrTrisMs(*scene, camera, box1, nullptr);
  AperturePlaneOrTrisMs(*scene, camera, box2, nullptr);
  for (int r = 0; r < o.rounds; ++r) {
    gl1.push_back(peer.Frame(false, draw));
    if (r == 0) gl1_image = peer.Read();
    ap1.push_back(AperturePlaneOrTrisMs(*scene, camera, box1, r == 0 ? &ap1_image : nullptr));
    gl4.push_back(peer.Frame(true, draw));
    if (r == 0) gl4_image = peer.Read();
    ap2.push_back(AperturePlaneOrTrisMs(*scene, camera, box2, r == 0 ? &ap2_image : nullptr));
  }
  // Dense references (64 x 64 samples per pixel box, 128 x 128 per 2 x 2 box) at random pixels
  // that an edge crosses (a neighbour of a different colour in llvmpipe's 1x image).
  const FrameGeometry geo = ProjectScene(*scene, camera, kWidth, kHeight, 2);
  std::vector<std::pair<int, int>> pixels;
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> px(1, kWidth - 2), py(1, kHeight - 2);
  while (static_cast<int>(pixels.size()) < o.psnr_pixels) {
    const int x = px(rng), y = py(rng);
    const Rgba c = gl1_image.at(x, y);
    bool edge = false;
    for (int dy = -1; dy <= 1 && !edge; ++dy)
      for (int dx = -1; dx <= 1 && !edge; ++dx) edge = !(gl1_image.at(x + dx, y + dy) == c);
    if (edge) pixels.push_back({x, y});
  }
  // Each reference sees only the polygons that reach its pixel's 2 x 2 box (from 16-pixel bins).
  constexpr int kBin = 16;
  const int bins_x = kWidth / kBin + 1, bins_y = kHeight / kBin + 1;
  std::vector<std::vector<int>> bins(static_cast<size_t>(bins_x) * bins_y);
  for (size_t k = 0; k < geo.polygons.size(); ++k) {
    const ScreenPolygon& p = geo.polygons[k];
    const int x0 = std::clamp(static_cast<int>(std::floor(p.min_x - 1)) / kBin, 0, bins_x - 1);
    const int x1 = std::clamp(static_cast<int>(std::floor(p.max_x + 1)) / kBin, 0, bins_x - 1);
    const int y0 = std::clamp(static_cast<int>(std::floor(p.min_y - 1)) / kBin, 0, bins_y - 1);
    const int y1 = std::clamp(static_cast<int>(std::floor(p.max_y + 1)) / kBin, 0, bins_y - 1);
    for (int by = y0; by <= y1; ++by)
      for (int bx = x0; bx <= x1; ++bx) bins[static_cast<size_t>(by) * bins_x + bx].push_back(k);
  }
  std::vector<Rgba> ref1, ref1_half, ref2;
  for (const auto& [x, y] : pixels) {
    FrameGeometry local;
    std::vector<int> material;
    for (int k : bins[static_cast<size_t>(y / kBin) * bins_x + x / kBin]) {
      const ScreenPolygon& p = geo.polygons[k];
      if (p.max_x <= x - 1 || p.min_x >= x + 2 || p.max_y <= y - 1 || p.min_y >= y + 2) continue;
      local.polygons.push_back(p);
      material.push_back(p.material);
    }
    auto local_colour = [&](int k) { return scene->materials[material[k]].base_color; };
    ref1.push_back(testing::DenseReferencePixel(local, local_colour, scene->sky,
                                                AntiAliasing::kBox1, x, y, 64));
    ref1_half.push_back(testing::DenseReferencePixel(local, local_colour, scene->sky,
                                                     AntiAliasing::kBox1, x, y, 32));
    ref2.push_back(testing::DenseReferencePixel(local, local_colour, scene->sky,
                                                AntiAliasing::kBox2, x, y, 128));
  }
  // Convergence: the pixel-box reference at 32 x 32 samples against 64 x 64, and what box1 scores
  // against each (a reference's own error caps the PSNR it can show).
  Image coarse = Image::Uninitialized(kWidth, kHeight);
  for (size_t i = 0; i < pixels.size(); ++i)
    coarse.at(pixels[i].first, pixels[i].second) = ref1_half[i];
  std::printf(
      "tris-%-8d %zu edge pixels; references of 32x32 and 64x64 samples per pixel are "
      "%.1f dB apart; box1 scores %.1f / %.1f dB against them\n",
      count, pixels.size(), Psnr(coarse, pixels, ref1), Psnr(ap1_image, pixels, ref1_half),
      Psnr(ap1_image, pixels, ref1));
  std::printf("tris-%-8d llvmpipe 1x %8.1f ms %5.1f dB | box1 %8.1f ms %5.1f dB | ratio %5.2fx\n",
              count, Median(gl1), Psnr(gl1_image, pixels, ref1), Median(ap1),
              Psnr(ap1_image, pixels, ref1), Median(ap1) / Median(gl1));
  std::printf(
      "tris-%-8d llvmpipe 4x %8.1f ms %5.1f dB | box2 %8.1f ms %5.1f dB | ratio %5.2fx"
      " (4x MSAA and box1 against the pixel box, box2 against the 2x2 box)\n",
      count, Median(gl4), Psnr(gl4_image, pixels, ref1), Median(ap2), Psnr(ap2_image, pixels, ref2),
      Median(ap2) / Median(gl4));
  std::fflush(stdout);
}

// Resident memory now and its peak since the last ResetPeakMemory, in MB (/proc/self/status).
std::pair<double, double> ResidentMemoryMb() {
  std::ifstream status("/proc/self/status");
  double rss = 0, peak = 0;
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmRSS:", 0) == 0) rss = std::atof(line.c_str() + 6) / 1024;
    if (line.rfind("VmHWM:", 0) == 0) peak = std::atof(line.c_str() + 6) / 1024;
  }
  return {rss, peak};
}

// Makes the peak the present resident size (Linux: "5" to /proc/self/clear_refs), so that the
// peak measured after it is the frame's, not the input's construction.
void ResetPeakMemory() {
  malloc_trim(0);
  std::ofstream("/proc/self/clear_refs") << "5";
}

// The peak memory of one tris-N frame of each renderer, each in a child process (forked before
// any OpenGL context or thread exists) that builds its input, lets go of what built it, and draws
// two frames (the first compiles llvmpipe's shaders). Prints the input's and the peak's size.
void RunMemory(int count) {
  // Each child writes its peak to a pipe for the ratio.
  auto child = [&](bool gl, int write_end) {
    std::fflush(stdout);
    const pid_t pid = fork();
    if (pid != 0) return pid;
    TrisArrays arrays;
    std::optional<Scene> scene;
    {
      auto built = BuildScene(MakeTrisScene(count));  // the proto is gone after this statement
      if (!built.ok()) std::_Exit(1);
      if (gl)
        arrays = TrisArraysOf(*built);
      else
        scene = *std::move(built);
    }
    ResetPeakMemory();
    const double input = ResidentMemoryMb().first;
    if (gl) {
      Peer peer;
      if (!peer.Init(/*quiet=*/true)) std::_Exit(1);
      for (int i = 0; i < 2; ++i) peer.Frame(true, [&] { DrawTris(arrays); });
    } else {
      RenderSettings box2;
      box2.aa = AntiAliasing::kBox2;
      box2.threads = 2;
      for (int i = 0; i < 2; ++i) AperturePlaneOrTrisMs(*scene, Camera{}, box2, nullptr);
    }
    const double peak = ResidentMemoryMb().second;
    std::printf("tris-%-8d memory %-11s input %7.1f MB, peak %7.1f MB\n", count,
                gl ? "llvmpipe 4x" : "box2", input, peak);
    std::fflush(stdout);
    const bool written = write(write_end, &peak, sizeof peak) == sizeof peak;
    std::_Exit(written ? 0 : 1);
  };
  double peaks[2] = {0, 0};
  for (const bool gl : {true, false}) {
    int ends[2], status = 0;
    if (pipe(ends) != 0) std::exit(1);
    const pid_t pid = child(gl, ends[1]);
    close(ends[1]);
    const bool read_ok = read(ends[0], &peaks[gl ? 0 : 1], sizeof(double)) == sizeof(double);
    close(ends[0]);
    if (pid < 0 || waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0 ||
        !read_ok) {
      std::fprintf(stderr, "peer_bench: the memory run of tris-%d failed\n", count);
      std::exit(1);
    }
  }
  std::printf("tris-%-8d memory ratio box2 / llvmpipe 4x %.2fx (peaks)\n", count,
              peaks[1] / peaks[0]);
}

// An n x n RGBA8 texture for llvmpipe with its mip-maps (glGenerateMipmap: box averages, as
// Aperture's pyramid), trilinear minification, repeated both ways.
GLuint UploadRepeatingTexture(const std::vector<uint8_t>& rgba8, int n) {
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, n, n, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba8.data());
  glGenerateMipmap(GL_TEXTURE_2D);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  return texture;
}

void RunPlane(Peer& peer, double pitch_deg, const Options& o) {
  auto scene = BuildScene(testing::MakeGrazingPlaneScene(20000));
  if (!scene.ok()) std::exit(1);
  Camera camera;  // DESIGN.md: at (0, 1, 0), pitched down by the angle
  camera.position = {0, 1, 0};
  camera.pitch_deg = -pitch_deg;
  camera.vertical_fov_deg = kFovDeg;
  // The checkerboard as an OpenGL texture with its mip-maps; u = x / 4, v = z / 4, repeated.
  static GLuint texture = 0;
  if (texture == 0) {
    const int n = 1024;
    std::vector<uint8_t> texels(static_cast<size_t>(n) * n * 4);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const uint8_t v = ((i / 128) + (j / 128)) % 2 == 0 ? 255 : 0;
        uint8_t* t = &texels[(static_cast<size_t>(j) * n + i) * 4];
        t[0] = t[1] = t[2] = v;
        t[3] = 255;
      }
    texture = UploadRepeatingTexture(texels, n);
  }
  // llvmpipe's anisotropic filtering (GL_EXT_texture_filter_anisotropic, up to 16), the peer of
  // Aperture's aniso; 1 is plain trilinear.
  const char* extensions = reinterpret_cast<const char*>(glGetString(GL_EXTENSIONS));
  const bool gl_aniso = extensions != nullptr &&
                        std::strstr(extensions, "GL_EXT_texture_filter_anisotropic") != nullptr;
  float max_anisotropy = 1;
  auto draw = [&] {
    glBindTexture(GL_TEXTURE_2D, texture);
    if (gl_aniso) glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MAX_ANISOTROPY_EXT, max_anisotropy);
    LoadProjection(0.1, 30000);
    glRotated(pitch_deg, 1, 0, 0);  // pitch down: the camera's view turned up by the same
    glTranslated(0, -1, 0);
    glEnable(GL_TEXTURE_2D);
    glBindTexture(GL_TEXTURE_2D, texture);
    glColor3f(1, 1, 1);
    const double e = 20000;
    glBegin(GL_QUADS);
    glTexCoord2d(-e / 4, e / 4), glVertex3d(-e, 0, e);
    glTexCoord2d(e / 4, e / 4), glVertex3d(e, 0, e);
    glTexCoord2d(e / 4, -e / 4), glVertex3d(e, 0, -e);
    glTexCoord2d(-e / 4, -e / 4), glVertex3d(-e, 0, -e);
    glEnd();
    glDisable(GL_TEXTURE_2D);
  };
  std::vector<double> gl, gl16, tri, aniso;
  for (int r = -1; r < o.rounds; ++r) {  // round -1 is not counted (shaders, seed 000's table)
    max_anisotropy = 1;
    const double gl_ms = peer.Frame(false, draw);
    if (r >= 0) gl.push_back(gl_ms);
    if (gl_aniso) {
      max_anisotropy = 16;
      const double gl16_ms = peer.Frame(false, draw);
      if (r >= 0) gl16.push_back(gl16_ms);
      // Its frames take seconds at grazing angles; without a pause the frame timed next ran
      // 1.6x slower than in a run without it.
      std::this_thread::sleep_for(std::chrono::milliseconds(300));
    }
    for (FilterMode f : {FilterMode::kTrilinear, FilterMode::kAniso}) {
      RenderSettings s;
      s.threads = 2;
      s.shading.override_filter = true;
      s.shading.filter = f;
      s.shading.texture_aperture = 1;
      const double ms = AperturePlaneOrTrisMs(*scene, camera, s, nullptr);
      if (r >= 0) (f == FilterMode::kTrilinear ? tri : aniso).push_back(ms);
    }
  }
  std::printf(
      "plane-%-4.0f llvmpipe trilinear %6.1f ms | trilinear %6.1f ms, ratio %5.2fx | aniso (a = 1) "
      "%6.1f ms, ratio %5.2fx, %4.2fx Aperture's trilinear\n",
      pitch_deg, Median(gl), Median(tri), Median(tri) / Median(gl), Median(aniso),
      Median(aniso) / Median(gl), Median(aniso) / Median(tri));
  if (gl_aniso)
    std::printf(
        "plane-%-4.0f llvmpipe aniso 16   %6.1f ms | aniso (a = 1) %6.1f ms, ratio %5.2fx\n",
        pitch_deg, Median(gl16), Median(aniso), Median(aniso) / Median(gl16));
  else
    std::printf("plane-%-4.0f llvmpipe has no GL_EXT_texture_filter_anisotropic\n", pitch_deg);
  std::fflush(stdout);
}

// A texture of the filter benchmarks (aperture-bench filter's: the checkerboard, 1024^2 of 8 x 8
// cells, or a photo) as llvmpipe's texture with its mip-maps and as Aperture's and OpenImageIO's
// samplers; and the grazing plane drawn through llvmpipe exactly as a GrazingPlaneView sees it (u =
// x / 4, v = z / 4 turned by the yaw, plus the view's texture origin).
class FilterPeers {
 public:
  FilterPeers(Peer& peer, const BenchTexture& texture)
      : peer_(peer),
        name_(texture.name),
        image_(texture.image),
        pyramid_(image_),
        trilinear_(pyramid_) {
    const int n = image_.width();
    std::vector<uint8_t> texels(static_cast<size_t>(n) * n * 4);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Rgba& c = image_.at(i, j);
        uint8_t* t = &texels[(static_cast<size_t>(j) * n + i) * 4];
        t[0] = static_cast<uint8_t>(std::lround(c.r * 255));
        t[1] = static_cast<uint8_t>(std::lround(c.g * 255));
        t[2] = static_cast<uint8_t>(std::lround(c.b * 255));
        t[3] = 255;
      }
    texture_ = UploadRepeatingTexture(texels, n);
    auto block = BuildPrefilteredTable(image_);
    if (!block.ok()) std::exit(1);
    block_ = *std::move(block);
    auto table = block_.View();
    auto oiio = OiioSampler::Create(image_);
    auto oiio16 = OiioSampler::Create(image_, "", kOiioAniso16Bilinear);
    if (!table.ok() || !oiio.ok() || !oiio16.ok()) std::exit(1);
    aniso_ = std::make_unique<AnisoSampler>(*table);
    oiio_ = *std::move(oiio);
    oiio16_ = *std::move(oiio16);
    // The plane in tiles growing away from the camera, each with its texture coordinates moved
    // by whole repeats to near zero: one quad 20 km wide would carry coordinates of +-5000
    // repeats, and llvmpipe's float interpolation of them is off by a third of a texel near the
    // camera.
    edges_ = {0};
    for (double e = 0.25; e <= 32768; e *= 2)
      edges_.push_back(e), edges_.insert(edges_.begin(), -e);
  }
  ~FilterPeers() { glDeleteTextures(1, &texture_); }

  const std::string& name() const { return name_; }
  const Image& image() const { return image_; }
  const TextureSampler& trilinear() const { return trilinear_; }
  const TextureSampler& aniso() const { return *aniso_; }
  const TextureSampler& oiio() const { return *oiio_; }
  const TextureSampler& oiio16() const { return *oiio16_; }

  // The view through llvmpipe: trilinear (max_anisotropy 1) or anisotropic.
  Image Llvmpipe(const GrazingPlaneView& view, float max_anisotropy) {
    const double c = std::cos(view.yaw_deg * M_PI / 180), s = std::sin(view.yaw_deg * M_PI / 180);
    auto draw = [&] {
      glBindTexture(GL_TEXTURE_2D, texture_);
      glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MAX_ANISOTROPY_EXT, max_anisotropy);
      LoadProjection(0.1, 100000, double(view.width) / view.height);
      glRotated(view.pitch_deg, 1, 0, 0);
      glTranslated(0, -1, 0);
      glEnable(GL_TEXTURE_2D);
      glColor3f(1, 1, 1);
      glBegin(GL_QUADS);
      // (u, v) = R(yaw) (x / 4, z / 4) + the origin, as GroundPoint computes them.
      auto tex = [&](double x, double z, double* u, double* v) {
        *u = 0.25 * (c * x - s * z) + view.origin_u, *v = 0.25 * (s * x + c * z) + view.origin_v;
      };
      for (size_t a = 0; a + 1 < edges_.size(); ++a)
        for (size_t b = 0; b + 1 < edges_.size(); ++b) {
          const double x0 = edges_[a], x1 = edges_[a + 1], z0 = edges_[b], z1 = edges_[b + 1];
          double cu, cv;
          tex(0.5 * (x0 + x1), 0.5 * (z0 + z1), &cu, &cv);
          cu = std::floor(cu), cv = std::floor(cv);
          for (const auto& [x, z] : {std::pair{x0, z1}, {x1, z1}, {x1, z0}, {x0, z0}}) {
            double u, v;
            tex(x, z, &u, &v);
            glTexCoord2d(u - cu, v - cv);
            glVertex3d(x, 0, z);
          }
        }
      glEnd();
      glDisable(GL_TEXTURE_2D);
    };
    peer_.Frame(false, draw, view.width, view.height);
    return peer_.Read(view.width, view.height);
  }

 private:
  Peer& peer_;
  std::string name_;
  Image image_;  // the texture (the checkerboard unless --filter_textures names others)
  MipPyramid pyramid_;
  TrilinearSampler trilinear_;
  TableBlock block_;
  std::unique_ptr<AnisoSampler> aniso_;
  std::unique_ptr<OiioSampler> oiio_, oiio16_;
  GLuint texture_ = 0;
  std::vector<double> edges_;
};

// aperture-bench filter's plane (1024 x 768, a = 1) at each of --filter_pitch from each of
// --filter_yaws: llvmpipe's trilinear and anisotropic 16 against Aperture's trilinear and aniso and
// OpenImageIO (defaults, and anisotropic 16 bilinear), every image scored against the same
// supersampled pixel box (at least 16 x 16 strata a pixel, 4 per texel of extent per side:
// aperture-bench filter's
// `--ref-min 16 --ref-density 4`, whose reference cache this shares) over the rows aperture-bench
// filter measures. With --positions P each view is scored from aperture-bench
// filter's P camera positions and the squared errors pooled. llvmpipe has no aperture to widen, so
// this is the pixel box (a = 1) only; aperture-bench filter scores OpenImageIO at a = 2.
void RunFilterQuality(FilterPeers& f, const BenchTexture& texture, const Options& o) {
  constexpr int kFilters = 6;
  const char* kNames[kFilters] = {"llvmpipe trilinear", "llvmpipe aniso 16",
                                  "Aperture trilinear", "Aperture aniso",
                                  "OpenImageIO",        "OpenImageIO aniso 16 bilinear"};
  for (double pitch : o.filter_pitches) {
    std::printf(
        "\nfilter quality: %s, 1024x768, pitch %g, a = 1, PSNR against the pixel box, %s\n\n|",
        f.name().c_str(), pitch,
        o.positions == 1 ? "one camera position"
                         : absl::StrCat(o.positions, " camera positions pooled").c_str());
    std::printf(" yaw |");
    for (const char* name : kNames) std::printf(" %s |", name);
    std::printf(" aniso - best peer |\n|---|---:|---:|---:|---:|---:|---:|---:|\n");
    std::vector<double> leads, aniso_by_yaw;
    for (double yaw : o.filter_yaws) {
      GrazingPlaneView view;
      view.pitch_deg = pitch;
      view.yaw_deg = yaw;
      view.aperture = 1;
      const int first = FirstMeasuredRow(view);
      std::vector<double> psnr[kFilters];  // per filter, one per position
      for (int k = 0; k < o.positions; ++k) {
        const GrazingPlaneView at = ViewAtPosition(view, k);
        bool cached = false;
        const double start = Now();
        auto reference = CachedReference(at, texture, 4, 128, 16, o.cache_dir, &cached);
        if (!reference.ok()) {
          std::fprintf(stderr, "peer_bench: %s\n",
                       std::string(reference.status().message()).c_str());
          std::exit(1);
        }
        std::fprintf(stderr, "  pitch %g yaw %g position %d/%d: reference %s in %.1f s\n", pitch,
                     yaw, k + 1, o.positions, cached ? "from cache" : "computed",
                     (Now() - start) / 1000);
        const Image images[kFilters] = {f.Llvmpipe(at, 1),
                                        f.Llvmpipe(at, 16),
                                        RenderGroundImage(at, f.trilinear()),
                                        RenderGroundImage(at, f.aniso()),
                                        RenderGroundImage(at, f.oiio()),
                                        RenderGroundImage(at, f.oiio16())};
        for (int m = 0; m < kFilters; ++m) psnr[m].push_back(Psnr(images[m], *reference, first));
      }
      double pooled[kFilters];
      for (int m = 0; m < kFilters; ++m) pooled[m] = PooledPsnr(psnr[m]);
      const double lead = pooled[3] - std::max({pooled[0], pooled[1], pooled[4], pooled[5]});
      std::printf("| %g |", yaw);
      for (double value : pooled) std::printf(" %.2f |", value);
      std::printf(" %+.2f |\n", lead);
      std::fflush(stdout);
      leads.push_back(lead);
      aniso_by_yaw.push_back(pooled[3]);
    }
    const YawSpread spread = SpreadAcrossYaws(o.filter_yaws, aniso_by_yaw);
    std::printf(
        "\nlead over the best peer: %+.2f to %+.2f dB; aniso's spread across the yaws %.2f dB\n",
        *std::min_element(leads.begin(), leads.end()),
        *std::max_element(leads.begin(), leads.end()), spread.spread);
  }
}

// aperture-bench flicker's fly-over (320 x 240, pitch 3, turning 30 degrees over
// --flicker_frames frames, 0.05 world units a frame, a = 1, the first texture) with llvmpipe in
// the same run: each filter's mean frame-to-frame change against the
// reference's, and the excess flicker, the mean of |its change - the reference's|.
void RunFlicker(FilterPeers& f, const Options& o) {
  struct Track {
    const char* name;
    std::function<Image(const GrazingPlaneView&)> render;
    Image previous;
    double change = 0, excess = 0, psnr = 0;
  };
  std::vector<Track> tracks = {
      {"llvmpipe trilinear", [&](const GrazingPlaneView& v) { return f.Llvmpipe(v, 1); }, {}},
      {"llvmpipe aniso 16", [&](const GrazingPlaneView& v) { return f.Llvmpipe(v, 16); }, {}},
      {"Aperture trilinear",
       [&](const GrazingPlaneView& v) { return RenderGroundImage(v, f.trilinear()); },
       {}},
      {"Aperture aniso",
       [&](const GrazingPlaneView& v) { return RenderGroundImage(v, f.aniso()); },
       {}},
      {"OpenImageIO",
       [&](const GrazingPlaneView& v) { return RenderGroundImage(v, f.oiio()); },
       {}}};
  const int frames = o.flicker_frames;
  GrazingPlaneView view;
  view.width = 320;
  view.height = 240;
  view.pitch_deg = 3;
  view.aperture = 1;
  const int first = FirstMeasuredRow(view);
  Image reference_previous;
  double reference_change = 0;
  for (int t = 0; t < frames; ++t) {
    view.yaw_deg = 30.0 * t / (frames - 1);
    const Image reference = RenderGroundReference(view, f.image(), 4, 64, 8);
    for (Track& track : tracks) {
      Image image = track.render(view);
      if (t > 0) {
        track.change += MeanAbsoluteChange(image, track.previous, nullptr, nullptr, first);
        track.excess +=
            MeanAbsoluteChange(image, track.previous, &reference, &reference_previous, first);
        track.psnr += Psnr(image, reference, first);
      }
      track.previous = std::move(image);
    }
    if (t > 0)
      reference_change +=
          MeanAbsoluteChange(reference, reference_previous, nullptr, nullptr, first);
    reference_previous = reference;
    MoveForward(&view, 0.05);
  }
  const double n = frames - 1;
  std::printf(
      "\nflicker: %s, 320x240, pitch 3, turning 30 degrees over %d frames, 0.05 world "
      "units a frame, a = 1; reference 8..64 strata a side, 4 per texel\n\n"
      "| mode | mean PSNR | frame-to-frame change | / reference's | excess flicker |\n"
      "|---|---:|---:|---:|---:|\n| reference | - | %.5f | 1.00 | - |\n",
      f.name().c_str(), frames, reference_change / n);
  for (const Track& track : tracks)
    std::printf("| %s | %.2f | %.5f | %.2f | %.5f |\n", track.name, track.psnr / n,
                track.change / n, reference_change > 0 ? track.change / reference_change : 0.0,
                track.excess / n);
  std::fflush(stdout);
}

template <typename T>
std::vector<T> ParseList(const char* s) {
  std::vector<T> out;
  for (const char* p = s; *p;) {
    char* end = nullptr;
    out.push_back(static_cast<T>(std::strtod(p, &end)));
    if (end == p) break;
    p = *end == ',' ? end + 1 : end;
  }
  return out;
}

}  // namespace
}  // namespace aperture

int main(int argc, char** argv) {
  // Aperture's frames as the server renders them: their buffers reused warm, not page-faulted
  // afresh each frame (llvmpipe keeps its framebuffer too).
  aperture::KeepLargeBuffersWarm();
  aperture::Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--rounds") {
      o.rounds = std::max(1, std::atoi(argv[i + 1]));
    } else if (flag == "--tris") {
      o.tris = aperture::ParseList<int>(argv[i + 1]);
    } else if (flag == "--planes") {
      o.planes = aperture::ParseList<double>(argv[i + 1]);
    } else if (flag == "--psnr_pixels") {
      o.psnr_pixels = std::max(1, std::atoi(argv[i + 1]));
    } else if (flag == "--filter_yaws") {
      o.filter_yaws = aperture::ParseList<double>(argv[i + 1]);
    } else if (flag == "--filter_pitch") {
      o.filter_pitches = aperture::ParseList<double>(argv[i + 1]);
    } else if (flag == "--positions") {
      o.positions = std::clamp(std::atoi(argv[i + 1]), 1, 64);
    } else if (flag == "--cache") {
      o.cache_dir = argv[i + 1];
    } else if (flag == "--flicker_frames") {
      o.flicker_frames = std::atoi(argv[i + 1]);
    } else if (flag == "--filter_textures") {
      o.filter_textures = argv[i + 1];
    } else if (flag == "--data") {
      o.data_dir = argv[i + 1];
    } else if (flag == "--memory") {
      o.memory = aperture::ParseList<int>(argv[i + 1]);
    } else {
      std::fprintf(stderr,
                   "usage: peer_bench [--rounds R] [--tris N,N,...] [--planes T,T,...] "
                   "[--psnr_pixels P] [--filter_yaws Y,Y,... [--filter_pitch T,T,...] "
                   "[--positions P] [--cache DIR]] [--flicker_frames N] "
                   "[--filter_textures checker,NAME,...] [--data DIR] [--memory N,N,...]\n");
      return 2;
    }
  }
  // Before this process has an OpenGL context or threads: the memory runs fork.
  for (int n : o.memory) aperture::RunMemory(n);
  aperture::Peer peer;
  if (!peer.Init()) {
    std::fprintf(stderr, "peer_bench: no OSMesa context with a 4x MSAA framebuffer\n");
    return 1;
  }
  std::printf(
      "1920x1080, median of %d interleaved rounds; Aperture --threads 2, llvmpipe "
      "LP_NUM_THREADS=%s\n",
      o.rounds, std::getenv("LP_NUM_THREADS") ? std::getenv("LP_NUM_THREADS") : "(unset)");
  for (int n : o.tris) aperture::RunTris(peer, n, o);
  for (double t : o.planes) aperture::RunPlane(peer, t, o);
  if (!o.filter_yaws.empty() || o.flicker_frames > 1) {
    auto textures = aperture::LoadBenchTextures(o.filter_textures, o.data_dir);
    if (!textures.ok()) {
      std::fprintf(stderr, "peer_bench: %s\n", std::string(textures.status().message()).c_str());
      return 1;
    }
    for (size_t t = 0; t < textures->size(); ++t) {
      aperture::FilterPeers filters(peer, (*textures)[t]);
      if (!o.filter_yaws.empty()) aperture::RunFilterQuality(filters, (*textures)[t], o);
      if (o.flicker_frames > 1 && t == 0) aperture::RunFlicker(filters, o);
    }
  }
  return 0;
}
