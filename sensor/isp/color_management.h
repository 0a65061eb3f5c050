// OpenColorIO output: scene-linear ACEScg → display-referred RGB through an OCIO config.
// This module is the only one that includes OpenColorIO (docs/color-management.md).
//
// Which config (resolveOcioConfig), highest priority first:
//   1. an explicit path (the CLI's --ocio-config),
//   2. $OCIO (the variable every OCIO application honours),
//   3. camsim's own config: $CAMSIM_LUTS/config.ocio if $CAMSIM_LUTS is set, else
//      CAMSIM_LUTS_DIR/config.ocio (the luts/ of the source tree).
// A missing or unparsable file throws InputError naming the file and where the path came from.
//
// The input colour space is camsim's ACEScg. With a config other than camsim's, OCIO needs to
// know which of its colour spaces that is: by default the colour space named (or aliased)
// "ACEScg", else the config's scene_linear role; OcioProcessor's second argument overrides it.
//
// A DisplayChoice is (display, view, looks); empty display = the config's default display,
// empty view = that display's default view, empty looks = none. `looks` is an OCIO look list
// ("a", "a, b", "+a, -b"): each name must be a look of the config. Unknown names throw
// InputError (key "display", "view" or "look") whose message lists the valid choices. A look on
// a data view (e.g. "Raw", which passes values through unchanged) throws InputError too.
//
// Output: packed float RGB in the display's encoding (e.g. sRGB-encoded, [0, 1] nominal; PQ
// code values in [0, 1] for Rec.2100-PQ). The caller quantises: quantizeDisplay8 / 16 clamp
// to [0, 1] and round; an 8-bit PNG written with writePng8 is tagged sRGB, which is only right
// for the sRGB display (tag or name other displays' files accordingly).
//
// Usage:
//   OcioProcessor ocio(args.ocioConfig);                 // "" → $OCIO → luts/config.ocio
//   DisplayPipeline pipe = ocio.pipeline({"sRGB", "ACES 1.0 - SDR Video", "camsim warm"});
//   std::vector<float> rgb = acescgPixels;               // width·height·3, rows top to bottom
//   pipe.applyInPlace(rgb, width, height);
//   writePng8(path, width, height, quantizeDisplay8(rgb));
//
// Thread safety: a loaded OcioProcessor and a built DisplayPipeline are immutable; their const
// members may be called from several threads (OCIO CPU processors are thread-safe).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "sensor/base/image.h"

namespace camsim {

enum class OcioConfigOrigin { Explicit, OcioEnvironment, Camsim };

struct OcioConfigLocation {
  std::filesystem::path path;
  OcioConfigOrigin origin = OcioConfigOrigin::Camsim;
};

// camsim's config: $CAMSIM_LUTS/config.ocio if $CAMSIM_LUTS is set and non-empty, else
// CAMSIM_LUTS_DIR/config.ocio. The file is not checked here.
std::filesystem::path camsimOcioConfigPath();

// explicit path (if non-empty) > $OCIO (if set and non-empty) > camsimOcioConfigPath().
OcioConfigLocation resolveOcioConfig(const std::filesystem::path& explicitPath = {});

// "explicit path", "$OCIO" or "camsim's luts/config.ocio" (for messages).
std::string describeOcioConfigOrigin(OcioConfigOrigin origin);

struct DisplayChoice {
  std::string display;  // "" = the config's default display
  std::string view;     // "" = the display's default view
  std::string looks;    // "" = no look; else an OCIO look list
};

class DisplayPipeline;

class OcioProcessor {
 public:
  // Loads the config chosen by resolveOcioConfig(explicitConfig). inputColorSpace: the config's
  // name for ACEScg; "" = "ACEScg" if the config has it, else its scene_linear role.
  // Throws InputError if the file is missing or invalid, or the input colour space is unknown.
  explicit OcioProcessor(const std::filesystem::path& explicitConfig = {},
                         const std::string& inputColorSpace = {});

  const OcioConfigLocation& location() const;
  const std::string& inputColorSpace() const;  // the resolved name

  std::vector<std::string> displays() const;  // active displays, in config order
  // The folders its search_path names (LUTs, looks), variables resolved, relative ones from
  // the config's working folder; in the config's order.
  std::vector<std::filesystem::path> searchFolders() const;
  std::string defaultDisplay() const;
  std::vector<std::string> views(const std::string& display) const;  // throws for unknown display
  std::string defaultView(const std::string& display) const;
  std::vector<std::string> looks() const;

  // Checks the names and fills in the defaults; throws InputError listing the valid names.
  DisplayChoice resolve(const DisplayChoice& choice) const;

  // resolve(choice), then builds the CPU processor ACEScg → (looks) → display/view.
  // Throws InputError if OCIO cannot build it (e.g. a user config's LUT file is missing).
  DisplayPipeline pipeline(const DisplayChoice& choice) const;

  // Convenience: an Image with channels R, G, B (ACEScg) → the same image display-encoded.
  Image toDisplay(const Image& acescg, const DisplayChoice& choice) const;

 private:
  struct Impl;  // holds the OCIO config; copies share it (it is immutable)
  std::shared_ptr<const Impl> impl_;
};

class DisplayPipeline {
 public:
  const DisplayChoice& choice() const { return choice_; }  // resolved names

  // rgb: width·height·3 floats, packed RGB; converted in place. CAMSIM_CHECKs the size.
  // A pixel whose largest |channel| exceeds kMaxInput is scaled down to it first, keeping
  // its ratios: OCIO's ACES output transforms overflow far above it (found by probing: 1e25
  // came out black between 1e20 and 1e35 white; 3e38 un-tone-mapped as inf).
  void applyInPlace(std::span<float> rgb, int width, int height) const;
  static constexpr float kMaxInput = 1e10f;
  std::array<float, 3> applyPixel(std::array<float, 3> rgb) const;

 private:
  friend class OcioProcessor;
  struct Impl;  // holds the OCIO CPU processor
  DisplayPipeline(DisplayChoice choice, std::shared_ptr<const Impl> impl);
  DisplayChoice choice_;
  std::shared_ptr<const Impl> impl_;
};

// Display-encoded floats → integer code values: clamp to [0, 1] (NaN → 0), round to nearest.
std::vector<std::uint8_t> quantizeDisplay8(std::span<const float> encoded);
std::vector<std::uint16_t> quantizeDisplay16(std::span<const float> encoded);

}  // namespace camsim
