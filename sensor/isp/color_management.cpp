#include "sensor/isp/color_management.h"

#include <OpenColorIO/OpenColorIO.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <system_error>
#include <utility>

#include "sensor/base/check.h"
#include "sensor/base/file_status.h"
#include "sensor/base/input_error.h"
#include "sensor/base/luts_directory.h"

namespace camsim {

namespace OCIO = OCIO_NAMESPACE;

struct OcioProcessor::Impl {
  OcioConfigLocation location;
  OCIO::ConstConfigRcPtr config;
  std::string input;
};

struct DisplayPipeline::Impl {
  OCIO::ConstCPUProcessorRcPtr cpu;
};

namespace {

std::string joinQuoted(const std::vector<std::string>& names) {
  if (names.empty()) return "(none)";
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "'" : ", '") + n + "'";
  return out;
}

std::string trim(const std::string& s) {
  const size_t begin = s.find_first_not_of(" \t");
  if (begin == std::string::npos) return {};
  return s.substr(begin, s.find_last_not_of(" \t") - begin + 1);
}

// The look names of an OCIO look list: "a, +b, -c" or alternatives "a | b".
std::vector<std::string> lookNames(const std::string& looks) {
  std::vector<std::string> names;
  std::string current;
  for (size_t i = 0; i <= looks.size(); ++i) {
    if (i == looks.size() || looks[i] == ',' || looks[i] == '|') {
      std::string name = trim(current);
      if (!name.empty() && (name[0] == '+' || name[0] == '-')) name = trim(name.substr(1));
      names.push_back(name);
      current.clear();
    } else {
      current += looks[i];
    }
  }
  return names;
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

}  // namespace

std::filesystem::path camsimOcioConfigPath() {
  return lutsDirectory() / "config.ocio";
}

OcioConfigLocation resolveOcioConfig(const std::filesystem::path& explicitPath) {
  if (!explicitPath.empty()) return {explicitPath, OcioConfigOrigin::Explicit};
  if (const char* env = std::getenv("OCIO"); env && *env)
    return {env, OcioConfigOrigin::OcioEnvironment};
  return {camsimOcioConfigPath(), OcioConfigOrigin::Camsim};
}

std::string describeOcioConfigOrigin(OcioConfigOrigin origin) {
  switch (origin) {
    case OcioConfigOrigin::Explicit:
      return "explicit path";
    case OcioConfigOrigin::OcioEnvironment:
      return "$OCIO";
    case OcioConfigOrigin::Camsim:
      return "camsim's luts/config.ocio";
  }
  return "?";
}

OcioProcessor::OcioProcessor(const std::filesystem::path& explicitConfig,
                             const std::string& inputColorSpace) {
  auto impl = std::make_shared<Impl>();
  impl->location = resolveOcioConfig(explicitConfig);
  const std::string file = impl->location.path.string();
  const SourceLocation where{file, 0, 0};
  const std::string from =
      " (OCIO config from " + describeOcioConfigOrigin(impl->location.origin) + ")";
  if (!isRegularFile(impl->location.path)) throw InputError(where, "", "no such file" + from);
  try {
    impl->config = OCIO::Config::CreateFromFile(file.c_str());
    impl->config->validate();
  } catch (const OCIO::Exception& e) {
    throw InputError(where, "", std::string("invalid OCIO config") + from + ": " + e.what());
  }
  const OCIO::Config& config = *impl->config;
  std::string wanted = inputColorSpace;
  if (wanted.empty()) wanted = config.getColorSpace("ACEScg") ? "ACEScg" : OCIO::ROLE_SCENE_LINEAR;
  const OCIO::ConstColorSpaceRcPtr space = config.getColorSpace(wanted.c_str());
  if (!space) {
    std::vector<std::string> names;
    for (int i = 0; i < config.getNumColorSpaces(); ++i)
      names.emplace_back(config.getColorSpaceNameByIndex(i));
    throw InputError(where, "input colour space",
                     "the config has no colour space '" + wanted +
                         "' for camsim's ACEScg; its colour spaces are " + joinQuoted(names));
  }
  impl->input = space->getName();
  impl_ = std::move(impl);
}

const OcioConfigLocation& OcioProcessor::location() const {
  return impl_->location;
}
const std::string& OcioProcessor::inputColorSpace() const {
  return impl_->input;
}

std::vector<std::filesystem::path> OcioProcessor::searchFolders() const {
  const OCIO::Config& config = *impl_->config;
  const OCIO::ConstContextRcPtr context = config.getCurrentContext();
  const std::filesystem::path working = config.getWorkingDir();
  std::vector<std::filesystem::path> out;
  for (int i = 0; i < config.getNumSearchPaths(); ++i) {
    const std::filesystem::path folder = context->resolveStringVar(config.getSearchPath(i));
    out.push_back(folder.is_absolute() ? folder : working / folder);
  }
  return out;
}

std::vector<std::string> OcioProcessor::displays() const {
  std::vector<std::string> out;
  for (int i = 0; i < impl_->config->getNumDisplays(); ++i)
    out.emplace_back(impl_->config->getDisplay(i));
  return out;
}

std::string OcioProcessor::defaultDisplay() const {
  return impl_->config->getDefaultDisplay();
}

std::vector<std::string> OcioProcessor::views(const std::string& display) const {
  const std::string d = resolve({display, "", ""}).display;
  std::vector<std::string> out;
  for (int i = 0; i < impl_->config->getNumViews(d.c_str()); ++i)
    out.emplace_back(impl_->config->getView(d.c_str(), i));
  return out;
}

std::string OcioProcessor::defaultView(const std::string& display) const {
  const std::string d = resolve({display, "", ""}).display;
  return impl_->config->getDefaultView(d.c_str());
}

std::vector<std::string> OcioProcessor::looks() const {
  std::vector<std::string> out;
  for (int i = 0; i < impl_->config->getNumLooks(); ++i)
    out.emplace_back(impl_->config->getLookNameByIndex(i));
  return out;
}

DisplayChoice OcioProcessor::resolve(const DisplayChoice& choice) const {
  const OCIO::Config& config = *impl_->config;
  const SourceLocation where{impl_->location.path.string(), 0, 0};
  DisplayChoice out = choice;
  if (out.display.empty()) out.display = config.getDefaultDisplay();
  const std::vector<std::string> allDisplays = displays();
  if (!contains(allDisplays, out.display))
    throw InputError(where, "display",
                     "unknown display '" + out.display + "'; the config's displays are " +
                         joinQuoted(allDisplays));
  if (out.view.empty()) out.view = config.getDefaultView(out.display.c_str());
  std::vector<std::string> allViews;
  for (int i = 0; i < config.getNumViews(out.display.c_str()); ++i)
    allViews.emplace_back(config.getView(out.display.c_str(), i));
  if (!contains(allViews, out.view))
    throw InputError(where, "view",
                     "unknown view '" + out.view + "' for display '" + out.display +
                         "'; its views are " + joinQuoted(allViews));
  out.looks = trim(out.looks);
  if (!out.looks.empty()) {
    const char* viewSpace =
        config.getDisplayViewColorSpaceName(out.display.c_str(), out.view.c_str());
    const OCIO::ConstColorSpaceRcPtr space = config.getColorSpace(viewSpace);
    if (space && space->isData())
      throw InputError(where, "look",
                       "view '" + out.view + "' of display '" + out.display +
                           "' shows data unchanged: looks cannot apply to it");
    const std::vector<std::string> allLooks = looks();
    for (const std::string& name : lookNames(out.looks))
      if (!contains(allLooks, name))
        throw InputError(where, "look",
                         "unknown look '" + name + "' in '" + out.looks +
                             "'; the config's looks are " + joinQuoted(allLooks));
  }
  return out;
}

DisplayPipeline OcioProcessor::pipeline(const DisplayChoice& choice) const {
  DisplayChoice resolved = resolve(choice);
  const char* input = impl_->input.c_str();
  auto group = OCIO::GroupTransform::Create();
  if (!resolved.looks.empty()) {
    // ACEScg → (process space → looks → back) → ACEScg, then the display/view.
    auto look = OCIO::LookTransform::Create();
    look->setSrc(input);
    look->setDst(input);
    look->setLooks(resolved.looks.c_str());
    group->appendTransform(look);
  }
  auto view = OCIO::DisplayViewTransform::Create();
  view->setSrc(input);
  view->setDisplay(resolved.display.c_str());
  view->setView(resolved.view.c_str());
  group->appendTransform(view);
  auto impl = std::make_shared<DisplayPipeline::Impl>();
  try {
    impl->cpu = impl_->config->getProcessor(group)->getDefaultCPUProcessor();
  } catch (const OCIO::Exception& e) {
    throw InputError(
        {impl_->location.path.string(), 0, 0}, "",
        "OCIO cannot build display '" + resolved.display + "', view '" + resolved.view + "'" +
            (resolved.looks.empty() ? "" : ", looks '" + resolved.looks + "'") + ": " + e.what());
  }
  return DisplayPipeline(std::move(resolved), std::move(impl));
}

Image OcioProcessor::toDisplay(const Image& acescg, const DisplayChoice& choice) const {
  const int r = acescg.channelIndex("R"), g = acescg.channelIndex("G");
  const int b = acescg.channelIndex("B");
  CAMSIM_CHECK(r >= 0 && g >= 0 && b >= 0);
  const DisplayPipeline pipe = pipeline(choice);
  Image out(acescg.width, acescg.height, {"R", "G", "B"});
  const size_t pixels = static_cast<size_t>(acescg.width) * static_cast<size_t>(acescg.height);
  const size_t stride = acescg.channels.size();
  for (size_t i = 0; i < pixels; ++i) {
    out.pixels[3 * i + 0] = acescg.pixels[stride * i + static_cast<size_t>(r)];
    out.pixels[3 * i + 1] = acescg.pixels[stride * i + static_cast<size_t>(g)];
    out.pixels[3 * i + 2] = acescg.pixels[stride * i + static_cast<size_t>(b)];
  }
  pipe.applyInPlace(out.pixels, out.width, out.height);
  return out;
}

namespace {

// One pixel scaled so that its largest |channel| is at most kMaxInput (applyInPlace).
void limitInput(float* rgb) {
  const float largest = std::max({std::abs(rgb[0]), std::abs(rgb[1]), std::abs(rgb[2])});
  if (!(largest > DisplayPipeline::kMaxInput)) return;
  if (std::isinf(largest)) {  // its infinite channels at the limit, the others nothing beside
    for (int c = 0; c < 3; ++c)
      rgb[c] = std::isinf(rgb[c]) ? std::copysign(DisplayPipeline::kMaxInput, rgb[c]) : 0.0f;
    return;
  }
  const float k = DisplayPipeline::kMaxInput / largest;
  for (int c = 0; c < 3; ++c) rgb[c] *= k;
}

}  // namespace

DisplayPipeline::DisplayPipeline(DisplayChoice choice, std::shared_ptr<const Impl> impl)
    : choice_(std::move(choice)), impl_(std::move(impl)) {}

void DisplayPipeline::applyInPlace(std::span<float> rgb, int width, int height) const {
  CAMSIM_CHECK(width >= 0 && height >= 0);
  CAMSIM_CHECK(rgb.size() == static_cast<size_t>(width) * static_cast<size_t>(height) * 3);
  if (rgb.empty()) return;
  for (std::size_t i = 0; i < rgb.size(); i += 3) limitInput(&rgb[i]);
  OCIO::PackedImageDesc desc(rgb.data(), width, height, 3);
  impl_->cpu->apply(desc);
}

std::array<float, 3> DisplayPipeline::applyPixel(std::array<float, 3> rgb) const {
  limitInput(rgb.data());
  impl_->cpu->applyRGB(rgb.data());
  return rgb;
}

namespace {

template <typename T>
std::vector<T> quantize(std::span<const float> encoded, float maxCode) {
  std::vector<T> out(encoded.size());
  for (size_t i = 0; i < encoded.size(); ++i) {
    const float v = encoded[i];
    const float clamped = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
    out[i] = static_cast<T>(std::lround(clamped * maxCode));
  }
  return out;
}

}  // namespace

std::vector<std::uint8_t> quantizeDisplay8(std::span<const float> encoded) {
  return quantize<std::uint8_t>(encoded, 255.0f);
}

std::vector<std::uint16_t> quantizeDisplay16(std::span<const float> encoded) {
  return quantize<std::uint16_t>(encoded, 65535.0f);
}

}  // namespace camsim
