// `camsim psf SCENE --field F[,F...] --wavelength NM[,NM...] [-o DIR] [--size PX]
// [--oversample K] [--rays N] [--seed S] [--object-distance M]`: PSF images of the scene's
// camera (issue 39; the computation is integrator/camera/psf_image.h, docs/mtf.md "PSF
// images"). For every (field, wavelength) it writes into DIR
//   psf_f<F>_<λ>nm.exr  one channel Y, the energy per cell (pitch/K), summing to 1
//   psf_f<F>_<λ>nm.png  a preview: log10 scale over 4 decades below the peak, grey
// and one psf.json with every entry's image height, centroid offset, RMS radius, 50 % and
// 80 % encircled-energy radii (µm) and the vignetted fraction, and prints one line per
// entry. Every value is checked before anything is traced: bad input exits 2 naming the
// option, nothing written; all files appear at once (OutputSet).
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "integrator/camera/psf_image.h"

namespace camsim {

struct PsfArgs {
  std::string scene;
  std::vector<double> fields{0.0};
  std::vector<double> wavelengthsNm{550.0};
  PsfSettings settings;  // size, oversample, rays, seed, objectDistance (field, λ per entry)
  std::string outputDir = "out";
  bool help = false;
};

// args[0] == "psf". UsageError on bad usage or a value out of range (named as the option).
PsfArgs parsePsfArgs(const std::vector<std::string>& args);
std::string psfUsageText();

// The file name of one entry: psf_f0.5_550nm (without the extension).
std::string psfEntryName(double field, double wavelengthNm);

// Loads the scene, computes every entry, writes the files; `out` gets the summary lines,
// `log` the files written. Throws InputError / UsageError (nothing written then).
std::vector<std::filesystem::path> runPsf(const PsfArgs& args, std::ostream& out,
                                          std::ostream& log);

// Entry point from main(): parses `args` (args[0] == "psf"), runs, returns the exit code.
int runPsfCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& log);

}  // namespace camsim
