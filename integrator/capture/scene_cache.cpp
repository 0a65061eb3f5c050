#include "integrator/capture/scene_cache.h"

namespace camsim {

Scene& SceneCache::sceneFor(const SceneDescription& d) {
  reused_ = scene_ && d.sourceFnv1a == sourceFnv1a_ && scene_->canRetarget(d);
  if (reused_) {
    try {
      scene_->retarget(d);  // may build the motion-dependent parts again (Scene::setCamera)
    } catch (...) {
      clear();  // a failed rebuild leaves the Scene unusable
      throw;
    }
  } else {
    scene_.reset();  // the old BVH is freed before the new one is built
    scene_ = std::make_unique<Scene>(d);
    sourceFnv1a_ = d.sourceFnv1a;
  }
  return *scene_;
}

}  // namespace camsim
