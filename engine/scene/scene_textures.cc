#include "scene/scene_textures.h"

#include <filesystem>

#include "absl/strings/str_cat.h"
#include "scene/scene_environment.h"
#include "texture/image_file.h"
#include "texture/packed/apv_file.h"
#include "texture/packed/packed_sampler.h"
#include "texture/texture_entries.h"

namespace aperture {
namespace {

constexpr int kMaxCheckerboardSize = 8192;  // as kMaxImageTexels

absl::Status Invalid(const std::string& where, const std::string& what) {
  return absl::InvalidArgumentError(absl::StrCat(where, ": ", what));
}

// A packed texture decoded from .apv bytes: in the store when there is one, else in memory.
absl::StatusOr<std::shared_ptr<const SceneTexture>> BuildPackedTexture(
    const std::string& id, std::span<const uint8_t> apv_bytes, const SceneBuildOptions& opt) {
  if (!opt.store) {
    auto texture = packed::DecodeApv(apv_bytes);
    if (!texture.ok()) return texture.status();
    return MakePackedSceneTexture(id, *std::move(texture));
  }
  auto entry = GetOrDecodePackedTexture(*opt.store, apv_bytes);
  if (!entry.ok()) return entry.status();
  const auto payload = (*entry)->payload();
  auto view = packed::PackedTextureView::FromBytes(
      {reinterpret_cast<const uint8_t*>(payload.data()), payload.size()});
  if (!view.ok()) return view.status();
  return MakePackedSceneTexture(id, *std::move(entry), *view);
}

}  // namespace

absl::StatusOr<std::shared_ptr<const SceneTexture>> BuildSceneTexture(
    const v1::Texture& t, const std::string& where, const SceneBuildOptions& opt) {
  switch (t.source_case()) {
    case v1::Texture::kFile: {
      std::filesystem::path path(t.file());
      if (path.is_relative() && !opt.base_dir.empty()) path = opt.base_dir / path;
      if (path.extension() == ".apv") {
        auto bytes = packed::ReadFileBytes(path.string());
        auto packed = bytes.ok() ? BuildPackedTexture(t.id(), *bytes, opt) : bytes.status();
        if (!packed.ok())
          return absl::Status(packed.status().code(),
                              absl::StrCat(where, ": ", packed.status().message()));
        return packed;
      }
      auto image = LoadImageFile(path.string());
      if (!image.ok())
        return absl::Status(image.status().code(),
                            absl::StrCat(where, ": ", image.status().message()));
      return MakeSceneTexture(t.id(), std::move(*image), opt.store);
    }
    case v1::Texture::kEncoded: {
      auto bytes =
          std::span(reinterpret_cast<const uint8_t*>(t.encoded().data()), t.encoded().size());
      if (packed::LooksLikeApv(bytes)) {
        auto packed = BuildPackedTexture(t.id(), bytes, opt);
        if (!packed.ok()) return Invalid(where, std::string(packed.status().message()));
        return packed;
      }
      auto image = DecodeImage(bytes);
      if (!image.ok()) return Invalid(where, std::string(image.status().message()));
      return MakeSceneTexture(t.id(), std::move(*image), opt.store);
    }
    case v1::Texture::kCheckerboard: {
      const v1::Checkerboard& c = t.checkerboard();
      const int size =
          c.size() == 0 ? 1024 : static_cast<int>(std::min<uint32_t>(c.size(), 1u << 30));
      const int cells =
          c.cells() == 0 ? 8 : static_cast<int>(std::min<uint32_t>(c.cells(), 1u << 30));
      if (size > kMaxCheckerboardSize)
        return Invalid(
            where, absl::StrCat("checkerboard size ", size, " is above ", kMaxCheckerboardSize));
      if (cells > size) return Invalid(where, "checkerboard has more cells than texels");
      Rgba a{1, 1, 1, 1}, b{0, 0, 0, 1};
      if (c.has_color_a()) {
        auto ca = ColorFromProto(c.color_a(), where + ".checkerboard.color_a");
        if (!ca.ok()) return ca.status();
        a = *ca;
      }
      if (c.has_color_b()) {
        auto cb = ColorFromProto(c.color_b(), where + ".checkerboard.color_b");
        if (!cb.ok()) return cb.status();
        b = *cb;
      }
      return MakeSceneTexture(t.id(), MakeCheckerboard(size, cells, a, b), opt.store);
    }
    case v1::Texture::SOURCE_NOT_SET:
      break;
  }
  return Invalid(where, "texture has no source (file, encoded or checkerboard)");
}

std::optional<FilterMode> FilterModeFromProto(int filter) {
  switch (filter) {
    case v1::TEXTURE_FILTER_NEAREST:
      return FilterMode::kNearest;
    case v1::TEXTURE_FILTER_BILINEAR:
      return FilterMode::kBilinear;
    case v1::TEXTURE_FILTER_TRILINEAR:
      return FilterMode::kTrilinear;
    case v1::TEXTURE_FILTER_ANISO:
      return FilterMode::kAniso;
    case v1::TEXTURE_FILTER_OIIO:
      return FilterMode::kOiio;
    case v1::TEXTURE_FILTER_REFERENCE:
      return FilterMode::kReference;
    default:
      return std::nullopt;
  }
}

absl::StatusOr<const TextureSampler*> SceneTexture::Sampler(
    FilterMode mode, const std::function<bool()>& stop) const {
  if (packed) return mode == FilterMode::kNearest ? packed_nearest.get() : packed_area.get();
  switch (mode) {
    case FilterMode::kNearest:
      return nearest.get();
    case FilterMode::kBilinear:
      return bilinear.get();
    case FilterMode::kTrilinear:
      return trilinear.get();
    case FilterMode::kAniso:
    case FilterMode::kOiio:
    case FilterMode::kReference:
      break;
  }
  auto sampler = footprint->Get(mode, stop);
  if (!sampler.ok())
    return absl::Status(sampler.status().code(),
                        absl::StrCat("texture '", id, "': ", sampler.status().message()));
  return *sampler;
}

std::shared_ptr<const SceneTexture> MakePackedSceneTexture(std::string id,
                                                           std::shared_ptr<const void> owner,
                                                           const packed::PackedTextureView& view) {
  auto scene_texture = std::make_shared<SceneTexture>();
  scene_texture->id = std::move(id);
  scene_texture->packed_nearest =
      std::make_unique<packed::PackedTextureSampler>(view, packed::PackedSampling::kNearest);
  scene_texture->packed_area =
      std::make_unique<packed::PackedTextureSampler>(view, packed::PackedSampling::kArea);
  scene_texture->packed = std::move(owner);
  return scene_texture;
}

std::shared_ptr<const SceneTexture> MakePackedSceneTexture(std::string id,
                                                           packed::PackedTexture texture) {
  auto shared = std::make_shared<const packed::PackedTexture>(std::move(texture));
  const packed::PackedTextureView view = shared->view();
  return MakePackedSceneTexture(std::move(id), std::move(shared), view);
}

std::shared_ptr<const SceneTexture> MakeSceneTexture(std::string id, Image image,
                                                     std::shared_ptr<const SharedStore> store) {
  auto texture = std::make_shared<SceneTexture>();
  texture->id = std::move(id);
  for (const Rgba& t : image.texels())
    if (t.a < 1.0f) {
      texture->has_alpha = true;
      break;
    }
  auto pyramid = std::make_shared<MipPyramid>(ResizeToPowerOfTwo(image));
  texture->nearest = std::make_unique<NearestSampler>(*pyramid);
  texture->bilinear = std::make_unique<BilinearSampler>(*pyramid);
  texture->trilinear = std::make_unique<TrilinearSampler>(*pyramid);
  texture->footprint = std::make_unique<FootprintSamplers>(pyramid->level(0), std::move(store));
  texture->pyramid = std::move(pyramid);
  return texture;
}

}  // namespace aperture
