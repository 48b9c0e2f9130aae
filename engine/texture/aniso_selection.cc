#include "texture/aniso_selection.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

namespace aperture {
namespace {

// Derivatives are clamped to this many texels: a footprint past 2^(3n) (n <= 13) is capped by
// the table anyway, and the squares stay finite in float.
constexpr float kMaxTexels = 0x1p40f;
// Below this second moment (texels^2) the footprint is a point: the base, bilinear.
constexpr float kMinMoment = 1e-30f;
// Base probes carry the thin apertures up to this half-extent, fading out to twice it.
constexpr float kProbeHalfExtent = 4.0f;
// Probes are this many texels apart along the long side once more than two are needed (1.125
// read 0.4-0.6 dB worse on the asphalt photo at pitch 5, a = 1, and saved 2-4 % of a frame).
constexpr float kProbeSpacing = 1.0f;
// The box probes (AddBoxProbesLane): apertures thinner than this half-thickness, whole up to
// kBoxProbeThickness - 1 / kBoxProbeFade = 1.25 and fading into the table's copies above it.
// Their two rows double the reads. The demo frame's aniso time over the sampler without box
// probes, in trilinear frames: +1.8 % with these constants, +5.6 % fading out up to 1.5 instead
// (thickness 1.5, fade 4) and +18 % whole up to 1.75 (thickness 2), for 0.06 and 0.43 dB more
// on the asphalt photo at pitch 20, a = 2 (aperture-bench filter).
constexpr float kBoxProbeThickness = 1.375f;
constexpr float kBoxProbeFade = 8.0f;
// The box probes' spacing: the first copy's box is 2 texels wide.
constexpr float kBoxProbeSpacing = 2.0f;

// x = 2^e (1 + m) with 0 <= m < 1, for finite x >= 1 (from the bits, exact).
struct PowerOfTwoSplit {
  int e;
  float m;
};
inline PowerOfTwoSplit SplitPowerOfTwo(float x) {
  const uint32_t bits = std::bit_cast<uint32_t>(x);
  const float mantissa = std::bit_cast<float>((bits & 0x7fffffu) | 0x3f800000u);
  return {static_cast<int>(bits >> 23) - 127, mantissa - 1.0f};
}

// 2^e for -126 <= e <= 127.
inline float PowerOfTwo(int e) {
  return std::bit_cast<float>(static_cast<uint32_t>(127 + e) << 23);
}

// Between the two tilts nearest the tangent, the next one's weight by the fraction of the way
// from the lower tilt's centre to the next one's: the nearer tilt alone within a quarter of the
// spacing of its centre, a linear blend over the middle half. Continuous, and half the samples
// read one tilt (a blend over the whole spacing cost 2 ms more a demo frame for 0.03 dB).
inline float NextTiltWeight(float fraction) {
  return std::clamp(2.0f * fraction - 0.5f, 0.0f, 1.0f);
}

// Where tangent tg falls among a cell's tilts (TiltTangent), as a fractional index: tilt k at k.
// Seed 000's tilts (indices 1 .. half, half = lambda / 2) lie evenly at x = (tg + 1) half / 2 +
// 1/2; the ends, -1 at index 0 and +1 at half + 1, are half a spacing beyond the outer ones
// (x = 1/2 and half + 1/2), so those two intervals are stretched to a whole index.
// `tilt_position` is (tg + 1) / 2.
inline float TiltIndex(float tilt_position, float half) {
  const float x = std::clamp(tilt_position * half + 0.5f, 0.5f, half + 0.5f);
  if (x < 1.0f) return 2.0f * x - 1.0f;
  if (half < x) return 2.0f * x - half;
  return x;
}

// The readings of one footprint (ReadingsOfFootprint). The table's copies are parallelograms with a
// pair of sides parallel to a texture axis: half extent H along the major axis with slope tg,
// half thickness L along the minor one, i.e. {s H (1, tg) + t L (0, 1)} (axes named major,
// minor). Seed 000 reads H, L and tg off the pixel parallelogram's bounding extents (eq. 3-4),
// which depend on how the footprint is turned against the texture: a square footprint turned
// 45 degrees gets a copy of twice its area. Our reading: the copy with the pixel
// parallelogram's second moments,
//   H^2 (1, tg) (1, tg)^T + L^2 (0, 1) (0, 1)^T = X X^T + Y Y^T,
// the Cholesky factor of the right side: H^2 = M_major, tg = M_cross / M_major,
// L = |X x Y| / H. The copy then has the pixel's area and its variance in every direction, so
// a footprint and the same footprint turned get copies of equal area and shape; along a
// texture axis (Y parallel to the major axis, or X and Y along the axes) it is the paper's.
// Along the axis of the larger moment |tg| <= 1, as the table's tilts need; along the other one
// (only inside the zone) |tg| stays under 1.14.
struct LaneReadings {
  bool valid = false;   // finite derivatives and a footprint larger than a point
  bool u_major = true;  // the first reading is along U
  float first = 0;      // the first reading's weight; the second's is 1 - first
  float H[2] = {}, L[2] = {}, tg[2] = {};
  // The moments of the pixel's half-axes X = (dUx, dVx), Y = (dUy, dVy) (texels, clamped) and
  // |X x Y|: the magnified taps' inputs.
  float uu = 0, uv = 0, vv = 0, area = 0;
};

LaneReadings ReadLane(float dudx, float dvdx, float dudy, float dvdy, float half_size) {
  // seed 000, eq. 2: one pixel step of the paper's 2 x 2 aperture is half the a-scaled
  // derivative (a = 2); in texel units. The pixel's aperture is then the parallelogram
  // {s X + t Y : |s|, |t| <= 1} with X = (dUx, dVx), Y = (dUy, dVy).
  float d[4] = {dudx * half_size, dvdx * half_size, dudy * half_size, dvdy * half_size};
  LaneReadings out;
  bool finite = true;
  for (float& x : d) {
    finite = finite && std::isfinite(x);
    x = std::clamp(x, -kMaxTexels, kMaxTexels);
  }
  const float dUx = d[0], dVx = d[1], dUy = d[2], dVy = d[3];
  const float uu = dUx * dUx + dUy * dUy, vv = dVx * dVx + dVy * dVy;
  const float uv = dUx * dVx + dUy * dVy;
  const float area = std::abs(dUx * dVy - dVx * dUy);  // |X x Y|
  const float total = uu + vv;
  if (!finite || !(total >= kMinMoment)) return out;
  out.valid = true;
  out.uu = uu, out.uv = uv, out.vv = vv, out.area = area;
  // The first reading along the larger moment; its weight 1 outside the zone, else
  // 1/2 + |M_uu - M_vv| / (2 zone), 1/2 on the diagonal. The zone is a band of the long axis's
  // angle phi to U: |M_uu - M_vv| = |cos 2 phi| D with D = sqrt((M_uu - M_vv)^2 + 4 M_uv^2),
  // the difference of the moments along the principal axes, so nearly round footprints (D
  // small, whose two readings nearly agree) are not all in it.
  const float difference = uu - vv, cross = 2.0f * uv;
  const float zone = kAxisBlendZone * std::sqrt(difference * difference + cross * cross);
  out.u_major = difference >= 0.0f;
  const float spread = std::abs(difference);
  out.first = spread >= zone ? 1.0f : 0.5f + 0.5f * (spread / zone);
  const float major = out.u_major ? uu : vv, minor = out.u_major ? vv : uu;
  // The second reading along the other axis (only read inside the zone, where minor is close
  // to major; outside it the first's moment keeps the arithmetic finite).
  const float majors[2] = {major, out.first < 1.0f ? minor : major};
  for (int r = 0; r < 2; ++r) {
    out.H[r] = std::sqrt(majors[r]);
    const float inv_h = 1.0f / out.H[r];
    out.tg[r] = uv * inv_h * inv_h;
    out.L[r] = area * inv_h;
  }
  return out;
}

// The larger eigenvalue of the symmetric 2 x 2 matrix ((a, c), (c, b)).
inline float LargerEigenvalue(float a, float b, float c) {
  const float half_difference = 0.5f * (a - b);
  return 0.5f * (a + b) + std::sqrt(half_difference * half_difference + c * c);
}

// A magnified reading (H < 1) in the footprint's principal axes. The
// magnification blend (TableSlots, AddProbesLane) reads the base and the first copy, the 2 x 2
// box, neither of them sheared, and puts its probes along (1, tg). With the parallelogram's
// (H, L, tg) its covariance is L^2 / 3 I + (H^2 - L^2) / 3 (1, tg)(1, tg)^T, short of the
// footprint's by L^2 tg / 3 in the cross term and L^2 tg^2 / 3 in the minor one: a turned
// footprint was filtered as if it were turned less. Built from the principal moments
// lambda_1 >= lambda_2 instead (H'^2 = lambda_1, L'^2 = lambda_2 = H^2 L^2 / lambda_1), with the
// probes along the principal axis (slope tp to the major axis), the same blend has the
// covariance L'^2 / 3 I + (H'^2 - L'^2) / 3 e e^T: the footprint's own. The probes' layout is
// computed along the major axis, so their positions are scaled by 1 / sqrt(1 + tp^2). Towards
// H = 1, where the table's copies take over with the parallelogram's values, the principal
// values are blended back by beta = min(1, (1 - H^2) / (2 (H'^2 - H^2))), which also keeps the
// blended H under 1. Returns whether the reading is wholly in the principal axes (beta = 1).
bool MagnifiedInPrincipalAxes(float& H, float& L, float& tg, float& scale) {
  const float major = H * H, L2 = L * L;
  const float cross = tg * major, minor = L2 + tg * cross;
  const float lambda1 = LargerEigenvalue(major, minor, cross);
  const float excess = lambda1 - major, room = 0.5f * (1.0f - major);
  const float beta = excess <= room ? 1.0f : room / excess;
  const float gap = lambda1 - minor;
  const float tp = gap > 0.0f ? cross / gap : 0.0f;
  const float lambda2 = major * L2 / lambda1;
  H = std::sqrt(major + beta * excess);
  L = std::sqrt(L2 + beta * (lambda2 - L2));
  tg = tg + beta * (tp - tg);
  scale = 1.0f + beta * (1.0f / std::sqrt(1.0f + tp * tp) - 1.0f);
  return beta == 1.0f;
}

// The magnified taps. Under a texel the readings' blend (the base and
// the first copy by H^2, or the first copy by L^2 and two probes along the long side, in the
// principal axes) has the footprint's covariance but not its shape: too much weight in its tails
// and at its centre. Against the pixel box on the bilinear texture (RMS over random positions,
// half-extents 0.3-0.85 texel, elongations 1-2.5, angles 0, 22.5 and 45 degrees;
// scripts/magnified-taps-error.py) it scores 48.6 / 45.7 / 72.0 dB on the grass / asphalt /
// brick photos where the taps below score 57.0 / 54.8 / 80.3; on the grass at pitch 60, a = 1, a
// view along a texture axis lost up to 1 dB more than one turned 45 degrees (spread 0.93 dB).
// The taps: the first copy (the 2 x 2 box, covariance I / 3) with the weight beta = det S, and
// four bilinear reads of the base at +-a and +-b sharing 1 - beta, where S = X X^T + Y Y^T (X, Y
// the pixel's half-axes in texels, ReadLane) and
//   (a b) = sqrt(2/3) R,   R = the symmetric square root of S_t = (S - beta I) / (1 - beta),
// so that the taps' covariance (a a^T + b b^T) / 2 = S_t / 3 and the blend's is the pixel box's,
// (beta I + S - beta I) / 3 (every read adds its tent's 1/6 to both). beta <= lambda2 (S's
// smaller eigenvalue) needs lambda1 <= 1.
//  - The shape. Of the four-point rules with that covariance, +-R e_u and +-R e_v put the taps on
//    the texel axes of the footprint's own frame: for a footprint along an axis a cross whose
//    three abscissae (weights 1/4, 1/2, 1/4) have nearly the box's fourth moment along that axis
//    (2/9 h^4 against 1/5 h^4), for one turned 45 degrees the two-point Gauss-Legendre grid of its
//    parallelogram. Along the texel axes the bilinear tent, separable, damps an error least, so
//    that is where the moments matter: the Gauss grid of the pixel's own parallelogram, turned
//    with the footprint, scores the same at 45 degrees, 2.2-3.4 dB less along an axis and 1.3-1.7
//    dB less on average on the three photos.
//  - The share. Below it the rule integrates the bilinear texture inside a small box almost
//    exactly; its error grows as the box crosses texel edges, where the box copy's shrinks.
//    beta = det S = lambda1 lambda2 (the squared area) scores best on average of lambda2 f(lambda1)
//    for f = lambda1^k (k = 0.75, 1, 1.5, 2) and 0.75 lambda1 (the script's --shares).
// R = (S_t + s I) / sqrt(tr S_t + 2 s) with s = sqrt(det S_t) = sqrt(beta (1 - tr S + beta)) /
// (1 - beta) is continuous through round footprints and the diagonals (no principal or reading
// axis is chosen). The taps' share w = clamp(kTapsFade (1 - sqrt(lambda1)), 0, 1) fades them into
// the readings' blend (weights 1 - w) as the long half-axis goes from 1 - 1 / kTapsFade to 1
// texel, so everything stays continuous.
constexpr float kTapsFade = 8.0f;

struct MagnifiedTapsOfLane {
  float share = 0, first = 0, weight = 0;
  float p[2] = {}, q[2] = {};  // a and b, (u, v) texels
};

// The taps of a valid lane from ReadLane's moments uu, uv, vv and area |X x Y|, texels.
MagnifiedTapsOfLane MagnifiedTaps(float uu, float uv, float vv, float area) {
  MagnifiedTapsOfLane out;
  const float lambda1 = LargerEigenvalue(uu, vv, uv);
  const float share = std::clamp(kTapsFade * (1.0f - std::sqrt(lambda1)), 0.0f, 1.0f);
  if (!(share > 0.0f)) return out;
  const float beta = area * area, rest = 1.0f - beta, inv_rest = 1.0f / rest;
  const float trace = uu + vv;
  // S_t's entries, its determinant's root s and the root's normalisation sqrt(tr S_t + 2 s),
  // with sqrt(2/3) folded in.
  const float tu = (uu - beta) * inv_rest, tv = (vv - beta) * inv_rest, tuv = uv * inv_rest;
  const float s = std::sqrt(std::max(0.0f, beta * (1.0f - trace + beta))) * inv_rest;
  const float k = 0.81649658092772603f / std::sqrt((trace - 2.0f * beta) * inv_rest + 2.0f * s);
  out.share = share;
  out.first = share * beta;
  out.weight = 0.25f * (share * rest);
  out.p[0] = (tu + s) * k, out.p[1] = tuv * k;
  out.q[0] = tuv * k, out.q[1] = (tv + s) * k;
  return out;
}

// The 2J evenly spread probes whose positions have the variance t (in units of the spacing^2,
// t > 1/4): J, and e, the weight of the outer two (the 2 (J - 1) inner ones share 1 - 2e).
// Where the count grows, the new outer pair starts at weight 0 (continuous).
struct EvenProbes {
  int J;
  float e;
};
EvenProbes SpreadEvenly(float t) {
  // The smallest J whose 2J evenly weighted probes reach t: (4 J^2 - 1) / 12 >= t.
  // t < 64 / 3 keeps J <= 9; the bound is the read lists' size.
  const int J = std::clamp(static_cast<int>(std::ceil(0.5f * std::sqrt(12.0f * t + 1.0f))), 2,
                           SelectionLanes::kMaxProbes / 2);
  // The 2 (J - 1) inner probes alone have the variance A (e = 0); e solves
  // A + 2 e ((J - 1/2)^2 - A) = t with inner weights (1 - 2 e) / (2 (J - 1)), and
  // (J - 1/2)^2 - A = J (2J - 1) / 3.
  const float Jf = static_cast<float>(J);
  const float A = (4.0f * (Jf - 1.0f) * (Jf - 1.0f) - 1.0f) * (1.0f / 12.0f);
  return {J, std::clamp(1.5f * (t - A) / (Jf * (2.0f * Jf - 1.0f)), 0.0f, 0.5f / Jf)};
}

// Below L = 1 the table's thinnest copies are up to twice too thick across the long side: the
// paper's table stops there. This mixes in bilinear probes of the base, spread along the long
// side, so that the blend's variances are the aperture's own (box of half-sides H and L on the
// bilinear texture: H^2 / 3 + 1/6 along the long side, L^2 / 3 + 1/6 across it, in texels^2).
// Across, a probe carries 1/6 (the bilinear tent alone) and the copies of L = 1 carry
// 1/3 + 1/6, so the copies keep the share L^2 and the probes take 1 - L^2. Along the long side
// the probes' positions must have the variance T (their own tents add the 1/6):
//  - H >= 1: the copies are the table's for (H, 1), T = H^2 / 3, the long side's box;
//  - H < 1: the first copy (2 x 2 box) alone with the share L^2, and T = (H^2 - L^2) /
//    (3 (1 - L^2)) makes the variance along the long side H^2 / 3 + 1/6 too. At H = 1 both are
//    1/3. Under sqrt(T) = 1/8 (nearly round) the magnification blend takes over (see below).
// Every change is continuous: under T = s^2 / 4 (s = kProbeSpacing) two
// probes at +-sqrt(T), faded into the magnification blend under 1/8 texel; above it 2J
// probes s apart, the outer two of weight e growing from 0 (where they appear) to the others'
// (where the next pair appears), e set so that the variance is T. The probes fade out between
// kProbeHalfExtent and twice it. This sets the probes of reading r of a lane when it is read and
// thin; their positions are scaled by the lane's probe_scale (MagnifiedInPrincipalAxes).
// The probes' fade between H = kProbeHalfExtent and twice it (the base and the box probes').
inline float ProbeFade(float H) { return std::min(1.0f, 2.0f - H / kProbeHalfExtent); }

// The base probes' share of a thin reading (L < 1, H < 2 kProbeHalfExtent).
inline float BaseProbeShare(float H, float L) { return ProbeFade(H) * (1.0f - L * L); }

void AddProbesLane(SelectionLanes& out, int r, int lane) {
  out.probes[r][lane] = 0;
  if (!(out.reading_weight[r][lane] > 0.0f)) return;
  const float H = out.H[r][lane], L = std::min(out.L[r][lane], H);
  if (!(L < 1.0f) || H >= 2.0f * kProbeHalfExtent) return;
  const float share = BaseProbeShare(H, L);
  float T = H * H * (1.0f / 3.0f);
  if (H < 1.0f) {
    T = (H * H - L * L) / (3.0f * (1.0f - L * L));
    // Nearly round (the probes under 1/8 texel from the centre): the magnification blend that
    // TableSlots left (base 1 - H^2, first copy H^2: two reads, where the probes take three),
    // faded into the probes' layout as d = sqrt(T) goes from 1/16 to 1/8 texel. Both have the
    // variance H^2 / 3 + 1/6 along the long side; across, the blend has up to d^2 more. (Fading
    // over [1/8, 1/4] instead lost 3.7 dB on the checkerboard at pitch 60, a = 1: the blend is
    // too round there.)
    const float d = std::sqrt(T);
    const float probes = std::clamp(16.0f * d - 1.0f, 0.0f, 1.0f);
    if (probes == 0.0f) return;
    if (probes < 1.0f) {
      out.weight[r][0][lane] = (1.0f - probes) * (1.0f - H * H);  // the base at the centre
      out.weight[r][1][lane] = probes * (L * L) + (1.0f - probes) * (H * H);  // the first copy
      out.probes[r][lane] = 2;
      out.probe_step[r][lane] = 2.0f * d * out.probe_scale[r][lane];
      out.probe_weight[r][lane] = 0.0f;
      out.probe_end_weight[r][lane] = probes * 0.5f * share;
      return;
    }
    out.copy[r][0][lane] = out.copy[r][1][lane];  // the first copy alone
    out.weight[r][0][lane] = 1.0f;
    out.weight[r][1][lane] = 0.0f;
  }
  constexpr float s2 = kProbeSpacing * kProbeSpacing;
  if (T <= 0.25f * s2) {
    out.probes[r][lane] = 2;
    out.probe_step[r][lane] = 2.0f * std::sqrt(T) * out.probe_scale[r][lane];
    out.probe_weight[r][lane] = 0.0f;
    out.probe_end_weight[r][lane] = 0.5f * share;
  } else {
    // In units of the spacing^2; H < 2 kProbeHalfExtent = 8 keeps t under 64 / 3.
    const auto [J, e] = SpreadEvenly(T / s2);
    const float Jf = static_cast<float>(J);
    out.probes[r][lane] = 2 * J;
    out.probe_step[r][lane] = kProbeSpacing * out.probe_scale[r][lane];
    out.probe_end_weight[r][lane] = e * share;
    out.probe_weight[r][lane] = (1.0f - 2.0f * e) / (2.0f * (Jf - 1.0f)) * share;
  }
  for (int s = 0; s < SelectionLanes::kSlots; ++s) out.weight[r][s][lane] *= 1.0f - share;
}

// The box probes. A table copy of half-extent c is read bilinearly
// between texels c apart (CopyExtent), so along each axis its kernel is the box of half-width c
// convolved with a tent of half-width c, where the pixel's box on the bilinear base is the box
// of half-width H convolved with a tent of one texel. Short apertures (the copies of H = 2-4 at
// texels 2-4 apart) were blurred at their ends: the 2-4 texel band of the checkerboard at a = 2
// was up to 1.1 dB behind OpenImageIO's anisotropic 16. The first copy, the 2 x 2 box, is
// stored at full resolution; its bilinear reads kBoxProbeSpacing = 2 texels apart along the long
// side tile the box: for an even H they sum to exactly the pixel's kernel along that side, and
// for any H their positions have the variance T = (H^2 - 1) / 3, the kernel's H^2 / 3 + 1/6 less
// the read's own 1/3 + 1/6 (the layout of AddProbesLane: two probes at +-sqrt(T) up to T = 1,
// then 2J probes). Across, one row is the first copy's own box (L = 1); for L > 1 two rows at
// +-d, d^2 = (L^2 - 1) / 3, have the variance L^2 / 3 + 1/6 (twice the reads, so they stop at
// kBoxProbeThickness). The probes follow (1, tg) and the rows the minor axis, so a turned
// footprint is read in its own parallelogram, with no tilt between.
// They take over the table's copies (whatever weight AddProbesLane left them: below L = 1 the
// copies of (H, 1), whose box the probes have) with the weight
// g = min(1, 2 - H / kProbeHalfExtent) min(1, (kBoxProbeThickness - L) kBoxProbeFade), fading
// out with the base probes between H = 4 and 8 and into the table's copies between L = 1.25
// and 1.375. Continuous: at H = 1 the probes meet at the centre (T = 0), the first copy alone,
// which is the table's copy there; the rows part from L = 1; g reaches 0 at the fades' ends.
void AddBoxProbesLane(SelectionLanes& out, int r, int lane) {
  out.box_probes[r][lane] = 0;
  if (!(out.reading_weight[r][lane] > 0.0f)) return;
  const float H = out.H[r][lane], L = std::min(out.L[r][lane], H);
  if (!(H >= 1.0f) || !(L < kBoxProbeThickness) || !(H < 2.0f * kProbeHalfExtent)) return;
  const float g = ProbeFade(H) * std::min(1.0f, (kBoxProbeThickness - L) * kBoxProbeFade);
  // What the base probes left the table (its slots' weights sum to that, up to rounding).
  const float table = 1.0f - (L < 1.0f ? BaseProbeShare(H, L) : 0.0f);
  for (int s = 0; s < SelectionLanes::kSlots; ++s) out.weight[r][s][lane] *= 1.0f - g;
  const float share = g * table;
  out.box_probe_rows[r][lane] = L > 1.0f ? std::sqrt((L * L - 1.0f) * (1.0f / 3.0f)) : 0.0f;
  const float T = (H * H - 1.0f) * (1.0f / 3.0f);
  const float t = T * (1.0f / (kBoxProbeSpacing * kBoxProbeSpacing));
  if (t <= 0.25f) {
    out.box_probes[r][lane] = 2;
    out.box_probe_step[r][lane] = 2.0f * std::sqrt(T);
    out.box_probe_weight[r][lane] = 0.0f;
    out.box_probe_end_weight[r][lane] = 0.5f * share;
    return;
  }
  const auto [J, e] = SpreadEvenly(t);  // H < 8: t < 63 / 12
  const float Jf = static_cast<float>(J);
  out.box_probes[r][lane] = 2 * J;
  out.box_probe_step[r][lane] = kBoxProbeSpacing;
  out.box_probe_end_weight[r][lane] = e * share;
  out.box_probe_weight[r][lane] = (1.0f - 2.0f * e) / (2.0f * (Jf - 1.0f)) * share;
}

}  // namespace

CopySelector::CopySelector(const PrefilteredTable& table)
    : log2_size_(table.log2_size()),
      half_size_(0.5f * static_cast<float>(table.size())),
      first_copy_(table.cell(0, 0).first) {
  const int n = log2_size_;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i < n; ++i) {
      first_.push_back(table.cell(j, i).first);
      tilts_.push_back(static_cast<int32_t>(table.cell(j, i).copies / 2));
    }
#if defined(__x86_64__) && defined(__GNUC__)
  kernel_ = __builtin_cpu_supports("avx2");
#endif
}

