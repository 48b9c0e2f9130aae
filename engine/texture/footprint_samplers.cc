#include "texture/footprint_samplers.h"

#include <spdlog/spdlog.h>
#include <tbb/task_arena.h>

#include "absl/strings/str_cat.h"
#include "base/stopwatch.h"
#include "texture/aniso_sampler.h"
#include "texture/oiio_sampler.h"
#include "texture/prefiltered_table_builder.h"
#include "texture/reference_sampler.h"
#include "texture/texture_entries.h"

namespace aperture {

FootprintSamplers::~FootprintSamplers() = default;

absl::Status FootprintSamplers::PrepareAniso(const std::function<bool()>& stop) const {
  if (aniso_done_.load(std::memory_order_acquire)) return aniso_status_;
  std::lock_guard<std::mutex> lock(aniso_mutex_);
  if (aniso_done_.load(std::memory_order_relaxed)) return aniso_status_;
  {
    const Stopwatch timer;
    // Isolated: while waiting for its own parallel loops this thread must not pick up an outer
    // task that could ask for the same table.
    tbb::this_task_arena::isolate([&] {
      std::span<const std::byte> bytes;
      if (store_) {
        auto entry = GetOrBuildPrefilteredTable(*store_, base_, stop);
        if (!entry.ok()) {
          aniso_status_ = entry.status();
          return;
        }
        bytes = (*entry)->payload();
        table_bytes_ = *std::move(entry);
      } else {
        TableBuildOptions options;
        options.stop = stop;
        auto block = BuildPrefilteredTable(base_, options);
        if (!block.ok()) {
          aniso_status_ = block.status();
          return;
        }
        auto owned = std::make_shared<TableBlock>(*std::move(block));
        bytes = owned->bytes;
        table_bytes_ = std::move(owned);
      }
      auto view = PrefilteredTable::View(bytes);
      if (!view.ok()) {
        aniso_status_ = view.status();
        return;
      }
      aniso_ = std::make_unique<AnisoSampler>(*view);
      // A 4096 x 4096 texture's table takes half a minute to build: say where the time went.
      const double ms = timer.Milliseconds();
      spdlog::info("seed 000 table of a {}x{} texture ready in {:.0f} ms ({} bytes{})",
                   base_.width(), base_.height(), ms, bytes.size(),
                   store_ ? ", built or mapped from the shared store" : "");
    });
    // A stopped build is not an answer: the next caller builds again.
    if (absl::IsCancelled(aniso_status_)) {
      const absl::Status stopped = aniso_status_;
      aniso_status_ = absl::OkStatus();
      return stopped;
    }
    if (!aniso_status_.ok())
      aniso_status_ = absl::Status(
          aniso_status_.code(), absl::StrCat("the aniso filter (seed 000 table) cannot be built: ",
                                             aniso_status_.message()));
  }
  aniso_done_.store(true, std::memory_order_release);
  return aniso_status_;
}

absl::StatusOr<const TextureSampler*> FootprintSamplers::Get(
    FilterMode mode, const std::function<bool()>& stop) const {
  switch (mode) {
    case FilterMode::kAniso:
      if (auto s = PrepareAniso(stop); !s.ok()) return s;
      return aniso_.get();
    case FilterMode::kOiio:
      std::call_once(oiio_once_, [&] {
        auto sampler = OiioSampler::Create(base_);
        if (sampler.ok()) {
          oiio_ = std::move(*sampler);
        } else {
          oiio_status_ = absl::Status(
              sampler.status().code(),
              absl::StrCat("the oiio filter (OpenImageIO's TextureSystem) cannot be built: ",
                           sampler.status().message()));
        }
      });
      if (!oiio_status_.ok()) return oiio_status_;
      return oiio_.get();
    case FilterMode::kReference:
      std::call_once(reference_once_,
                     [&] { reference_ = std::make_unique<ReferenceSampler>(base_); });
      return reference_.get();
    case FilterMode::kNearest:
    case FilterMode::kBilinear:
    case FilterMode::kTrilinear:
      break;
  }
  return absl::InvalidArgumentError(absl::StrCat(
      "the ", FilterModeName(mode), " filter is the mip-map's, not a footprint filter"));
}

}  // namespace aperture
