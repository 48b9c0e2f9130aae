#include "texture/oiio_sampler.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/texture.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>

#include "absl/strings/str_cat.h"

namespace aperture {

struct OiioSampler::State {
  OIIO::TextureSystem* system = nullptr;
  OIIO::TextureSystem::TextureHandle* handle = nullptr;
  OIIO::TextureOpt options;  // OpenImageIO's defaults but periodic wrap, and OiioOptions
  std::string tx_path;
  bool remove_file = false;

  ~State() {
    if (system != nullptr) OIIO::TextureSystem::destroy(system);
    if (remove_file) {
      std::error_code ignored;
      std::filesystem::remove(tx_path, ignored);
    }
  }
};

OiioSampler::OiioSampler(std::unique_ptr<State> state) : state_(std::move(state)) {}
OiioSampler::~OiioSampler() = default;

absl::StatusOr<std::unique_ptr<OiioSampler>> OiioSampler::Create(const Image& image,
                                                                 std::string tx_path,
                                                                 const OiioOptions& options) {
  if (options.anisotropic < 1)
    return absl::InvalidArgumentError("oiio sampler: anisotropic must be at least 1");
  if (image.empty()) return absl::InvalidArgumentError("oiio sampler: empty image");
  auto state = std::make_unique<State>();
  if (tx_path.empty()) {
    static std::atomic<int> counter{0};
    tx_path = (std::filesystem::temp_directory_path() /
               absl::StrCat("aperture-oiio-", getpid(), "-", counter++, ".tx"))
                  .string();
    state->remove_file = true;
  }
  state->tx_path = tx_path;
  // maketx: tiled, mip-mapped, 8-bit like the source, periodic wrap recorded in the file.
  OIIO::ImageSpec spec(image.width(), image.height(), 4, OIIO::TypeDesc::FLOAT);
  OIIO::ImageBuf src(spec, const_cast<Rgba*>(image.texels().data()));
  OIIO::ImageSpec config;
  config.set_format(OIIO::TypeDesc::UINT8);
  config.attribute("wrapmodes", "periodic,periodic");
  config.attribute("maketx:fileformatname", "tiff");
  if (!OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxTexture, src, tx_path, config))
    return absl::InternalError(absl::StrCat("oiio sampler: make_texture: ", OIIO::geterror()));
  state->system = OIIO::TextureSystem::create(/*shared=*/false);
  state->system->attribute("max_memory_MB", 1024.0f);
  state->handle = state->system->get_texture_handle(OIIO::ustring(tx_path));
  if (state->handle == nullptr)
    return absl::InternalError(absl::StrCat("oiio sampler: cannot open ", tx_path));
  state->options.swrap = OIIO::TextureOpt::WrapPeriodic;
  state->options.twrap = OIIO::TextureOpt::WrapPeriodic;
  state->options.anisotropic = options.anisotropic;
  if (options.bilinear) state->options.interpmode = OIIO::TextureOpt::InterpBilinear;
  return std::unique_ptr<OiioSampler>(new OiioSampler(std::move(state)));
}

Rgba OiioSampler::Sample(const TextureFootprint& f) const {
  OIIO::TextureOpt options = state_->options;
  float result[4] = {0, 0, 0, 0};
  OIIO::TextureSystem::Perthread* thread = state_->system->get_perthread_info();
  // (s, t) = (u, v): t = 0 is the first image row, as here.
  state_->system->texture(state_->handle, thread, options, static_cast<float>(f.u),
                          static_cast<float>(f.v), f.dudx, f.dvdx, f.dudy, f.dvdy, 4, result);
  return {result[0], result[1], result[2], result[3]};
}

}  // namespace aperture
