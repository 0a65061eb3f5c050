// Lens prescription files: pbrt-v4's realistic-camera format, extended.
//
// One surface per line from the object side to the image side; `#` starts a comment;
// blank lines are skipped. Four whitespace-separated columns, then optional key=value
// tokens (camsim's extension; pbrt-v4's files have none and read unchanged):
//
// | column / key | unit        | meaning |
// |--------------|-------------|---------|
// | radius       | mm          | vertex radius of curvature R; > 0: centre of curvature on the image side; 0: a plane (and on the stop line) |
// | thickness    | mm          | axial distance to the next surface's vertex, ≥ 0 (the last line's is not used: focusing sets the sensor) |
// | N            | —           | index after the surface at λ_d = 587.56 nm; 1 air, 0 the aperture stop (radius 0), else in [1, 3] |
// | aperture     | mm          | clear-aperture diameter, > 0 (the stop's: its largest diameter) |
// | glass=NAME   | —           | the medium's dispersion from luts/spectra/glasses/NAME.csv, shifted to n(λ_d) = N (glass.h) |
// | abbe=V       | —           | dispersion from the Abbe number V_d in [5, 200], N as n_d (glass.h) |
// | conic=k      | —           | conic constant (0 sphere, −1 paraboloid, < −1 hyperboloid, > 0 oblate ellipsoid) |
// | a4 … a16     | mm^(1−2i)   | even asphere terms a_{2i}, i = 2 … 8 |
//
// The surface's sag (its axial departure from the vertex plane, towards the image for
// z > 0) at radial distance r is
//
//   z(r) = c r² / (1 + √(1 − (1 + k) c² r²)) + Σ_{i=2..8} a_{2i} r^{2i},   c = 1/R.
//
// A line with neither glass nor abbe has no dispersion (n = N at every wavelength): the
// default, as in pbrt-v4. Both on one line, either on an air line (N = 1), or any extension
// key on the stop line is an error; so are an unknown or repeated key, a value that is no
// number, NaN or ∞, a negative thickness, a clear aperture ≤ 0, a surface whose sag is
// undefined inside its clear aperture, no stop, two stops, an index after the last surface
// other than 1 (the sensor is in air), or more than kMaxLensSurfaces lines. pbrt-v4 takes
// any radius-0 line as the stop; camsim takes the N = 0 line and reads radius 0 with
// N ≥ 1 as a plane (a filter, a cover glass). The medium after the stop is the medium
// before it (air in every published file).
//
// Everything is converted once to SI: metres, and a_{2i} in m^(1−2i).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "integrator/camera/lens_surface.h"
#include "sensor/base/table_search.h"

namespace camsim {

struct LensPrescription {
  std::string source;                 // file name, for messages
  std::vector<LensSurface> surfaces;  // object side first
  int stopIndex = -1;                 // index of the stop in surfaces
};

// Where glass=NAME is looked for: glasses/NAME.csv in search's folders (a scene passes
// its own spectra path; the default is luts/spectra). Each table read is recorded.
TableSearch defaultGlassSearch();

// Parses a prescription. Throws InputError naming sourceName, the line, the column and
// the column's name or the key.
LensPrescription parseLensPrescription(std::string_view text, const std::string& sourceName,
                                       const TableSearch& glassSearch = defaultGlassSearch());
// Reads and parses a file (InputError if it cannot be read).
LensPrescription readLensPrescription(const std::filesystem::path& file,
                                      const TableSearch& glassSearch = defaultGlassSearch());

}  // namespace camsim
