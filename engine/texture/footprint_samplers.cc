#include "texture/footprint_samplers.h"

#include <spdlog/spdlog.h>
#include <tbb/task_arena.h>

#include "texture/aniso_sampler.h"
#include "texture/oiio_sampler.h"
#include "texture/prefiltered_table_builder.h"
#include "texture/reference_sampler.h"

namespace aperture {

FootprintSamplers::~FootprintSamplers() = default;

const TextureSampler& FootprintSamplers::Get(FilterMode mode,
                                             const TextureSampler& fallback) const {
  switch (mode) {
    case FilterMode::kAniso:
      std::call_once(aniso_once_, [&] {
        // Isolated: while waiting for its own parallel loops this thread must not pick up an
        // outer task that could ask for the same table.
        tbb::this_task_arena::isolate([&] {
          auto block = BuildPrefilteredTable(base_);
          if (!block.ok()) {
            spdlog::error("aniso filter unavailable, using trilinear: {}",
                          block.status().ToString());
            return;
          }
          table_ = std::move(*block);
          auto view = table_.View();
          if (view.ok()) aniso_ = std::make_unique<AnisoSampler>(*view);
        });
      });
      return aniso_ ? *aniso_ : fallback;
    case FilterMode::kOiio:
      std::call_once(oiio_once_, [&] {
        auto sampler = OiioSampler::Create(base_);
        if (sampler.ok()) {
          oiio_ = std::move(*sampler);
        } else {
          spdlog::error("oiio filter unavailable, using trilinear: {}",
                        sampler.status().ToString());
        }
      });
      return oiio_ ? *oiio_ : fallback;
    case FilterMode::kReference:
      std::call_once(reference_once_,
                     [&] { reference_ = std::make_unique<ReferenceSampler>(base_); });
      return *reference_;
    case FilterMode::kNearest:
    case FilterMode::kBilinear:
    case FilterMode::kTrilinear:
      break;
  }
  return fallback;
}

}  // namespace aperture
