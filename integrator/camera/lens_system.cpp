// LensSystem: construction, the stop, the media's indices and the paraxial data (the
// equations are in lens_system.h). Tracing and focus: lens_trace.cpp.
#include "integrator/camera/lens_system.h"

#include <cmath>

#include "sensor/base/check.h"
#include "sensor/base/format.h"
#include "sensor/base/input_error.h"

namespace camsim {

LensSystem::LensSystem(LensPrescription prescription)
    : lens_(std::move(prescription)), stop_(1.0, 0, 0.0) {
  const int count = static_cast<int>(lens_.surfaces.size());
  CAMSIM_CHECK(count >= 1 && count <= kMaxLensSurfaces);
  CAMSIM_CHECK(lens_.stopIndex >= 0 && lens_.stopIndex < count);
  LensSurface& stopSurface = lens_.surfaces[static_cast<size_t>(lens_.stopIndex)];
  CAMSIM_CHECK(stopSurface.stop && stopSurface.radius == 0.0 && !stopSurface.aspheric());
  // The medium behind the stop is the one in front of it (lens_file.h).
  stopSurface.medium = lens_.stopIndex > 0
                           ? lens_.surfaces[static_cast<size_t>(lens_.stopIndex - 1)].medium
                           : Glass::air();
  // Vertices: the rear one at z = 0, each earlier one its thickness further towards +z.
  shapes_.resize(static_cast<size_t>(count));
  double z = 0.0;
  for (int i = count - 1; i >= 0; --i) {
    const LensSurface& s = lens_.surfaces[static_cast<size_t>(i)];
    CAMSIM_CHECK(s.apertureDiameter > 0.0 && s.thickness >= 0.0);
    if (i < count - 1) z += s.thickness;
    shapes_[static_cast<size_t>(i)] = SurfaceShape::from(s, z);
  }
  setStop(maxStopDiameter());
}

LensSystem LensSystem::forCamera(LensPrescription prescription) {
  LensSystem lens(std::move(prescription));
  const Indices n = lens.indicesAt(kLambdaDNm);
  const Matrix m = lens.matrix(0, lens.surfaceCount() - 1, n);
  const auto fail = [&](const std::string& message) {
    throw InputError({lens.lens_.source, 0, 0}, "", message);
  };
  if (!(m.c < 0.0) || !std::isfinite(-1.0 / m.c))
    fail("the lens does not converge (paraxial power " + formatShortest(-m.c) +
         " 1/m at 587.56 nm): no camera lens");
  if (!(-m.a / m.c > 0.0))
    fail("the lens images infinity in front of its rear vertex (back focal length " +
         formatShortest(-m.a / m.c * 1e3) + " mm)");
  if (!(std::abs(lens.frontGroup(n).a) > 1e-9) || !(std::abs(lens.rearGroup(n).d) > 1e-9))
    fail("the stop images to infinity (a telecentric lens): not supported");
  for (const ParaxialField& field : paraxialFields(lens.paraxial()))
    if (!std::isfinite(field.value) && field.name != std::string("object_distance"))
      fail(std::string("the lens's paraxial ") + field.name + " is not finite");
  return lens;
}

double LensSystem::maxStopDiameter() const {
  return lens_.surfaces[static_cast<size_t>(lens_.stopIndex)].apertureDiameter;
}

void LensSystem::setStop(double diameter, int blades, double rotation) {
  CAMSIM_CHECK(diameter > 0.0 && diameter <= maxStopDiameter() * (1.0 + 1e-9));
  stop_ = Aperture(diameter, blades, rotation);
}

double LensSystem::stopDiameterForFNumber(double fNumber) const {
  const Indices n = indicesAt(kLambdaDNm);
  const double f = -1.0 / matrix(0, surfaceCount() - 1, n).c;
  return f / fNumber * std::abs(frontGroup(n).a);
}

double LensSystem::minFNumber() const {
  const Indices n = indicesAt(kLambdaDNm);
  const double f = -1.0 / matrix(0, surfaceCount() - 1, n).c;
  return f / (maxStopDiameter() / std::abs(frontGroup(n).a));
}

std::string LensSystem::fNumberProblem(double fNumber) const {
  const double widest = minFNumber();
  if (fNumber < widest * (1.0 - 1e-9))
    return "f_number " + formatNumber(fNumber, 6) + " is faster than the lens's widest, f/" +
           formatNumber(widest, 6) + " (its file's stop)";
  if (fNumber > kMaxTracedFNumber)
    return "f_number " + formatNumber(fNumber, 6) +
           " is slower than a traced lens is stopped to, f/" + formatNumber(kMaxTracedFNumber, 6) +
           " (its bundles on the rear element become too narrow for the exit-pupil bounds; "
           "docs/camera.md)";
  return "";
}

double LensSystem::rearClearRadius() const {
  return std::sqrt(shapes_.back().clearRadius2);
}

bool LensSystem::disperses() const {
  for (const LensSurface& s : lens_.surfaces)
    if (s.medium.disperses()) return true;
  return false;
}

LensSystem::Indices LensSystem::indicesAt(double lambdaNm) const {
  Indices n;
  for (size_t i = 0; i < lens_.surfaces.size(); ++i)
    n.after[i] = lens_.surfaces[i].medium.index(lambdaNm);
  return n;
}

bool LensSystem::insideStop(double x, double y) const {
  const double r = stop_.circumradius();
  const double r2 = x * x + y * y;
  if (stop_.blades() == 0 || r2 == 0.0) return r2 <= r * r;
  // A regular N-gon: inside when the point's projection on its sector's apothem direction
  // is at most the apothem R cos(π/N).
  const double sector = 2.0 * M_PI / stop_.blades();
  double phi = std::atan2(y, x) - stop_.rotation();
  phi -= sector * std::floor(phi / sector);  // [0, sector)
  return std::sqrt(r2) * std::cos(phi - 0.5 * sector) <= r * std::cos(0.5 * sector);
}

LensSystem::Matrix LensSystem::matrix(int first, int last, const Indices& n) const {
  Matrix m;
  for (int i = first; i <= last; ++i) {
    const double before = i > 0 ? n.after[static_cast<size_t>(i - 1)] : 1.0;
    const double after = n.after[static_cast<size_t>(i)];
    // Refraction [[1, 0], [−φ, 1]] applied after m.
    const double phi = (after - before) * lens_.surfaces[static_cast<size_t>(i)].curvature();
    m = {m.a, m.b, m.c - phi * m.a, m.d - phi * m.b};
    if (i < last) {  // the gap to the next surface: [[1, t/n], [0, 1]]
      const double reduced = lens_.surfaces[static_cast<size_t>(i)].thickness / after;
      m = {m.a + reduced * m.c, m.b + reduced * m.d, m.c, m.d};
    }
  }
  return m;
}

ParaxialData LensSystem::paraxial(double lambdaNm, double objectDistance,
                                  glm::dvec2 sensorSize) const {
  const Indices n = indicesAt(lambdaNm);
  const Matrix m = matrix(0, surfaceCount() - 1, n);
  const Matrix front = frontGroup(n), rear = rearGroup(n);
  const double stopD = stop_.area() > 0.0 ? std::sqrt(4.0 * stop_.area() / M_PI) : 0.0;
  ParaxialData p;
  p.wavelengthNm = lambdaNm;
  p.objectDistance = objectDistance;
  p.totalTrack = frontVertexZ();
  const double f = -1.0 / m.c;  // ±∞ when afocal
  p.effectiveFocalLength = f;
  p.backFocalLength = -m.a / m.c;
  p.frontFocalLength = -m.d / m.c;
  p.frontPrincipalPlaneZ = frontVertexZ() - f * (1.0 - m.d);
  p.rearPrincipalPlaneZ = f * (1.0 - m.a);
  const double pupilOffset = front.b / front.a;  // entrance pupil behind the front vertex
  p.entrancePupilZ = frontVertexZ() - pupilOffset;
  p.entrancePupilDiameter = stopD / std::abs(front.a);
  p.exitPupilZ = rear.b / rear.d;
  p.exitPupilDiameter = stopD / std::abs(rear.d);
  p.pupilMagnification = p.exitPupilDiameter / p.entrancePupilDiameter;
  p.fNumber = f / p.entrancePupilDiameter;
  p.sensorSize = sensorSize;
  const glm::dvec3 half(0.5 * sensorSize.x, 0.5 * sensorSize.y,
                        0.5 * std::hypot(sensorSize.x, sensorSize.y));
  glm::dvec3 fov;
  if (std::isinf(objectDistance)) {
    p.imageDistance = p.backFocalLength;
    p.magnification = 0.0;
    p.workingFNumber = p.fNumber;
    for (int k = 0; k < 3; ++k) fov[k] = 2.0 * std::atan(half[k] / f);
  } else {
    const double d = objectDistance;
    p.imageDistance = -(m.a * d + m.b) / (m.c * d + m.d);
    p.magnification = 1.0 / (m.c * d + m.d);
    // The marginal ray from the axial object point through the entrance pupil's rim.
    const double u = 0.5 * p.entrancePupilDiameter / (d + pupilOffset);
    const double uImage = m.c * (u * d) + m.d * u;
    p.workingFNumber = 1.0 / (2.0 * std::abs(uImage));
    // The object-space field: the sensor's image on the object plane seen from the pupil.
    for (int k = 0; k < 3; ++k)
      fov[k] = 2.0 * std::atan(half[k] / std::abs(p.magnification) / (d + pupilOffset));
  }
  p.fieldOfViewHorizontal = fov.x;
  p.fieldOfViewVertical = fov.y;
  p.fieldOfViewDiagonal = fov.z;
  return p;
}

std::vector<ParaxialField> paraxialFields(const ParaxialData& p) {
  return {{"wavelength", "nm", p.wavelengthNm},
          {"object_distance", "m", p.objectDistance},
          {"total_track", "m", p.totalTrack},
          {"effective_focal_length", "m", p.effectiveFocalLength},
          {"back_focal_length", "m", p.backFocalLength},
          {"front_focal_length", "m", p.frontFocalLength},
          {"front_principal_plane_z", "m", p.frontPrincipalPlaneZ},
          {"rear_principal_plane_z", "m", p.rearPrincipalPlaneZ},
          {"entrance_pupil_z", "m", p.entrancePupilZ},
          {"entrance_pupil_diameter", "m", p.entrancePupilDiameter},
          {"exit_pupil_z", "m", p.exitPupilZ},
          {"exit_pupil_diameter", "m", p.exitPupilDiameter},
          {"pupil_magnification", "", p.pupilMagnification},
          {"f_number", "", p.fNumber},
          {"image_distance", "m", p.imageDistance},
          {"magnification", "", p.magnification},
          {"working_f_number", "", p.workingFNumber},
          {"sensor_width", "m", p.sensorSize.x},
          {"sensor_height", "m", p.sensorSize.y},
          {"field_of_view_horizontal", "rad", p.fieldOfViewHorizontal},
          {"field_of_view_vertical", "rad", p.fieldOfViewVertical},
          {"field_of_view_diagonal", "rad", p.fieldOfViewDiagonal}};
}

}  // namespace camsim