// seed 000, eq. 5 with the tilt blend, for one reading of one lane.
void CopySelector::TableSlots(float H, float L, float tg, bool along_v, SelectionLanes& out,
                              int reading, int lane) const {
  auto set = [&](int slot, uint32_t copy, float weight) {
    out.copy[reading][slot][lane] = copy;
    out.weight[reading][slot][lane] = weight;
  };
  if (H < 1.0f) {
    // Magnification, between the base (bilinear texels, H = 0) and the first copy (the box of
    // 2 x 2 texels, H = L = 1). The paper falls back to the base for all H < 1; blending with
    // weight H^2 gives the blend the variance of a box of 2H texels, so the blur grows
    // continuously up to the table (+2.1 to +4.7 dB over the paper's fallback on the grazing
    // plane at pitch 60, a = 2).
    const float m = H * H;
    set(0, 0, 1.0f - m);
    set(1, first_copy_, m);
    for (int s = 2; s < SelectionLanes::kSlots; ++s) set(s, 0, 0.0f);
    return;
  }
  const int n = log2_size_;
  // The copies' extents (CopyExtent); L between 1 (the thinnest copy) and H, raised to
  // H / 2^(n-1) where lambda is frozen.
  const float Hc = std::min(CopyExtent(H), PowerOfTwo(3 * n));
  const float Lc = std::clamp(CopyExtent(L), std::max(1.0f, Hc * PowerOfTwo(1 - n)), Hc);
  // seed 000, eq. 5: H = 2^eH (1 + M_H), L = 2^eL (1 + M_L).
  const auto [eH, mH] = SplitPowerOfTwo(Hc);
  const auto [eL, mL] = SplitPowerOfTwo(Lc);
  int cells[3];
  float weights[3];
  if (eL >= n) {  // L >= 2^n: the aperture covers whole periods both ways
    cells[0] = cells[1] = cells[2] = n * n + std::min(eH - n, n - 1);
    weights[0] = 1.0f, weights[1] = weights[2] = 0.0f;
  } else {
    int i = eH - eL;
    float mh = mH;
    if (i >= n - 1) {  // lambda frozen: no cell (eL, eH + 1); L was raised so that M_H = M_L
      i = n - 1;
      mh = std::min(mh, mL);
    }
    // R1, then R3 = (eH + 1, eL) when M_H >= M_L, else R4 = (eH, eL + 1), then R2.
    const bool r3 = mh >= mL;
    cells[0] = eL * n + i;
    cells[1] = r3 ? eL * n + i + 1 : (eL + 1) * n + i - 1;
    cells[2] = (eL + 1) * n + i;
    weights[0] = 1.0f - std::max(mh, mL);
    weights[1] = std::abs(mh - mL);
    weights[2] = std::min(mh, mL);
  }
  // The two tilts around tg (TiltIndex; the skewed read follows tg between them).
  const float tilt_position = (tg + 1.0f) * 0.5f;
  const uint32_t v_offset = along_v ? 1 : 0;
  for (int c = 0; c < 3; ++c) {
    const int tilts = tilts_[cells[c]];
    const uint32_t first = first_[cells[c]] + v_offset * static_cast<uint32_t>(tilts);
    if (tilts <= 1) {  // one copy per axis (0: the one untilted copy)
      set(2 * c, first, weights[c]);
      set(2 * c + 1, first, 0.0f);
      continue;
    }
    const float k = TiltIndex(tilt_position, static_cast<float>(tilts - 2));
    const int k0 = std::min(static_cast<int>(k), tilts - 2);
    const float next = NextTiltWeight(k - static_cast<float>(k0));
    set(2 * c, first + static_cast<uint32_t>(k0), weights[c] * (1.0f - next));
    set(2 * c + 1, first + static_cast<uint32_t>(k0) + 1, weights[c] * next);
  }
}

