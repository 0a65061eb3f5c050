// Re-exposure without re-rendering (issue 37): a render's noise-free expected electrons,
// read back from its raw EXR, turned into new raw frames — other noise draws, another ISO,
// another exposure time of a static scene — through the capture's own step 5
// (exposeChannels, sensor/model/sensor_model.h) and its writers (writeDng, writeRawExr).
// What `camsim expose` and Python's camsim.expose_file() run; every setting is checked here
// once.
//
// | setting        | unit | default                      | meaning |
// |----------------|------|------------------------------|---------|
// | sensor         | —    | the file's camsim:sensor     | preset or YAML (needed when camsim:sensor_source is file); another sensor only with the same CFA, pixel area and QE |
// | iso            | —    | the file's camsim:iso        | gain K(ISO) and noise (noiseAtIso: calibrated range, errors) |
// | exposure_scale | —    | 1                            | X: electrons and exposure time × X; (0, 10⁶] |
// | frames         | —    | 1                            | N frames, 1 … 100000 |
// | seed           | —    | the file's camsim:noise_seed | frame f draws noise (seed, f) |
// | noise          | —    | full                         | none, photon, full |
//
// Input: a render's NAME_raw.exr (or NAME_evX_raw.exr): the layers electrons.<channel>
// (expected photo-electrons per photosite at the frame's exposure; one channel for a
// Bayer or mono sensor, one per plane for a stacked sensor), the header's camsim:sensor,
// camsim:cfa, camsim:exposure_time_s and camsim:static_scene. Exposure scaling is exact for
// a static scene: its expected electrons are ∫ irradiance dt over the shutter, so
//   μ_e(X·t) = X · μ_e(t)   (and likewise for the aperture area)
// A scene that moves during the exposure (camsim:static_scene 0: camera or object motion;
// a rolling shutter then matters too) has electrons that depend on the shutter interval:
// re-exposing it at scale X ≠ 1 is refused (new noise draws at X = 1 are exact and
// allowed). A file without camsim:static_scene (camsim before issue 37) is judged by its
// camsim:modelled ("static (no time sampling)" or "time (…)"); with neither it is refused.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "sensor/base/image.h"
#include "sensor/io/dng_writer.h"
#include "sensor/model/dark_frames.h"
#include "sensor/model/raw_image.h"
#include "sensor/model/sensor_model.h"
#include "sensor/model/sensor_spec.h"

namespace camsim {

class OutputSet;

inline constexpr long long kMaxExposeFrames = 100000;
inline constexpr double kMaxExposureScale = 1e6;

// electrons × scale, as a capture's bracket scales a static scene's; InputError (key
// exposure_scale, no file: the caller's to add) when a value would leave float's range (found
// by probing: inf was written, exit 0).
void scaleElectrons(Image& electrons, double scale);

struct ExposeFileSettings {
  std::string sensor;         // preset or YAML path; "": the file's camsim:sensor
  std::optional<double> iso;  // none: the file's camsim:iso (else the sensor's base ISO)
  double exposureScale = 1.0;
  long long frames = 1;
  std::optional<std::uint64_t> seed;  // none: the file's camsim:noise_seed (else 0)
  std::string noise = "full";
};

// A render's raw EXR as re-exposure reads it.
struct ElectronsExr {
  std::filesystem::path path;
  Image electrons;    // the electrons.<c> layers, named <c>
  Metadata metadata;  // every string attribute, as written
  std::string sensorName, cfaName;
  // camsim:sensor_source: "preset", "file" (SensorSpec::sourceKind) or "" (files before it)
  std::string sensorSource;
  double exposureTimeS = 0.0;
  std::optional<double> iso;
  std::optional<std::uint64_t> noiseSeed;
  std::optional<double> fNumber, focalLengthM;  // camsim:f_number, camsim:focal_length_m (m), > 0
  bool staticScene = false;
  std::string motion;  // why it is not static (camsim:modelled), for messages
};
// InputError naming the file and the missing or bad layer/attribute.
ElectronsExr readElectronsExr(const std::filesystem::path& path);

// Everything checked, electrons scaled: ready to expose frames.
struct ExposeJob {
  ElectronsExr input;
  SensorSpec sensor;
  Image electrons;  // input.electrons × exposureScale (as a capture's bracket scales them)
  ExposureSettings exposure;
  NoiseMode noise = NoiseMode::kFull;
  std::uint64_t seed = 0;
  long long frames = 1;
  double exposureScale = 1.0;
  std::string stem;   // output names: <stem>_f<NNNN>.dng, <stem>_f<NNNN>_raw.exr
  DngColor dngColor;  // from the sensor's QE under D65 (mosaic R, G, B sensors)
  // The sensor's dark frames in noise mode full (darkFramesFor), as the render adds them.
  std::optional<DarkFrameSet> darkFrames;
};
// Reads the file and checks the settings against it. InputError naming the file and the key
// (frames, exposure_scale, iso, noise, sensor, camsim:static_scene, …). lutsDir: the sensor
// presets and the ColorChecker reflectances of the DNG's colour matrices.
ExposeJob prepareExpose(const std::filesystem::path& electronsExr,
                        const ExposeFileSettings& settings, const std::filesystem::path& lutsDir);

// Frame f's raw planes: exposeChannels(electrons, sensor, exposure, noise, seed, f).
std::vector<RawImage> exposeJobFrame(const ExposeJob& job, std::uint64_t frame);

// The frame's output file names (a stacked sensor: one raw EXR per plane, no DNG).
std::vector<std::string> exposeFrameFiles(const ExposeJob& job, std::uint64_t frame);

// Writes frame f's files (to `paths`, one per exposeFrameFiles name, e.g. an OutputSet's
// temporaries) as `camsim render` writes its raw outputs: the DNG (mosaic sensors; EXIF
// exposure time × X, the chosen ISO, colour from the sensor's QE under D65) and the raw EXR
// (raw.DN and the scaled electrons.<c>: re-exposable itself). The header keeps the input's
// attributes with camsim:sensor, camsim:iso, camsim:exposure_time_s, camsim:noise_seed and
// camsim:frame replaced, plus camsim:exposed_from, camsim:exposure_scale and camsim:noise.
// Frames may be written from several threads at once (each to its own files).
void writeExposedFrame(const ExposeJob& job, std::uint64_t frame, const std::vector<RawImage>& raws,
                       const std::vector<std::filesystem::path>& paths);
// Exposes and writes frames 0 … job.frames − 1 into outputs (not committed), one after the
// other; `progress` (may be empty) is called after each frame with the number done.
void writeExposedFrames(const ExposeJob& job, OutputSet& outputs,
                        const std::function<void(long long)>& progress);

}  // namespace camsim
