// The scene loader's `camera.lens`: a traced lens (integrator/camera/lens_camera.h) read
// from a prescription file, its f-number and focus distance range-checked here, once
// (docs/scene-format.md, `camera.lens`).
#include <string>

#include "integrator/scene/scene_loader_parts.h"
#include "integrator/scene/setting_ranges.h"
#include "sensor/base/format.h"
#include "sensor/base/input_error.h"
#include "sensor/base/luts_directory.h"

namespace camsim {

void parseCameraLens(const YamlValue& value, const YamlMap& camera, const TableSearch& search,
                     PhysicalCameraParams& c) {
  // The thin lens's own keys have no meaning beside a prescription: refused, not ignored.
  for (const char* key :
       {"focal_length_mm", "f_number", "focus_distance_m", "distortion", "projection", "gltf"})
    if (camera.has(key))
      value.fail(std::string("camera.lens replaces the thin lens: remove camera.") + key +
                 " (the lens file gives the focal length; f_number and focus_distance_m go "
                 "inside camera.lens)");
  if (c.pupil != LensPupil::kAplanatic)
    value.fail("camera.aperture.pupil has no meaning with camera.lens (the pupil is traced)");
  YamlMap lm(value);
  const YamlValue fileValue = lm.require("file");
  // A path relative to the scene's folder (the search's first), else a name in luts/lenses.
  TableSearch lensSearch;
  if (!search.directories.empty()) lensSearch.directories.push_back(search.directories.front());
  lensSearch.directories.push_back(lutsDirectory() / "lenses");
  lensSearch.filesRead = search.filesRead;
  const std::filesystem::path file = lensSearch.find(fileValue, fileValue.string(), "lens file");
  LensSpec spec;
  std::optional<LensSystem> lens;
  try {
    spec.prescription = readLensPrescription(file, search);
    lens.emplace(LensSystem::forCamera(spec.prescription));
  } catch (const InputError& e) {
    fileValue.failInNamedFile(e);
  }
  if (auto v = lm.find("f_number")) {
    spec.fNumber = v->number(setting_ranges::kFNumber.lo, setting_ranges::kFNumber.hi);
    if (const std::string problem = lens->fNumberProblem(spec.fNumber); !problem.empty())
      v->fail(problem);
  }
  if (spec.fNumber > 0.0) lens->setStop(lens->stopDiameterForFNumber(spec.fNumber));
  const ParaxialData paraxial = lens->paraxial();
  if (auto v = lm.find("focus_distance_m")) {
    spec.focusDistance = v->number(0.0, 1e12, true);
    const double fromVertex = objectDistanceFromVertex(*lens, spec.focusDistance);
    if (!(fromVertex > paraxial.frontFocalLength * 1.0001) ||
        !(spec.focusDistance > paraxial.effectiveFocalLength * 1.0001))
      v->fail(
          "focus distance (from the entrance pupil) must put the object beyond the lens's "
          "front focal point and beyond 1.0001 × its focal length (" +
          std::to_string(paraxial.effectiveFocalLength * 1.0001) + " m)");
    // Found by probing: a fisheye's entrance pupil lies 11.5 mm inside it, so 10.1 mm put the
    // plane of focus inside the glass (rendered, exit 0); a telephoto at 0.349 m, beyond its
    // front focal point, has a real bundle that leaves the rear group diverging (its best
    // focus in front of the rear vertex: an internal check aborted the render).
    if (!(fromVertex > 0.0))
      v->fail("focus distance " + formatShortest(spec.focusDistance) +
              " m (from the entrance pupil) puts the plane of focus " +
              formatNumber(-fromVertex * 1e3, 4) +
              " mm behind the lens's front vertex, inside the lens; the entrance pupil lies " +
              formatNumber((spec.focusDistance - fromVertex) * 1e3, 4) + " mm behind it");
  }
  lm.finish({"file", "f_number", "focus_distance_m"});
  if (c.aperture) {
    spec.blades = c.aperture->blades;
    spec.rotation = c.aperture->rotation;
  }
  // Focused at infinity (the default) too: found by probing, an aspheric singlet whose real
  // rays from infinity diverge passed here and aborted the render on an internal check.
  if (const std::string problem = realImageProblem(spec); !problem.empty()) {
    const auto focus = lm.find("focus_distance_m");
    (focus ? *focus : value).fail(problem + (focus ? "; focus farther away" : ""));
  }
  // The thin-lens stand-in (intrinsics, project(), the ground truth): the lens's paraxial
  // focal length and f-number at λ_d; PhysicalCamera sets them again from the same lens.
  c.focalLength = paraxial.effectiveFocalLength;
  c.fNumber = spec.fNumber > 0.0 ? spec.fNumber : paraxial.fNumber;
  c.focusDistance = spec.focusDistance;
  c.lens = std::move(spec);
}

}  // namespace camsim
