// EXR codecs for frames sent over a network: for each built-in scene, size and compression, the
// bytes of one frame, the encode time (the engine's encoder, as the server runs it), the decode
// time (OpenImageIO, as a client or display would read it), the link a 30 Hz stream needs and the
// PSNR against the half-float frame (compression none), on sRGB-encoded RGB
// (support/srgb_psnr.h). Prints a Markdown table; scripts/bench-codecs.sh runs it.
//
//   codec_bench --scenes airport --sizes 1280x720,1920x1080 --codecs none,zip,b44a --repeat 5
// Protobuf's headers before OpenImageIO's, whose farmhash.h #undefs the bswap_32 and bswap_64
// that protobuf's port.h needs.
// clang-format off
#include "aperture/v1/render_service.pb.h"
// clang-format on
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_split.h"
#include "base/stopwatch.h"
#include "frame/camera_proto.h"
#include "frame/frame_job.h"
#include "io/exr_writer.h"
#include "render/frame_renderer.h"
#include "scene/builtin_scenes.h"
#include "scene/scene_builder.h"
#include "support/srgb_psnr.h"

ABSL_FLAG(std::string, scenes, "airport", "built-in scenes, comma-separated");
ABSL_FLAG(std::string, sizes, "1280x720,1920x1080", "frame sizes WxH, comma-separated");
ABSL_FLAG(std::string, codecs, "none,zip,zips,piz,dwaa,dwab,b44,b44a,rle",
          "EXR compressions, comma-separated");
ABSL_FLAG(int, repeat, 5, "encodes and decodes of each frame; the fastest is reported");
ABSL_FLAG(int, threads, 2, "threads of the render, the encoder and OpenEXR's decoder");
ABSL_FLAG(double, rate_hz, 30, "the frame rate the link figure is for");