void CopySelector::SelectPortable(const float* dudx, const float* dvdx, const float* dudy,
                                  const float* dvdy, int n, SelectionLanes& out) const {
  for (int lane = 0; lane < n; ++lane) {
    const LaneReadings r = ReadLane(dudx[lane], dvdx[lane], dudy[lane], dvdy[lane], half_size_);
    out.reading_weight[0][lane] = r.valid ? r.first : 0.0f;
    out.reading_weight[1][lane] = r.valid ? 1.0f - r.first : 0.0f;
    out.along_v[0][lane] = r.u_major ? 0 : 1;
    out.along_v[1][lane] = r.u_major ? 1 : 0;
    float H[2], L[2], tg[2], scale[2];
    bool principal[2] = {false, false};
    for (int k = 0; k < 2; ++k) {
      H[k] = r.H[k], L[k] = r.L[k], tg[k] = r.tg[k], scale[k] = 1.0f;
      if (out.reading_weight[k][lane] > 0.0f && H[k] < 1.0f)
        principal[k] = MagnifiedInPrincipalAxes(H[k], L[k], tg[k], scale[k]);
    }
    // Two readings wholly in the principal axes blend the same reads (the same untilted copies,
    // the probes along the same axis at the same distances): the first alone is read.
    if (principal[0] && principal[1])
      out.reading_weight[0][lane] = 1.0f, out.reading_weight[1][lane] = 0.0f;
    // The magnified taps take their share w; the readings the rest (none where w = 1).
    const MagnifiedTapsOfLane taps =
        r.valid ? MagnifiedTaps(r.uu, r.uv, r.vv, r.area) : MagnifiedTapsOfLane{};
    out.taps_share[lane] = taps.share;
    out.taps_first[lane] = taps.first;
    out.taps_weight[lane] = taps.weight;
    for (int c = 0; c < 2; ++c) out.tap_p[c][lane] = taps.p[c], out.tap_q[c][lane] = taps.q[c];
    const float readings = 1.0f - taps.share;
    out.reading_weight[0][lane] *= readings;
    out.reading_weight[1][lane] *= readings;
    for (int k = 0; k < 2; ++k) {
      out.H[k][lane] = H[k], out.L[k][lane] = L[k], out.tg[k][lane] = tg[k];
      out.probe_scale[k][lane] = scale[k];
      if (out.reading_weight[k][lane] > 0.0f)
        TableSlots(H[k], L[k], tg[k], out.along_v[k][lane] != 0, out, k, lane);
    }
  }
  for (int lane = 0; lane < n; ++lane)
    for (int k = 0; k < 2; ++k) {
      AddProbesLane(out, k, lane);
      AddBoxProbesLane(out, k, lane);
    }
}

