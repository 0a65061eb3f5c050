// The projection override's parts (overrides.h): read and checked by the scene loader on a
// camera-only probe scene, as the pose override is, and written back as one line of JSON.
#pragma once

#include <string>
#include <string_view>

#include "integrator/scene/overrides.h"

namespace camsim {

// The camera.projection map in `text` (YAML or JSON, flow or block), checked by the loader:
// InputError at where, key camera.projection.<key> (camera.projection for a syntax error).
ProjectionOverride readProjectionOverride(std::string_view text, const SourceLocation& where);

// p as one line of JSON, numbers in their shortest round-trip form:
// {"model": "equidistant", "max_field_angle_deg": 95}.
std::string projectionOverrideText(const ProjectionOverride& p);

// Sets d's camera.projection (and whether its intrinsics follow the lens) from p, checked by
// the loader again; InputError at where for what the loader refuses, and for a model other
// than opencv on a camera whose aperture.pupil is flat.
void setProjection(SceneDescription& d, const ProjectionOverride& p, const SourceLocation& where);

}  // namespace camsim
