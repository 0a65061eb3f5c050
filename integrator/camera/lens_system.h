// LensSystem: a sequential lens (lens_file.h) placed in lens space (lens_surface.h: z along
// the axis towards the object, z = 0 at the rear vertex, the sensor at z = −s), with
//   - paraxial data by ray-transfer matrices at one wavelength (lens_system.cpp),
//   - real rays traced from the sensor out of the front, or from the object in, at one
//     wavelength: spheres, planes and even aspheres, Snell refraction, total internal
//     reflection and every clear aperture and the stop losing the ray (lens_trace.cpp),
//   - focus: the sensor distance s that images an object at a distance (lens_trace.cpp).
//
// Paraxial optics (reduced angles nu): a surface refracts by [[1, 0], [−φ, 1]], φ = (n' − n)c,
// a gap t in index n transfers by [[1, t/n], [0, 1]]. With the whole system's matrix
// [[A, B], [C, D]] (front vertex → rear vertex, object and image in air):
//   EFL f = −1/C, BFL = −A/C, FFL = −D/C (front vertex → front focal point, towards the
//   object), rear principal plane at z = f(1 − A), front at z = z_front − f(1 − D);
//   with the front group's (front vertex → stop) [[A_f, B_f], …] the entrance pupil is at
//   B_f/A_f behind the front vertex, of diameter D_stop/|A_f|; with the rear group's
//   (stop → rear vertex) [[…, B_r], […, D_r]] the exit pupil is at z = B_r/D_r, of diameter
//   D_stop/|D_r|. f-number N = f/EPD; an object at distance d images at
//   s = −(A d + B)/(C d + D) with magnification m = 1/(C d + D); the working f-number is
//   1/(2|u'|) for the image-space slope u' of the marginal ray through the pupil's rim.
//
// | quantity           | unit | meaning |
// |--------------------|------|---------|
// | object distance d  | m    | from the front vertex to the object plane; +∞: infinity |
// | sensor distance s  | m    | from the rear vertex to the sensor (the sensor plane is z = −s) |
// | stop diameter      | m    | the stop's circle-equivalent diameter (a bladed stop has the circle's area, as Aperture) |
#pragma once

#include <array>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "integrator/camera/aperture.h"
#include "integrator/camera/lens_file.h"

namespace camsim {

inline constexpr double kInfiniteDistance = std::numeric_limits<double>::infinity();

// A ray in lens space: origin (m) and unit direction.
struct LensRay {
  glm::dvec3 origin{0.0};
  glm::dvec3 direction{0.0, 0.0, 1.0};
};

// Paraxial (first-order) data at one wavelength, for one object distance and sensor. Plain
// doubles for a JSON sidecar or an EXR header (paraxialFields). Positions are lens-space z
// (m, +z towards the object, 0 at the rear vertex); ±∞ where a pupil is telecentric.
struct ParaxialData {
  double wavelengthNm = kLambdaDNm;           // nm
  double objectDistance = kInfiniteDistance;  // m, from the front vertex
  double totalTrack = 0.0;                    // m, front vertex z (rear vertex at 0)
  double effectiveFocalLength = 0.0;          // m, EFL
  double backFocalLength = 0.0;               // m, rear vertex → back focal point
  double frontFocalLength = 0.0;              // m, front vertex → front focal point (objectwards)
  double frontPrincipalPlaneZ = 0.0;          // m
  double rearPrincipalPlaneZ = 0.0;           // m
  double entrancePupilZ = 0.0;                // m
  double entrancePupilDiameter = 0.0;         // m
  double exitPupilZ = 0.0;                    // m
  double exitPupilDiameter = 0.0;             // m
  double pupilMagnification = 0.0;            // XPD / EPD
  double fNumber = 0.0;                       // EFL / EPD
  double imageDistance = 0.0;                 // m, rear vertex → paraxial image of the object
  double magnification = 0.0;                 // lateral, signed (< 0: inverted)
  double workingFNumber = 0.0;                // 1 / (2|u'|), the marginal ray's image slope
  glm::dvec2 sensorSize{0.0};                 // m, the sensor the field of view is for
  double fieldOfViewHorizontal = 0.0;         // rad, full angle seen from the entrance pupil
  double fieldOfViewVertical = 0.0;           // rad
  double fieldOfViewDiagonal = 0.0;           // rad
};

// ParaxialData as (name, unit, value) rows, one per field, in the struct's order: what a
// sidecar or EXR header writes (names snake_case, units "m", "nm", "rad", ""). At infinity
// object_distance is +∞ (sensor/io's JSON writer writes null, as focus_distance_m); for a
// lens that passed forCamera every other value is finite.
struct ParaxialField {
  const char* name;
  const char* unit;
  double value;
};
std::vector<ParaxialField> paraxialFields(const ParaxialData& p);

// The slowest f-number a traced lens is stopped to: beyond it the bundle from a film point is
// so narrow on the rear plane that the exit-pupil bounds (lens_pupil.h), which test three
// film radii per interval, no longer cover the radii between (measured: the double-Gauss's
// bounds lose their passing area from about f/500; lens_pupil_test).
inline constexpr double kMaxTracedFNumber = 128.0;

// How focusSensorDistance places the sensor.
enum class FocusMethod {
  kParaxial,  // the paraxial image at the wavelength (exact for the formulas above)
  kBestRms,   // the plane of least RMS spot radius of the real on-axis bundle filling the stop
};

class LensSystem {
 public:
  // Any valid prescription (plates and afocal systems too: tests). The stop starts at the
  // file's diameter, circular.
  explicit LensSystem(LensPrescription prescription);
  // For a camera: also throws InputError (naming the file) unless the lens converges
  // (0 < EFL < ∞), forms a real image behind its rear vertex (BFL > 0), has an entrance
  // and exit pupil at finite distance and finite paraxial data (at λ_d, infinity focus).
  static LensSystem forCamera(LensPrescription prescription);

