#include "texture/aniso_sampler.h"

#include <algorithm>

#include "texture/footprint_batch.h"

namespace aperture {

AnisoSampler::AnisoSampler(PrefilteredTable table, const AnisoOptions& options)
    : table_(std::move(table)), selector_(table_, options), reader_(table_) {}

Rgba AnisoSampler::SampleCopy(const CopyEntry& e, double u, double v, double tg) const {
  // One reading of one copy, weight 1: the reader's plain skewed bilinear read.
  SelectionLanes s{};
  s.reading_weight[0][0] = 1.0f;
  s.tg[0][0] = static_cast<float>(tg);
  s.copy[0][0][0] = static_cast<uint32_t>(&e - table_.directory().data());
  s.weight[0][0][0] = 1.0f;
  Rgba out;
  reader_.Read(s, &u, &v, 1, &out);
  return out;
}

Rgba AnisoSampler::Sample(const TextureFootprint& f) const {
  Rgba out;
  SampleLanes(&f.dudx, &f.dvdx, &f.dudy, &f.dvdy, &f.u, &f.v, 1, &out);
  return out;
}

void AnisoSampler::SampleLanes(const float* dudx, const float* dvdx, const float* dudy,
                               const float* dvdy, const double* u, const double* v, int n,
                               Rgba* out) const {
  SelectionLanes lanes;
  selector_.Select(dudx, dvdx, dudy, dvdy, n, lanes);
  reader_.Read(lanes, u, v, n, out);
}

void AnisoSampler::SampleMany(const TextureFootprint* in, Rgba* out, int count) const {
  // Groups of eight as arrays (the selection's lanes).
  constexpr int kGroup = SelectionLanes::kLanes;
  alignas(32) float dudx[kGroup], dvdx[kGroup], dudy[kGroup], dvdy[kGroup];
  double u[kGroup], v[kGroup];
  for (int first = 0; first < count; first += kGroup) {
    const int n = std::min(kGroup, count - first);
    for (int i = 0; i < n; ++i) {
      const TextureFootprint& f = in[first + i];
      dudx[i] = f.dudx, dvdx[i] = f.dvdx, dudy[i] = f.dudy, dvdy[i] = f.dvdy;
      u[i] = f.u, v[i] = f.v;
    }
    SampleLanes(dudx, dvdx, dudy, dvdy, u, v, n, out + first);
  }
}

void AnisoSampler::SampleBatch(const FootprintBatch& in, Rgba* out) const {
  constexpr int kGroup = SelectionLanes::kLanes;
  for (int first = 0; first < in.count; first += kGroup)
    SampleLanes(in.dudx + first, in.dvdx + first, in.dudy + first, in.dvdy + first, in.u + first,
                in.v + first, std::min(kGroup, in.count - first), out + first);
}

}  // namespace aperture