#if defined(__x86_64__) && defined(__GNUC__)
namespace {

__attribute__((target("avx2"))) inline __m256 Abs(__m256 x) {
  return _mm256_andnot_ps(_mm256_set1_ps(-0.0f), x);
}

// Where mask is set, the slot takes this copy and weight (magnified lanes).
__attribute__((target("avx2"))) inline void BlendSlot(SelectionLanes& out, int r, int slot,
                                                      __m256 mask, __m256i copy, __m256 weight) {
  __m256i* c = reinterpret_cast<__m256i*>(out.copy[r][slot]);
  _mm256_store_si256(c, _mm256_blendv_epi8(_mm256_load_si256(c), copy, _mm256_castps_si256(mask)));
  _mm256_store_ps(out.weight[r][slot],
                  _mm256_blendv_ps(_mm256_load_ps(out.weight[r][slot]), weight, mask));
}

// Where `lanes` is set, `to` takes `value`.
__attribute__((target("avx2"))) inline void BlendStore(float* to, __m256 value, __m256 lanes) {
  _mm256_storeu_ps(to, _mm256_blendv_ps(_mm256_loadu_ps(to), value, lanes));
}

// LargerEigenvalue for eight lanes, the same operations.
__attribute__((target("avx2"))) inline __m256 LargerEigenvalueAvx2(__m256 a, __m256 b, __m256 c) {
  const __m256 half = _mm256_set1_ps(0.5f);
  const __m256 half_difference = _mm256_mul_ps(half, _mm256_sub_ps(a, b));
  return _mm256_add_ps(_mm256_mul_ps(half, _mm256_add_ps(a, b)),
                       _mm256_sqrt_ps(_mm256_add_ps(_mm256_mul_ps(half_difference, half_difference),
                                                    _mm256_mul_ps(c, c))));
}

// MagnifiedInPrincipalAxes for the lanes of `lanes`, the same operations; scale is 1 elsewhere.
// Returns the lanes wholly in the principal axes (beta = 1) among `lanes`.
__attribute__((target("avx2"))) __m256 MagnifiedInPrincipalAxesAvx2(__m256 lanes, __m256& H,
                                                                    __m256& L, __m256& tg,
                                                                    __m256& scale) {
  const __m256 one = _mm256_set1_ps(1.0f), half = _mm256_set1_ps(0.5f);
  const __m256 zero = _mm256_setzero_ps();
  const __m256 major = _mm256_mul_ps(H, H), L2 = _mm256_mul_ps(L, L);
  const __m256 cross = _mm256_mul_ps(tg, major);
  const __m256 minor = _mm256_add_ps(L2, _mm256_mul_ps(tg, cross));
  const __m256 lambda1 = LargerEigenvalueAvx2(major, minor, cross);
  const __m256 excess = _mm256_sub_ps(lambda1, major);
  const __m256 room = _mm256_mul_ps(half, _mm256_sub_ps(one, major));
  const __m256 beta =
      _mm256_blendv_ps(_mm256_div_ps(room, excess), one, _mm256_cmp_ps(excess, room, _CMP_LE_OQ));
  const __m256 gap = _mm256_sub_ps(lambda1, minor);
  const __m256 tp = _mm256_and_ps(_mm256_cmp_ps(gap, zero, _CMP_GT_OQ), _mm256_div_ps(cross, gap));
  const __m256 lambda2 = _mm256_div_ps(_mm256_mul_ps(major, L2), lambda1);
  H = _mm256_blendv_ps(H, _mm256_sqrt_ps(_mm256_add_ps(major, _mm256_mul_ps(beta, excess))), lanes);
  L = _mm256_blendv_ps(
      L, _mm256_sqrt_ps(_mm256_add_ps(L2, _mm256_mul_ps(beta, _mm256_sub_ps(lambda2, L2)))), lanes);
  tg = _mm256_blendv_ps(tg, _mm256_add_ps(tg, _mm256_mul_ps(beta, _mm256_sub_ps(tp, tg))), lanes);
  const __m256 cosine =
      _mm256_div_ps(one, _mm256_sqrt_ps(_mm256_add_ps(one, _mm256_mul_ps(tp, tp))));
  scale = _mm256_blendv_ps(one, _mm256_add_ps(one, _mm256_mul_ps(beta, _mm256_sub_ps(cosine, one))),
                           lanes);
  return _mm256_and_ps(lanes, _mm256_cmp_ps(beta, one, _CMP_EQ_OQ));
}

// MagnifiedTaps for the lanes of `valid`, the same operations, stored into `out`'s taps; returns
// the share (0 in the other lanes).
__attribute__((target("avx2"))) __m256 MagnifiedTapsAvx2(__m256 valid, __m256 uu, __m256 uv,
                                                         __m256 vv, __m256 area,
                                                         SelectionLanes& out) {
  const __m256 one = _mm256_set1_ps(1.0f), zero = _mm256_setzero_ps();
  const __m256 two = _mm256_set1_ps(2.0f);
  const __m256 lambda1 = LargerEigenvalueAvx2(uu, vv, uv);
  // std::clamp(x, 0, 1): x < 0 ? 0 : (1 < x ? 1 : x).
  const __m256 x =
      _mm256_mul_ps(_mm256_set1_ps(kTapsFade), _mm256_sub_ps(one, _mm256_sqrt_ps(lambda1)));
  __m256 share = _mm256_blendv_ps(x, one, _mm256_cmp_ps(one, x, _CMP_LT_OQ));
  share = _mm256_blendv_ps(share, zero, _mm256_cmp_ps(x, zero, _CMP_LT_OQ));
  const __m256 has = _mm256_and_ps(valid, _mm256_cmp_ps(share, zero, _CMP_GT_OQ));
  _mm256_store_ps(out.taps_share, _mm256_and_ps(has, share));
  if (_mm256_movemask_ps(has) == 0) return zero;
  const __m256 beta = _mm256_mul_ps(area, area), rest = _mm256_sub_ps(one, beta);
  const __m256 inv_rest = _mm256_div_ps(one, rest);
  const __m256 trace = _mm256_add_ps(uu, vv);
  const __m256 tu = _mm256_mul_ps(_mm256_sub_ps(uu, beta), inv_rest);
  const __m256 tv = _mm256_mul_ps(_mm256_sub_ps(vv, beta), inv_rest);
  const __m256 tuv = _mm256_mul_ps(uv, inv_rest);
  // std::max(0, y): 0 < y ? y : 0 (y is never NaN on these lanes).
  const __m256 det = _mm256_mul_ps(beta, _mm256_add_ps(_mm256_sub_ps(one, trace), beta));
  const __m256 s = _mm256_mul_ps(_mm256_sqrt_ps(_mm256_max_ps(det, zero)), inv_rest);
  const __m256 k =
      _mm256_div_ps(_mm256_set1_ps(0.81649658092772603f),
                    _mm256_sqrt_ps(_mm256_add_ps(
                        _mm256_mul_ps(_mm256_sub_ps(trace, _mm256_mul_ps(two, beta)), inv_rest),
                        _mm256_mul_ps(two, s))));
  // Lanes without taps store zeros (finite, never read).
  _mm256_store_ps(out.taps_first, _mm256_and_ps(has, _mm256_mul_ps(share, beta)));
  _mm256_store_ps(out.taps_weight, _mm256_and_ps(has, _mm256_mul_ps(_mm256_set1_ps(0.25f),
                                                                    _mm256_mul_ps(share, rest))));
  _mm256_store_ps(out.tap_p[0], _mm256_and_ps(has, _mm256_mul_ps(_mm256_add_ps(tu, s), k)));
  _mm256_store_ps(out.tap_p[1], _mm256_and_ps(has, _mm256_mul_ps(tuv, k)));
  _mm256_store_ps(out.tap_q[0], _mm256_and_ps(has, _mm256_mul_ps(tuv, k)));
  _mm256_store_ps(out.tap_q[1], _mm256_and_ps(has, _mm256_mul_ps(_mm256_add_ps(tv, s), k)));
  return _mm256_and_ps(has, share);
}

// For J = 2..9 (index J - 2): AddProbesLane's A, J - 1, J (2J - 1) and 0.5 / J.
struct ProbeTable {
  alignas(32) float A[8], J1[8], denominator[8], top[8];
};
constexpr ProbeTable MakeProbeTable() {
  ProbeTable t{};
  for (int i = 0; i < 8; ++i) {
    const float Jf = static_cast<float>(i + 2);
    t.A[i] = (4.0f * (Jf - 1.0f) * (Jf - 1.0f) - 1.0f) * (1.0f / 12.0f);
    t.J1[i] = Jf - 1.0f;
    t.denominator[i] = Jf * (2.0f * Jf - 1.0f);
    t.top[i] = 0.5f / Jf;
  }
  return t;
}
constexpr ProbeTable kProbeTable = MakeProbeTable();
static_assert(SelectionLanes::kMaxProbes / 2 - 2 < 8, "J - 2 indexes eight entries");

// SpreadEvenly for eight lanes: J, J - 1 and e, the same floats (its functions of J looked up).
__attribute__((target("avx2"))) inline void SpreadEvenlyAvx2(__m256 t, __m256i& J, __m256& J1,
                                                             __m256& e) {
  const __m256 one = _mm256_set1_ps(1.0f), zero = _mm256_setzero_ps();
  J = _mm256_min_epi32(
      _mm256_max_epi32(
          _mm256_cvttps_epi32(_mm256_ceil_ps(_mm256_mul_ps(
              _mm256_set1_ps(0.5f),
              _mm256_sqrt_ps(_mm256_add_ps(_mm256_mul_ps(_mm256_set1_ps(12.0f), t), one))))),
          _mm256_set1_epi32(2)),
      _mm256_set1_epi32(SelectionLanes::kMaxProbes / 2));
  const __m256i row = _mm256_sub_epi32(J, _mm256_set1_epi32(2));
  const __m256 A = _mm256_permutevar8x32_ps(_mm256_load_ps(kProbeTable.A), row);
  J1 = _mm256_permutevar8x32_ps(_mm256_load_ps(kProbeTable.J1), row);
  // std::clamp(y, 0, 0.5 / J): y < 0 ? 0 : (0.5 / J < y ? 0.5 / J : y).
  const __m256 y =
      _mm256_div_ps(_mm256_mul_ps(_mm256_set1_ps(1.5f), _mm256_sub_ps(t, A)),
                    _mm256_permutevar8x32_ps(_mm256_load_ps(kProbeTable.denominator), row));
  const __m256 top = _mm256_permutevar8x32_ps(_mm256_load_ps(kProbeTable.top), row);
  e = _mm256_blendv_ps(y, top, _mm256_cmp_ps(top, y, _CMP_LT_OQ));
  e = _mm256_blendv_ps(e, zero, _mm256_cmp_ps(y, zero, _CMP_LT_OQ));
}

// Where `spread` is set, the 2J probes of SpreadEvenly(t), `spacing` texels apart, sharing
// `share`, into a probe layout: the lane code's floats.
__attribute__((target("avx2"))) inline void BlendEvenProbesAvx2(__m256 t, __m256 spacing,
                                                                __m256 share, __m256 spread,
                                                                __m256i& probes, __m256& step,
                                                                __m256& weight,
                                                                __m256& end_weight) {
  const __m256 one = _mm256_set1_ps(1.0f), two = _mm256_set1_ps(2.0f);
  __m256i J;
  __m256 J1, e;
  SpreadEvenlyAvx2(t, J, J1, e);
  probes = _mm256_blendv_epi8(probes, _mm256_add_epi32(J, J), _mm256_castps_si256(spread));
  step = _mm256_blendv_ps(step, spacing, spread);
  weight = _mm256_blendv_ps(
      weight,
      _mm256_mul_ps(
          _mm256_div_ps(_mm256_sub_ps(one, _mm256_mul_ps(two, e)), _mm256_mul_ps(two, J1)), share),
      spread);
  end_weight = _mm256_blendv_ps(end_weight, _mm256_mul_ps(e, share), spread);
}

// ProbeFade and BaseProbeShare, the same operations.
__attribute__((target("avx2"))) inline __m256 ProbeFadeAvx2(__m256 H) {
  // H / kProbeHalfExtent, a power of two: the same float as the division.
  return _mm256_min_ps(_mm256_sub_ps(_mm256_set1_ps(2.0f),
                                     _mm256_mul_ps(H, _mm256_set1_ps(1.0f / kProbeHalfExtent))),
                       _mm256_set1_ps(1.0f));
}
__attribute__((target("avx2"))) inline __m256 BaseProbeShareAvx2(__m256 H, __m256 L) {
  return _mm256_mul_ps(ProbeFadeAvx2(H), _mm256_sub_ps(_mm256_set1_ps(1.0f), _mm256_mul_ps(L, L)));
}

// AddProbesLane for the lanes of `thin` (read, L < 1, H < 2 kProbeHalfExtent and not nearly
// round), the same operations; `magnify`: H < 1.
__attribute__((target("avx2"))) void AddProbesAvx2(SelectionLanes& out, int r, __m256 thin,
                                                   __m256 magnify, __m256 H, __m256 L) {
  static_assert(kProbeSpacing == 1.0f, "t = T / s^2 = T and the step s are written as 1 below");
  const __m256 one = _mm256_set1_ps(1.0f), zero = _mm256_setzero_ps();
  const __m256 half = _mm256_set1_ps(0.5f), two = _mm256_set1_ps(2.0f);
  const __m256 L2 = _mm256_mul_ps(L, L), H2 = _mm256_mul_ps(H, H);
  const __m256 share = BaseProbeShareAvx2(H, L);
  __m256 T = _mm256_mul_ps(H2, _mm256_set1_ps(1.0f / 3.0f));
  if (_mm256_movemask_ps(_mm256_and_ps(thin, magnify)) != 0)
    T = _mm256_blendv_ps(T,
                         _mm256_div_ps(_mm256_sub_ps(H2, L2),
                                       _mm256_mul_ps(_mm256_set1_ps(3.0f), _mm256_sub_ps(one, L2))),
                         magnify);
  const __m256 root = _mm256_sqrt_ps(T);
  // Magnified: the fade into the two-read blend while p = clamp(16 sqrt(T) - 1, 0, 1) < 1.
  const __m256 x = _mm256_sub_ps(_mm256_mul_ps(_mm256_set1_ps(16.0f), root), one);
  __m256 p = _mm256_blendv_ps(x, one, _mm256_cmp_ps(one, x, _CMP_LT_OQ));
  p = _mm256_blendv_ps(p, zero, _mm256_cmp_ps(x, zero, _CMP_LT_OQ));
  const __m256 fade =
      _mm256_and_ps(_mm256_and_ps(thin, magnify), _mm256_cmp_ps(p, one, _CMP_LT_OQ));
  const __m256 probed = _mm256_andnot_ps(fade, thin);  // the layouts below, then the scaling
  // Two probes at +-sqrt(T) where T <= s^2 / 4 (only magnified lanes), else 2J probes s apart.
  const __m256 two_probes = _mm256_cmp_ps(T, _mm256_set1_ps(0.25f), _CMP_LE_OQ);
  __m256i probes = _mm256_set1_epi32(2);
  __m256 step = _mm256_mul_ps(two, root), weight = zero, end_weight = _mm256_mul_ps(half, share);
  const __m256 spread = _mm256_andnot_ps(two_probes, thin);
  if (_mm256_movemask_ps(spread) != 0) {  // 2J probes (never where a lane fades: T < 1 / 64)
    BlendEvenProbesAvx2(T, one, share, spread, probes, step, weight, end_weight);
  }
  // The fading lanes: two probes at +-sqrt(T) of weight p / 2 share, the blend's two reads.
  probes = _mm256_blendv_epi8(probes, _mm256_set1_epi32(2), _mm256_castps_si256(fade));
  step = _mm256_blendv_ps(step, _mm256_mul_ps(two, root), fade);
  weight = _mm256_blendv_ps(weight, zero, fade);
  end_weight = _mm256_blendv_ps(end_weight, _mm256_mul_ps(_mm256_mul_ps(p, half), share), fade);
  const __m256 q = _mm256_sub_ps(one, p);
  BlendStore(out.weight[r][0], _mm256_mul_ps(q, _mm256_sub_ps(one, H2)), fade);
  BlendStore(out.weight[r][1], _mm256_add_ps(_mm256_mul_ps(p, L2), _mm256_mul_ps(q, H2)), fade);
  __m256i* lane_probes = reinterpret_cast<__m256i*>(out.probes[r]);
  _mm256_store_si256(lane_probes, _mm256_blendv_epi8(_mm256_load_si256(lane_probes), probes,
                                                     _mm256_castps_si256(thin)));
  BlendStore(out.probe_step[r], _mm256_mul_ps(step, _mm256_load_ps(out.probe_scale[r])), thin);
  BlendStore(out.probe_end_weight[r], end_weight, thin);
  BlendStore(out.probe_weight[r], weight, thin);
  // The magnified lanes past the fade: the first copy alone (slot 1's copy in slot 0).
  const __m256 first_alone = _mm256_and_ps(probed, magnify);
  if (_mm256_movemask_ps(first_alone) != 0) {
    __m256i* copy0 = reinterpret_cast<__m256i*>(out.copy[r][0]);
    _mm256_store_si256(
        copy0,
        _mm256_blendv_epi8(_mm256_load_si256(copy0),
                           _mm256_load_si256(reinterpret_cast<const __m256i*>(out.copy[r][1])),
                           _mm256_castps_si256(first_alone)));
    BlendStore(out.weight[r][0], one, first_alone);
    BlendStore(out.weight[r][1], zero, first_alone);
  }
  const __m256 rest = _mm256_sub_ps(one, share);
  for (int slot = 0; slot < SelectionLanes::kSlots; ++slot)
    BlendStore(out.weight[r][slot], _mm256_mul_ps(_mm256_loadu_ps(out.weight[r][slot]), rest),
               probed);
}

// The lanes of `read` that AddBoxProbesLane gives box probes, and their weight g, the same
// operations.
__attribute__((target("avx2"))) inline __m256 BoxProbedAvx2(__m256 read, __m256 H, __m256 L) {
  return _mm256_and_ps(
      _mm256_and_ps(read, _mm256_cmp_ps(H, _mm256_set1_ps(1.0f), _CMP_GE_OQ)),
      _mm256_and_ps(_mm256_cmp_ps(L, _mm256_set1_ps(kBoxProbeThickness), _CMP_LT_OQ),
                    _mm256_cmp_ps(H, _mm256_set1_ps(2.0f * kProbeHalfExtent), _CMP_LT_OQ)));
}
__attribute__((target("avx2"))) inline __m256 BoxProbeWeightAvx2(__m256 H, __m256 L) {
  return _mm256_mul_ps(
      ProbeFadeAvx2(H),
      _mm256_min_ps(_mm256_mul_ps(_mm256_sub_ps(_mm256_set1_ps(kBoxProbeThickness), L),
                                  _mm256_set1_ps(kBoxProbeFade)),
                    _mm256_set1_ps(1.0f)));
}

// AddBoxProbesLane for the lanes of `read`, the same operations; L is min(L, H). The caller
// has set every lane's count to 0.
__attribute__((target("avx2"))) void AddBoxProbesAvx2(SelectionLanes& out, int r, __m256 read,
                                                      __m256 H, __m256 L) {
  const __m256 one = _mm256_set1_ps(1.0f), zero = _mm256_setzero_ps();
  const __m256 two = _mm256_set1_ps(2.0f);
  const __m256 boxed = BoxProbedAvx2(read, H, L);
  if (_mm256_movemask_ps(boxed) == 0) return;
  const __m256 g = BoxProbeWeightAvx2(H, L);
  const __m256 table = _mm256_sub_ps(
      one, _mm256_and_ps(_mm256_cmp_ps(L, one, _CMP_LT_OQ), BaseProbeShareAvx2(H, L)));
  const __m256 keep = _mm256_sub_ps(one, g);
  for (int slot = 0; slot < SelectionLanes::kSlots; ++slot)
    BlendStore(out.weight[r][slot], _mm256_mul_ps(_mm256_loadu_ps(out.weight[r][slot]), keep),
               boxed);
  const __m256 share = _mm256_mul_ps(g, table);
  const __m256 third = _mm256_set1_ps(1.0f / 3.0f);
  const __m256 rows =
      _mm256_and_ps(_mm256_cmp_ps(L, one, _CMP_GT_OQ),
                    _mm256_sqrt_ps(_mm256_mul_ps(_mm256_sub_ps(_mm256_mul_ps(L, L), one), third)));
  const __m256 T = _mm256_mul_ps(_mm256_sub_ps(_mm256_mul_ps(H, H), one), third);
  const __m256 t = _mm256_mul_ps(T, _mm256_set1_ps(1.0f / (kBoxProbeSpacing * kBoxProbeSpacing)));
  __m256i probes = _mm256_set1_epi32(2);
  __m256 step = _mm256_mul_ps(two, _mm256_sqrt_ps(T)), weight = zero,
         end_weight = _mm256_mul_ps(_mm256_set1_ps(0.5f), share);
  const __m256 spread =
      _mm256_andnot_ps(_mm256_cmp_ps(t, _mm256_set1_ps(0.25f), _CMP_LE_OQ), boxed);
  if (_mm256_movemask_ps(spread) != 0) {
    BlendEvenProbesAvx2(t, _mm256_set1_ps(kBoxProbeSpacing), share, spread, probes, step, weight,
                        end_weight);
  }
  _mm256_store_si256(reinterpret_cast<__m256i*>(out.box_probes[r]),
                     _mm256_and_si256(probes, _mm256_castps_si256(boxed)));
  BlendStore(out.box_probe_step[r], step, boxed);
  BlendStore(out.box_probe_weight[r], weight, boxed);
  BlendStore(out.box_probe_end_weight[r], end_weight, boxed);
  BlendStore(out.box_probe_rows[r], rows, boxed);
}

// The AVX2 lanes of SelectPortable: ReadLane and TableSlots for eight lanes, the same float
// operations in the same order. Lanes whose readings are not read compute harmless values
// (clamped cell indices, finite arithmetic) that are never used; the second reading is skipped
// when no lane is near a diagonal; the base probes by AddProbesAvx2, the box probes by
// AddBoxProbesAvx2.
__attribute__((target("avx2"))) void SelectAvx2(const float* dudx, const float* dvdx,
                                                const float* dudy, const float* dvdy,
                                                float half_size, int n_log2, uint32_t first_copy,
                                                const uint32_t* cell_first,
                                                const int32_t* cell_tilts, SelectionLanes& out) {
  const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f), half = _mm256_set1_ps(0.5f);
  const __m256 max_texels = _mm256_set1_ps(kMaxTexels);
  const __m256 min_texels = _mm256_set1_ps(-kMaxTexels);
  const __m256 infinity = _mm256_set1_ps(INFINITY);
  const __m256 s = _mm256_set1_ps(half_size);
  __m256 d[4] = {_mm256_mul_ps(_mm256_loadu_ps(dudx), s), _mm256_mul_ps(_mm256_loadu_ps(dvdx), s),
                 _mm256_mul_ps(_mm256_loadu_ps(dudy), s), _mm256_mul_ps(_mm256_loadu_ps(dvdy), s)};
  // finite: |x| < inf (false for NaN and infinities); then the clamp (std::clamp's order).
  __m256 finite = _mm256_castsi256_ps(_mm256_set1_epi32(-1));
  for (__m256& x : d) {
    finite = _mm256_and_ps(finite, _mm256_cmp_ps(Abs(x), infinity, _CMP_LT_OQ));
    x = _mm256_min_ps(_mm256_max_ps(x, min_texels), max_texels);
  }
  const __m256 dUx = d[0], dVx = d[1], dUy = d[2], dVy = d[3];
  const __m256 uu = _mm256_add_ps(_mm256_mul_ps(dUx, dUx), _mm256_mul_ps(dUy, dUy));
  const __m256 vv = _mm256_add_ps(_mm256_mul_ps(dVx, dVx), _mm256_mul_ps(dVy, dVy));
  const __m256 uv = _mm256_add_ps(_mm256_mul_ps(dUx, dVx), _mm256_mul_ps(dUy, dVy));
  const __m256 area = Abs(_mm256_sub_ps(_mm256_mul_ps(dUx, dVy), _mm256_mul_ps(dVx, dUy)));
  const __m256 total = _mm256_add_ps(uu, vv);
  const __m256 valid =
      _mm256_and_ps(finite, _mm256_cmp_ps(total, _mm256_set1_ps(kMinMoment), _CMP_GE_OQ));
  const __m256 difference = _mm256_sub_ps(uu, vv);
  const __m256 cross = _mm256_mul_ps(_mm256_set1_ps(2.0f), uv);
  const __m256 zone =
      _mm256_mul_ps(_mm256_set1_ps(kAxisBlendZone),
                    _mm256_sqrt_ps(_mm256_add_ps(_mm256_mul_ps(difference, difference),
                                                 _mm256_mul_ps(cross, cross))));
  const __m256 u_major = _mm256_cmp_ps(difference, zero, _CMP_GE_OQ);
  const __m256 spread = Abs(difference);
  const __m256 outside = _mm256_cmp_ps(spread, zone, _CMP_GE_OQ);
  // Lanes with D = 0 (round footprints, where spread = 0 >= zone) and invalid ones may divide 0
  // by 0 here; the first are outside the zone, the others masked below.
  const __m256 inside_weight =
      _mm256_add_ps(half, _mm256_mul_ps(half, _mm256_div_ps(spread, zone)));
  __m256 first = _mm256_blendv_ps(inside_weight, one, outside);
  const __m256 major = _mm256_blendv_ps(vv, uu, u_major);
  const __m256 minor = _mm256_blendv_ps(uu, vv, u_major);
  const __m256 second_major = _mm256_blendv_ps(major, minor, _mm256_cmp_ps(first, one, _CMP_LT_OQ));
  const __m256i v_first = _mm256_andnot_si256(_mm256_castps_si256(u_major), _mm256_set1_epi32(1));
  const __m256i v_second = _mm256_and_si256(_mm256_castps_si256(u_major), _mm256_set1_epi32(1));
  // Invalid lanes: both weights 0 (a valid lane's 1 - first is computed as in the lane code).
  __m256 second = _mm256_and_ps(valid, _mm256_sub_ps(one, first));
  first = _mm256_and_ps(valid, first);
  _mm256_store_si256(reinterpret_cast<__m256i*>(out.along_v[0]), v_first);
  _mm256_store_si256(reinterpret_cast<__m256i*>(out.along_v[1]), v_second);