  // The stop's circle-equivalent diameter (m, in (0, file's diameter]) and shape.
  void setStop(double diameter, int blades = 0, double rotation = 0.0);
  const Aperture& stop() const { return stop_; }
  double maxStopDiameter() const;  // m, the file's
  // The stop diameter (m) giving f-number N (EFL/EPD at λ_d), and the smallest N possible.
  double stopDiameterForFNumber(double fNumber) const;
  double minFNumber() const;
  // "" when the lens can be stopped to f/`fNumber` (from minFNumber to kMaxTracedFNumber),
  // else why not (the scene loader and the --f-number override name camera.lens.f_number).
  std::string fNumberProblem(double fNumber) const;

  const LensPrescription& prescription() const { return lens_; }
  int surfaceCount() const { return static_cast<int>(shapes_.size()); }
  int stopIndex() const { return lens_.stopIndex; }
  const SurfaceShape& shape(int i) const { return shapes_[static_cast<size_t>(i)]; }
  double frontVertexZ() const { return shapes_.front().vertexZ; }  // m, the total track
  double rearClearRadius() const;                                  // m, of the last surface
  bool disperses() const;

  // The media's indices at λ: after[i] behind surface i (in front of surface 0: air, 1).
  struct Indices {
    std::array<double, kMaxLensSurfaces> after;
  };
  Indices indicesAt(double lambdaNm) const;

  // Real rays (no allocation). From the film: a ray heading +z from the sensor side leaves
  // the front surface (the returned origin is on it, the direction towards the object).
  // From the object: a ray heading −z enters the front and leaves the rear surface. None
  // if it misses a surface, falls outside a clear aperture or the stop, or is totally
  // internally reflected.
  std::optional<LensRay> traceFromFilm(const LensRay& ray, const Indices& n) const;
  std::optional<LensRay> traceFromObject(const LensRay& ray, const Indices& n) const;
  std::optional<LensRay> traceFromFilm(const LensRay& ray, double lambdaNm) const {
    return traceFromFilm(ray, indicesAt(lambdaNm));
  }
  std::optional<LensRay> traceFromObject(const LensRay& ray, double lambdaNm) const {
    return traceFromObject(ray, indicesAt(lambdaNm));
  }
  // Whether (x, y) (m) on the stop's plane is inside the stop.
  bool insideStop(double x, double y) const;

  ParaxialData paraxial(double lambdaNm = kLambdaDNm, double objectDistance = kInfiniteDistance,
                        glm::dvec2 sensorSize = {0.036, 0.024}) const;
  // The sensor distance s (m) that focuses an object at objectDistance (m from the front
  // vertex, +∞ default) at λ. An object has a real image only beyond the front focal point
  // (objectDistance > ParaxialData::frontFocalLength): the caller range-checks.
  double focusSensorDistance(double objectDistance = kInfiniteDistance,
                             double lambdaNm = kLambdaDNm,
                             FocusMethod method = FocusMethod::kParaxial) const;
  // The focal length (m) measured with a real parallel ray at height h (m) from the object
  // side: h / tan u' of the ray leaving the rear; none if the ray is lost.
  std::optional<double> tracedFocalLength(double height, double lambdaNm = kLambdaDNm) const;
  // The angle (rad) to the axis, in object space, of the chief ray (through the stop's
  // centre) from the film point at height filmHeight (m) with the sensor at s: half the
  // full field angle at the sensor's corner. Clear apertures are ignored (a vignetted chief
  // ray still gives the field); none if the aim fails (the ray misses a surface).
  std::optional<double> chiefRayAngle(double filmHeight, double sensorDistance,
                                      double lambdaNm = kLambdaDNm) const;

 private:
  struct Matrix {
    double a = 1.0, b = 0.0, c = 0.0, d = 1.0;
  };
  // The paraxial matrix from just in front of surface `first` to just behind surface
  // `last`: each surface's refraction, and each gap's transfer but the one after `last`.
  Matrix matrix(int first, int last, const Indices& n) const;
  Matrix frontGroup(const Indices& n) const { return matrix(0, stopIndex(), n); }  // → stop
  Matrix rearGroup(const Indices& n) const {  // stop → rear vertex
    return matrix(stopIndex(), surfaceCount() - 1, n);
  }
  // Traces from the sensor side through surfaces last … first (first ≥ 0), with or without
  // the clear apertures and the stop.
  std::optional<LensRay> traceBack(const LensRay& ray, const Indices& n, int first,
                                   bool apertures) const;

  LensPrescription lens_;
  std::vector<SurfaceShape> shapes_;
  Aperture stop_;
};

}  // namespace camsim