namespace aperture {
namespace {

struct Size {
  int width = 0, height = 0;
};

std::vector<Size> ParseSizes(const std::string& text) {
  std::vector<Size> sizes;
  for (absl::string_view item : absl::StrSplit(text, ',', absl::SkipEmpty())) {
    std::vector<std::string> wh = absl::StrSplit(item, 'x');
    Size s;
    if (wh.size() != 2 || !absl::SimpleAtoi(wh[0], &s.width) ||
        !absl::SimpleAtoi(wh[1], &s.height) || s.width <= 0 || s.height <= 0) {
      std::fprintf(stderr, "codec_bench: --sizes: '%s' is not WxH\n", std::string(item).c_str());
      std::exit(2);
    }
    sizes.push_back(s);
  }
  return sizes;
}

absl::StatusOr<ExrCompression> CompressionNamed(const std::string& name) {
  for (ExrCompression c : {ExrCompression::kNone, ExrCompression::kRle, ExrCompression::kZips,
                           ExrCompression::kZip, ExrCompression::kPiz, ExrCompression::kDwaa,
                           ExrCompression::kB44, ExrCompression::kB44a, ExrCompression::kDwab})
    if (name == ExrCompressionName(c)) return c;
  return absl::InvalidArgumentError("--codecs: unknown compression '" + name + "'");
}

// The file's pixels as float RGBA, read from memory by OpenImageIO (OpenEXR's C++ library).
absl::StatusOr<std::vector<float>> Decode(const std::string& bytes) {
  OIIO::Filesystem::IOMemReader reader(bytes.data(), bytes.size());
  OIIO::ImageSpec config;
  void* proxy = &reader;
  config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  auto in = OIIO::ImageInput::open("frame.exr", &config, &reader);
  if (!in) return absl::InternalError("OpenImageIO cannot open the frame: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.nchannels != 4) return absl::InternalError("the frame is not RGBA");
  std::vector<float> pixels(static_cast<size_t>(spec.width) * spec.height * 4);
  if (!in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, pixels.data()))
    return absl::InternalError("OpenImageIO cannot read the frame: " + in->geterror());
  return pixels;
}

struct Measured {
  size_t bytes = 0;
  double encode_ms = 1e300, decode_ms = 1e300, psnr = 0;
};

absl::StatusOr<Measured> Measure(const Image& image, ExrOptions exr, int repeat, int threads,
                                 const std::vector<float>* reference,
                                 std::vector<float>* decoded_out = nullptr) {
  Measured m;
  std::string bytes;
  for (int i = 0; i < repeat; ++i) {
    const Stopwatch timer;
    auto encoded = EncodeExr(image, exr);
    const double ms = timer.Milliseconds();
    if (!encoded.ok()) return encoded.status();
    m.encode_ms = std::min(m.encode_ms, ms);
    bytes = *std::move(encoded);
  }
  m.bytes = bytes.size();
  std::vector<float> decoded;
  for (int i = 0; i < repeat; ++i) {
    // dwaa and dwab encode with OpenEXR's pool off (io/exr_writer.cc); decoding gets `threads`.
    OIIO::attribute("exr_threads", threads);
    const Stopwatch timer;
    auto pixels = Decode(bytes);
    const double ms = timer.Milliseconds();
    if (!pixels.ok()) return pixels.status();
    m.decode_ms = std::min(m.decode_ms, ms);
    decoded = *std::move(pixels);
  }
  const std::vector<float>& against = reference != nullptr ? *reference : decoded;
  m.psnr = testing::SrgbPsnr(decoded.data(), against.data(), decoded.size() / 4);
  if (decoded_out != nullptr) *decoded_out = std::move(decoded);
  return m;
}

int Run() {
  const int repeat = std::max(1, absl::GetFlag(FLAGS_repeat));
  const int threads = std::max(1, absl::GetFlag(FLAGS_threads));
  const double rate = absl::GetFlag(FLAGS_rate_hz);
  std::vector<ExrCompression> codecs;
  const std::vector<std::string> codec_names =
      absl::StrSplit(absl::GetFlag(FLAGS_codecs), ',', absl::SkipEmpty());
  for (const std::string& name : codec_names) {
    auto c = CompressionNamed(name);
    if (!c.ok()) {
      std::fprintf(stderr, "codec_bench: %s\n", std::string(c.status().message()).c_str());
      return 2;
    }
    codecs.push_back(*c);
  }
  const std::vector<Size> sizes = ParseSizes(absl::GetFlag(FLAGS_sizes));
  std::printf(
      "EXR codecs, RGBA half; encode: the engine's encoder on %d threads; decode: OpenImageIO %s "
      "on %d threads; fastest of %d each; link: bytes x 8 x %g Hz; PSNR: R, G, B clamped to "
      "[0, 1] and sRGB-encoded, peak 1, against the frame with compression none\n\n",
      threads, OIIO_VERSION_STRING, threads, repeat, rate);
  std::printf(
      "| scene | size | codec | bytes / frame | of none | encode ms | decode ms | Gbit/s at %g Hz "
      "| PSNR dB |\n|---|---|---|---:|---:|---:|---:|---:|---:|\n",
      rate);
  std::fflush(stdout);
  const std::vector<std::string> scene_names =
      absl::StrSplit(absl::GetFlag(FLAGS_scenes), ',', absl::SkipEmpty());
  for (const std::string& name : scene_names) {
    auto builtin = FindBuiltinScene(name);
    if (!builtin.ok()) {
      std::fprintf(stderr, "codec_bench: %s\n", std::string(builtin.status().message()).c_str());
      return 2;
    }
    auto scene = BuildScene(builtin->scene);
    if (!scene.ok()) {
      std::fprintf(stderr, "codec_bench: %s\n", std::string(scene.status().message()).c_str());
      return 1;
    }
    for (const Size& size : sizes) {
      // The frame aperture-render and the service make of the scene's own camera at this size.
      v1::RenderFrameRequest request;
      *request.mutable_camera() = CameraToProto(builtin->camera);
      request.mutable_options()->set_width(static_cast<uint32_t>(size.width));
      request.mutable_options()->set_height(static_cast<uint32_t>(size.height));
      auto job = FrameJobFromRequest(request);
      if (!job.ok()) {
        std::fprintf(stderr, "codec_bench: %s\n", std::string(job.status().message()).c_str());
        return 2;
      }
      job->settings.threads = threads;
      auto frame = RenderFrame(*scene, job->camera, job->settings);
      if (!frame.ok()) {
        std::fprintf(stderr, "codec_bench: %s\n", std::string(frame.status().message()).c_str());
        return 1;
      }
      ExrOptions exr = job->exr;
      exr.threads = threads;
      exr.metadata =
          FrameMetadata(scene->name, job->camera, *frame, size.width, size.height, "raster");
      // The half-float frame every codec is measured against.
      exr.compression = ExrCompression::kNone;
      std::vector<float> reference;
      auto none = Measure(frame->image, exr, 1, threads, nullptr, &reference);
      if (!none.ok()) {
        std::fprintf(stderr, "codec_bench: %s\n", std::string(none.status().message()).c_str());
        return 1;
      }
      for (ExrCompression c : codecs) {
        exr.compression = c;
        auto m = Measure(frame->image, exr, repeat, threads, &reference);
        if (!m.ok()) {
          std::fprintf(stderr, "codec_bench: %s: %s\n", ExrCompressionName(c),
                       std::string(m.status().message()).c_str());
          return 1;
        }
        const std::string psnr =
            std::isinf(m->psnr) ? "lossless" : absl::StrFormat("%.1f", m->psnr);
        std::printf("| %s | %dx%d | %s | %zu | %.1f %% | %.1f | %.1f | %.3f | %s |\n", name.c_str(),
                    size.width, size.height, ExrCompressionName(c), m->bytes,
                    100.0 * static_cast<double>(m->bytes) / static_cast<double>(none->bytes),
                    m->encode_ms, m->decode_ms, static_cast<double>(m->bytes) * 8 * rate / 1e9,
                    psnr.c_str());
        std::fflush(stdout);
      }
    }
  }
  return 0;
}

}  // namespace
}  // namespace aperture

int main(int argc, char** argv) {
  absl::ParseCommandLine(argc, argv);
  return aperture::Run();
}