  const int n = n_log2;
  const __m256 max_h = _mm256_set1_ps(PowerOfTwo(3 * n));
  const __m256 frozen_ratio = _mm256_set1_ps(PowerOfTwo(1 - n));
  const __m256i vn = _mm256_set1_epi32(n), vn1 = _mm256_set1_epi32(n - 1);
  const __m256i ione = _mm256_set1_epi32(1), izero = _mm256_setzero_si256();
  const __m256i last_cell = _mm256_set1_epi32((n + 1) * n - 1);
  const __m256i mantissa_bits = _mm256_set1_epi32(0x7fffff),
                one_bits = _mm256_set1_epi32(0x3f800000);
  const __m256 majors[2] = {major, second_major};
  const __m256i along_v[2] = {v_first, v_second};
  // The magnified taps' share; the readings the rest (none where it is 1: their shapes are not
  // computed there, and groups of eight tapped lanes skip them).
  const __m256 taps_share = MagnifiedTapsAvx2(valid, uu, uv, vv, area, out);
  const __m256 readings = _mm256_sub_ps(one, taps_share);
  const __m256 untapped = _mm256_cmp_ps(readings, zero, _CMP_GT_OQ);
  __m256 read[2] = {_mm256_and_ps(untapped, _mm256_cmp_ps(first, zero, _CMP_GT_OQ)),
                    _mm256_and_ps(untapped, _mm256_cmp_ps(second, zero, _CMP_GT_OQ))};
  // Both readings' shapes; magnified ones in the principal axes (MagnifiedInPrincipalAxes), and
  // where both are wholly so the first alone is read (as in SelectPortable).
  __m256 shape_h[2] = {one, one}, shape_l[2] = {one, one}, shape_tg[2] = {zero, zero};
  __m256 principal[2] = {zero, zero};
  for (int r = 0; r < 2; ++r) {
    if (_mm256_movemask_ps(read[r]) == 0) continue;
    shape_h[r] = _mm256_sqrt_ps(majors[r]);
    const __m256 inv_h = _mm256_div_ps(one, shape_h[r]);
    shape_tg[r] = _mm256_mul_ps(_mm256_mul_ps(uv, inv_h), inv_h);
    shape_l[r] = _mm256_mul_ps(area, inv_h);
    const __m256 magnify = _mm256_cmp_ps(shape_h[r], one, _CMP_LT_OQ);
    __m256 probe_scale = one;
    if (_mm256_movemask_ps(_mm256_and_ps(magnify, read[r])) != 0)
      principal[r] = _mm256_and_ps(
          read[r],
          MagnifiedInPrincipalAxesAvx2(magnify, shape_h[r], shape_l[r], shape_tg[r], probe_scale));
    _mm256_store_ps(out.probe_scale[r], probe_scale);
  }
  const __m256 one_reading = _mm256_and_ps(principal[0], principal[1]);
  first = _mm256_blendv_ps(first, one, one_reading);
  second = _mm256_andnot_ps(one_reading, second);
  first = _mm256_mul_ps(first, readings);
  second = _mm256_mul_ps(second, readings);
  read[0] = _mm256_and_ps(read[0], _mm256_cmp_ps(first, zero, _CMP_GT_OQ));
  read[1] = _mm256_and_ps(_mm256_andnot_ps(one_reading, read[1]),
                          _mm256_cmp_ps(second, zero, _CMP_GT_OQ));
  _mm256_store_ps(out.reading_weight[0], first);
  _mm256_store_ps(out.reading_weight[1], second);
  for (int r = 0; r < 2; ++r) {
    _mm256_store_si256(reinterpret_cast<__m256i*>(out.probes[r]), _mm256_setzero_si256());
    _mm256_store_si256(reinterpret_cast<__m256i*>(out.box_probes[r]), _mm256_setzero_si256());
    if (_mm256_movemask_ps(read[r]) == 0) continue;
    const __m256 H = shape_h[r], L = shape_l[r], tg = shape_tg[r];
    // Magnified: H under 1 (the principal axes' H, blended, stays under 1 where the axis one is).
    const __m256 magnify = _mm256_cmp_ps(H, one, _CMP_LT_OQ);
    _mm256_store_ps(out.H[r], H);
    _mm256_store_ps(out.tg[r], tg);
    _mm256_store_ps(out.L[r], L);
    // AddProbesLane's tests: read, min(L, H) < 1 and H < 2 kProbeHalfExtent; and not magnified
    // and nearly round (16 sqrt(T) - 1 <= 0), the same operations.
    const __m256 Lmin = _mm256_min_ps(L, H);
    __m256 round = zero;
    if (_mm256_movemask_ps(magnify) != 0) {  // only magnified lanes can be nearly round
      const __m256 Lmin2 = _mm256_mul_ps(Lmin, Lmin);
      const __m256 T =
          _mm256_div_ps(_mm256_sub_ps(_mm256_mul_ps(H, H), Lmin2),
                        _mm256_mul_ps(_mm256_set1_ps(3.0f), _mm256_sub_ps(one, Lmin2)));
      round = _mm256_and_ps(
          magnify,
          _mm256_cmp_ps(_mm256_sub_ps(_mm256_mul_ps(_mm256_set1_ps(16.0f), _mm256_sqrt_ps(T)), one),
                        zero, _CMP_LE_OQ));
    }
    const __m256 thin = _mm256_andnot_ps(
        round,
        _mm256_and_ps(_mm256_and_ps(read[r], _mm256_cmp_ps(Lmin, one, _CMP_LT_OQ)),
                      _mm256_cmp_ps(H, _mm256_set1_ps(2.0f * kProbeHalfExtent), _CMP_LT_OQ)));
    // TableSlots: magnified lanes the base and the first copy by H^2; the others seed 000's.
    const __m256 m = _mm256_mul_ps(H, H);
    if ((_mm256_movemask_ps(_mm256_andnot_ps(magnify, read[r])) & 0xff) == 0) {
      _mm256_store_si256(reinterpret_cast<__m256i*>(out.copy[r][0]), izero);
      _mm256_store_ps(out.weight[r][0], _mm256_sub_ps(one, m));
      _mm256_store_si256(reinterpret_cast<__m256i*>(out.copy[r][1]),
                         _mm256_set1_epi32(static_cast<int>(first_copy)));
      _mm256_store_ps(out.weight[r][1], m);
      for (int slot = 2; slot < SelectionLanes::kSlots; ++slot) {
        _mm256_store_si256(reinterpret_cast<__m256i*>(out.copy[r][slot]), izero);
        _mm256_store_ps(out.weight[r][slot], zero);
      }
      if (_mm256_movemask_ps(thin) != 0) AddProbesAvx2(out, r, thin, magnify, H, Lmin);
      continue;
    }
    // Every lane read wholly by the box probes (g = 1, where the lane code's table weights end
    // as 0): the table's copies are not chosen.
    const __m256 whole_box =
        _mm256_and_ps(BoxProbedAvx2(read[r], H, Lmin),
                      _mm256_cmp_ps(BoxProbeWeightAvx2(H, Lmin), one, _CMP_EQ_OQ));
    if (_mm256_movemask_ps(whole_box) == _mm256_movemask_ps(read[r])) {
      for (int slot = 0; slot < SelectionLanes::kSlots; ++slot) {
        _mm256_store_si256(reinterpret_cast<__m256i*>(out.copy[r][slot]), izero);
        _mm256_store_ps(out.weight[r][slot], zero);
      }
      if (_mm256_movemask_ps(thin) != 0) AddProbesAvx2(out, r, thin, magnify, H, Lmin);
      AddBoxProbesAvx2(out, r, read[r], H, Lmin);
      continue;
    }
    // CopyExtent of H and L. Its x < 1 branch is not needed here: H >= 1 on these lanes, and
    // an L under 1 gives an extent under 1 either way, which the clamp below raises to lo >= 1.
    const __m256 scale = _mm256_set1_ps(kCopyExtentScale),
                 rest = _mm256_set1_ps(1.0f - kCopyExtentScale);
    const __m256 He =
        _mm256_sqrt_ps(_mm256_add_ps(_mm256_mul_ps(_mm256_mul_ps(scale, H), H), rest));
    const __m256 Le =
        _mm256_sqrt_ps(_mm256_add_ps(_mm256_mul_ps(_mm256_mul_ps(scale, L), L), rest));
    const __m256 Hc = _mm256_min_ps(He, max_h);
    // std::clamp(Le, lo, hi): Le < lo ? lo : (hi < Le ? hi : Le).
    const __m256 lo = _mm256_max_ps(one, _mm256_mul_ps(Hc, frozen_ratio));
    __m256 Lc = _mm256_blendv_ps(Le, Hc, _mm256_cmp_ps(Hc, Le, _CMP_LT_OQ));
    Lc = _mm256_blendv_ps(Lc, lo, _mm256_cmp_ps(Le, lo, _CMP_LT_OQ));
    // Lanes that are not read may hold anything: keep their splits in range.
    const __m256 Hs = _mm256_blendv_ps(Hc, one, magnify), Ls = _mm256_blendv_ps(Lc, one, magnify);
    const __m256i hbits = _mm256_castps_si256(Hs), lbits = _mm256_castps_si256(Ls);
    const __m256i eH = _mm256_sub_epi32(_mm256_srli_epi32(hbits, 23), _mm256_set1_epi32(127));
    const __m256i eL = _mm256_sub_epi32(_mm256_srli_epi32(lbits, 23), _mm256_set1_epi32(127));
    const __m256 mH = _mm256_sub_ps(
        _mm256_castsi256_ps(_mm256_or_si256(_mm256_and_si256(hbits, mantissa_bits), one_bits)),
        one);
    const __m256 mL = _mm256_sub_ps(
        _mm256_castsi256_ps(_mm256_or_si256(_mm256_and_si256(lbits, mantissa_bits), one_bits)),
        one);
    const __m256i whole = _mm256_cmpgt_epi32(eL, vn1);  // eL >= n
    __m256i i = _mm256_sub_epi32(eH, eL);
    const __m256i frozen = _mm256_cmpgt_epi32(i, _mm256_sub_epi32(vn1, ione));  // i >= n - 1
    i = _mm256_blendv_epi8(i, vn1, frozen);
    const __m256 mh = _mm256_blendv_ps(mH, _mm256_min_ps(mH, mL), _mm256_castsi256_ps(frozen));
    const __m256 r3 = _mm256_cmp_ps(mh, mL, _CMP_GE_OQ);
    const __m256i row = _mm256_mullo_epi32(eL, vn), next_row = _mm256_add_epi32(row, vn);
    __m256i cells[3] = {_mm256_add_epi32(row, i),
                        _mm256_blendv_epi8(_mm256_sub_epi32(_mm256_add_epi32(next_row, i), ione),
                                           _mm256_add_epi32(_mm256_add_epi32(row, i), ione),
                                           _mm256_castps_si256(r3)),
                        _mm256_add_epi32(next_row, i)};
    __m256 weights[3] = {_mm256_sub_ps(one, _mm256_max_ps(mh, mL)), Abs(_mm256_sub_ps(mh, mL)),
                         _mm256_min_ps(mh, mL)};
    // Whole periods: cell (n, min(eH - n, n - 1)) alone.
    const __m256i whole_cell =
        _mm256_add_epi32(_mm256_set1_epi32(n * n), _mm256_min_epi32(_mm256_sub_epi32(eH, vn), vn1));
    for (int c = 0; c < 3; ++c) {
      cells[c] = _mm256_blendv_epi8(cells[c], whole_cell, whole);
      cells[c] = _mm256_min_epi32(_mm256_max_epi32(cells[c], izero), last_cell);
    }
    weights[0] = _mm256_blendv_ps(weights[0], one, _mm256_castsi256_ps(whole));
    weights[1] = _mm256_andnot_ps(_mm256_castsi256_ps(whole), weights[1]);
    weights[2] = _mm256_andnot_ps(_mm256_castsi256_ps(whole), weights[2]);
    const __m256 tilt_position = _mm256_mul_ps(_mm256_add_ps(tg, one), half);
    for (int c = 0; c < 3; ++c) {
      // Neighbouring samples mostly share the cell: then two loads, not two gathers.
      const int cell = _mm256_cvtsi256_si32(cells[c]);
      const bool shared =
          _mm256_movemask_epi8(_mm256_cmpeq_epi32(cells[c], _mm256_set1_epi32(cell))) == -1;
      const __m256i tilts = shared ? _mm256_set1_epi32(cell_tilts[cell])
                                   : _mm256_i32gather_epi32(cell_tilts, cells[c], 4);
      const __m256i cell_firsts =
          shared ? _mm256_set1_epi32(static_cast<int>(cell_first[cell]))
                 : _mm256_i32gather_epi32(reinterpret_cast<const int*>(cell_first), cells[c], 4);
      const __m256i firsts = _mm256_add_epi32(cell_firsts, _mm256_mullo_epi32(along_v[r], tilts));
      // TiltIndex, the same operations: x = std::clamp(tilt_position half + 1/2, 1/2, half +
      // 1/2) with half = tilts - 2, then the stretched end intervals.
      const __m256i spans = _mm256_sub_epi32(tilts, _mm256_set1_epi32(2));
      const __m256 halff = _mm256_cvtepi32_ps(spans);
      const __m256 x0 = _mm256_add_ps(_mm256_mul_ps(tilt_position, halff), half);
      const __m256 top = _mm256_add_ps(halff, half);
      __m256 x = _mm256_blendv_ps(x0, top, _mm256_cmp_ps(top, x0, _CMP_LT_OQ));
      x = _mm256_blendv_ps(x, half, _mm256_cmp_ps(x0, half, _CMP_LT_OQ));
      const __m256 twice = _mm256_mul_ps(_mm256_set1_ps(2.0f), x);
      __m256 k =
          _mm256_blendv_ps(x, _mm256_sub_ps(twice, halff), _mm256_cmp_ps(halff, x, _CMP_LT_OQ));
      k = _mm256_blendv_ps(k, _mm256_sub_ps(twice, one), _mm256_cmp_ps(x, one, _CMP_LT_OQ));
      const __m256i k0 = _mm256_min_epi32(_mm256_cvttps_epi32(k), spans);
      // NextTiltWeight: std::clamp(2 f - 0.5, 0, 1).
      const __m256 y = _mm256_sub_ps(
          _mm256_mul_ps(_mm256_set1_ps(2.0f), _mm256_sub_ps(k, _mm256_cvtepi32_ps(k0))), half);
      __m256 next = _mm256_blendv_ps(y, one, _mm256_cmp_ps(one, y, _CMP_LT_OQ));
      next = _mm256_blendv_ps(next, zero, _mm256_cmp_ps(y, zero, _CMP_LT_OQ));
      const __m256i tilted = _mm256_cmpgt_epi32(tilts, ione);  // more than one copy per axis
      const __m256i copy0 = _mm256_blendv_epi8(firsts, _mm256_add_epi32(firsts, k0), tilted);
      const __m256i copy1 =
          _mm256_blendv_epi8(firsts, _mm256_add_epi32(_mm256_add_epi32(firsts, k0), ione), tilted);
      const __m256 w0 =
          _mm256_blendv_ps(weights[c], _mm256_mul_ps(weights[c], _mm256_sub_ps(one, next)),
                           _mm256_castsi256_ps(tilted));
      const __m256 w1 = _mm256_and_ps(_mm256_castsi256_ps(tilted), _mm256_mul_ps(weights[c], next));
      _mm256_store_si256(reinterpret_cast<__m256i*>(out.copy[r][2 * c]), copy0);
      _mm256_store_si256(reinterpret_cast<__m256i*>(out.copy[r][2 * c + 1]), copy1);
      _mm256_store_ps(out.weight[r][2 * c], w0);
      _mm256_store_ps(out.weight[r][2 * c + 1], w1);
    }
    // Magnified lanes: the base and the first copy by H^2.
    if (_mm256_movemask_ps(magnify) != 0) {
      BlendSlot(out, r, 0, magnify, izero, _mm256_sub_ps(one, m));
      BlendSlot(out, r, 1, magnify, _mm256_set1_epi32(static_cast<int>(first_copy)), m);
      for (int slot = 2; slot < SelectionLanes::kSlots; ++slot)
        BlendSlot(out, r, slot, magnify, izero, zero);
    }
    if (_mm256_movemask_ps(thin) != 0) AddProbesAvx2(out, r, thin, magnify, H, Lmin);
    AddBoxProbesAvx2(out, r, read[r], H, Lmin);
  }
}

}  // namespace
#endif

