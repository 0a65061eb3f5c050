// The sensor stage: expected electrons per photosite → digital numbers, EMVA 1288's model.
// In this order, for photosite (x, y) with expected photo-electrons μ_e (noise-free, from
// the film: photons × QE); the ISO-dependent values (K, σ_pre, full well, R, σ_row.t, b)
// come from noiseAtIso (sensor/model/sensor_noise.h):
//
//   1. dark:      μ_d = I_dark(T) · t_exp,   I_dark(T) = I_ref · 2^((T − T_ref)/T_double);
//                 a hot photosite (fixed, fraction f_hot) adds I_hot(T) · t_exp
//   2. shot:      n = Poisson(μ_e + μ_d)              (exact Poisson for every mean)
//   3. PRNU/DSNU: n' = n · (1 + σ_prnu · a(x,y)) + σ_dsnu · b(x,y) + σ_row · r(y) + σ_col · c(x)
//                 a, b, r, c ~ N(0,1), fixed: drawn from (pattern_seed, x, y), identical every frame
//   4. read:      n'' = n' + N(0, σ_pre²)
//   5. clip:      n''' = min(n'', full well)   (no clamp at 0 e⁻: read noise, DSNU and FPN
//                 may take a dark pixel below the black level, as in real raw data; step 7
//                 clamps at 0 DN, so nothing wraps around)
//   6. gain:      y = n''' · K + R + σ_row.t · q(frame, y) + b_tile   [DN], K = system gain at
//                 the ISO; R ~ N(0, σ_post²) or Tukey-λ(λ, s); q ~ N(0, 1) per row per frame
//   7. ADC:       DN = clamp(round(y + black level), 0, 2^bits − 1); a stuck photosite
//                 (fixed, fraction f_stuck) reads its fixed value instead
//
// Noise modes: none (steps 2–4 and the noise of 6 skipped: μ instead of random values),
// photon (only 2), full (all; hot and stuck photosites and black offsets only here). A
// noiseless sensor (SensorSpec::noiseless) always behaves as none. Random numbers come
// from a counter-based generator (sensor/base/counter_rng.h) keyed by (noise seed, frame,
// x, y): results do not depend on threads, tile order or image size (a crop at the origin
// reads the same values). The fixed patterns a, b, r, c are keyed by
// (pattern_seed, x, y) only. Rounding in step 7 is half-up: floor(v + 0.5).
//
// A stacked sensor (cfa "xyz", CfaLayout::isStacked()) records every channel at every
// photosite: call expose() once per channel image (all with the same spec); use a
// different noiseSeed per channel so that the channels' temporal noise is independent
// (the fixed patterns are shared: they belong to the photosite).
#pragma once

#include <cstdint>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sensor/base/enum_names.h"
#include "sensor/base/image.h"
#include "sensor/model/dark_frames.h"
#include "sensor/model/raw_image.h"
#include "sensor/model/sensor_spec.h"

namespace camsim {

enum class NoiseMode { kNone, kPhoton, kFull };
// The names scene files, --noise, Python and the JSON sidecar use (sensor/base/enum_names.h).
template <>
struct EnumNames<NoiseMode> {
  static constexpr EnumName<NoiseMode> kTable[] = {
      {NoiseMode::kNone, "none"}, {NoiseMode::kPhoton, "photon"}, {NoiseMode::kFull, "full"}};
};
// The same through the table, for callers that want plain functions.
const char* noiseModeName(NoiseMode mode);
std::optional<NoiseMode> noiseModeFromName(std::string_view name);  // nullopt if unknown
std::string noiseModeNames();  // "none, photon, full", for messages

struct ExposureSettings {
  double exposureTimeS = 1.0 / 60.0;  // for dark current (the film already holds the light)
  double iso = 100.0;
  // Noise mode full: add these recorded dark frames instead of the parametric
  // signal-independent terms (sensor/model/dark_frames.h). Not owned; null: none.
  const DarkFrameSet* darkFrames = nullptr;
};

// expectedElectrons: one channel, the noise-free photo-electrons per photosite.
RawImage expose(const Image& expectedElectrons, const SensorSpec& sensor,
                const ExposureSettings& settings, NoiseMode mode, std::uint64_t noiseSeed,
                std::uint64_t frame);

// Every channel of expectedElectrons: one RawImage for a one-channel (mosaic) image, one
// per channel for a stacked sensor's planes, channel c with noise seed
// noiseSeed + c·0x9e3779b9 so that the planes' temporal noise is independent (the fixed
// patterns are the photosite's and shared). What a capture's expose step and the Python
// module's camsim.expose() call, so both give the same DN for the same (seed, frame).
std::vector<RawImage> exposeChannels(const Image& expectedElectrons, const SensorSpec& sensor,
                                     const ExposureSettings& settings, NoiseMode mode,
                                     std::uint64_t noiseSeed, std::uint64_t frame);

// The noise-free output in DN before rounding (mode none): electrons plus the mean dark
// signal, clipped at the full well, times K, plus the black level, within [0, white level].
// Throws InputError for an ISO ≤ 0 or a negative exposure time (as expose() does).
double expectedDn(double electrons, const SensorSpec& sensor, const ExposureSettings& settings);

// The temporal variance of a photosite's output as a line in its mean signal (DN, black
// level subtracted, before clipping and quantisation), as a DNG NoiseProfile states it:
//   σ_y² = slopeDn · (μ_y − black) + offsetDn2,  slopeDn = K,  offsetDn2 = K²σ_pre² + σ_R² + σ_row²
// (the dark electrons' shot noise is in the first term: μ_y − black = K(μ_e + μ_d); the
// fixed patterns, black offsets, hot and stuck photosites are not temporal and not in it).
// Throws InputError as expectedDn() does.
struct VarianceLine {
  double slopeDn = 0.0;    // DN per DN of signal (= K)
  double offsetDn2 = 0.0;  // DN² at zero signal above the black level
};
VarianceLine temporalVarianceLine(const SensorSpec& sensor, const ExposureSettings& settings);

// What expose() draws in `mode` (the sidecar's noise_terms and the DNG's NoiseProfile
// both come from here): full gives modelledNoiseTerms (sensor_noise.h) or, with the
// sensor's dark_frames, shot, prnu (if set) and dark_frames; photon gives shot; none or a
// noiseless sensor nothing. The line is temporalVarianceLine's, with offset 0 for photon,
// and absent when nothing is drawn or dark frames carry the signal-independent noise (not
// a line the model knows). Both throw InputError as expectedDn() does, in every mode.
std::vector<std::string> exposedNoiseTerms(const SensorSpec& sensor, double iso, NoiseMode mode);
std::optional<VarianceLine> exposedVarianceLine(const SensorSpec& sensor,
                                                const ExposureSettings& settings, NoiseMode mode);

// One Poisson draw with mean `mean` from the counter-based stream named by `key` (exposed
// for tests). Exact for every mean: inversion by sequential search for mean < 10,
// Hörmann's PTRS transformed rejection (with a cancellation-free log-pmf) for mean ≥ 10;
// no normal approximation. Means ≤ 0 or NaN give 0; means above 2^52 are clamped to 2^52
// (far beyond any full well). Deterministic: the same (mean, key) gives the same draw.
std::uint64_t samplePoisson(double mean, std::uint64_t key);

}  // namespace camsim
