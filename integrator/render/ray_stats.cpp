#include "integrator/render/ray_stats.h"

namespace camsim {

const char* rayKindName(RayKind kind) {
  switch (kind) {
    case RayKind::kCamera:
      return "camera";
    case RayKind::kBounce:
      return "bounce";
    case RayKind::kShadow:
      return "shadow";
  }
  return "?";
}

}  // namespace camsim