void CopySelector::Select(const float* dudx, const float* dvdx, const float* dudy,
                          const float* dvdy, int n, SelectionLanes& out) const {
#if defined(__x86_64__) && defined(__GNUC__)
  if (kernel_ && n == SelectionLanes::kLanes) {
    SelectAvx2(dudx, dvdx, dudy, dvdy, half_size_, log2_size_, first_copy_, first_.data(),
               tilts_.data(), out);
    return;
  }
#endif
  SelectPortable(dudx, dvdx, dudy, dvdy, n, out);
}

// The one-footprint forms (tests, tools): the lane code.

ApertureReadings ReadingsOfFootprint(const TextureFootprint& f, int texture_size) {
  const LaneReadings r =
      ReadLane(f.dudx, f.dvdx, f.dudy, f.dvdy, 0.5f * static_cast<float>(texture_size));
  ApertureReadings out;
  if (!r.valid) return out;
  out.count = r.first < 1.0f ? 2 : 1;
  for (int k = 0; k < out.count; ++k) {
    out.shape[k].axis = (k == 0) == r.u_major ? TiltAxis::kU : TiltAxis::kV;
    out.shape[k].H = r.H[k];
    out.shape[k].L = r.L[k];
    out.shape[k].tg = r.tg[k];
  }
  out.weight[0] = r.first;
  out.weight[1] = 1.0f - r.first;
  return out;
}

ApertureShape ApertureFromFootprint(const TextureFootprint& f, int texture_size) {
  const ApertureReadings r = ReadingsOfFootprint(f, texture_size);
  return r.count > 0 ? r.shape[0] : ApertureShape{};
}

namespace {

CopyBlend BlendOf(const PrefilteredTable& table, const ApertureShape& shape, bool probes) {
  CopyBlend blend;
  if (shape.axis == TiltAxis::kNone || !(shape.H > 0.0)) {
    blend.magnify = true;  // degenerate derivatives: the base, bilinear
    return blend;
  }
  SelectionLanes lanes;
  lanes.reading_weight[0][0] = 1.0f;
  lanes.H[0][0] = static_cast<float>(shape.H);
  lanes.L[0][0] = static_cast<float>(shape.L);
  lanes.tg[0][0] = static_cast<float>(shape.tg);
  CopySelector(table).TableSlots(lanes.H[0][0], lanes.L[0][0], lanes.tg[0][0],
                                 shape.axis == TiltAxis::kV, lanes, 0, 0);
  lanes.probes[0][0] = 0;
  lanes.probe_scale[0][0] = 1.0f;  // the given shape as it is (no principal axes)
  lanes.box_probes[0][0] = 0;
  if (probes) {
    AddProbesLane(lanes, 0, 0);
    AddBoxProbesLane(lanes, 0, 0);
  }
  for (int s = 0; s < SelectionLanes::kSlots; ++s) {
    if (!(lanes.weight[0][s][0] > 0.0f)) continue;
    blend.copy[blend.count] = lanes.copy[0][s][0];
    blend.weight[blend.count++] = lanes.weight[0][s][0];
  }
  blend.probes = lanes.probes[0][0];
  if (blend.probes > 0) {
    blend.probe_step = lanes.probe_step[0][0];
    blend.probe_weight = lanes.probe_weight[0][0];
    blend.probe_end_weight = lanes.probe_end_weight[0][0];
  }
  blend.box_probes = lanes.box_probes[0][0];
  if (blend.box_probes > 0) {
    blend.box_probe_step = lanes.box_probe_step[0][0];
    blend.box_probe_weight = lanes.box_probe_weight[0][0];
    blend.box_probe_end_weight = lanes.box_probe_end_weight[0][0];
    blend.box_probe_rows = lanes.box_probe_rows[0][0];
  }
  return blend;
}

}  // namespace

CopyBlend SelectCopies(const PrefilteredTable& table, const ApertureShape& shape) {
  return BlendOf(table, shape, true);
}

CopyBlend SelectTableCopies(const PrefilteredTable& table, const ApertureShape& shape) {
  return BlendOf(table, shape, false);
}

}  // namespace aperture
