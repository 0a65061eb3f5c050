#include "sensor/measure/mtf_measurement.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <glm/mat3x3.hpp>

#include "sensor/base/format.h"
#include "sensor/base/input_error.h"
#include "sensor/io/exr_io.h"
#include "sensor/io/json_writer.h"
#include "sensor/io/png_io.h"
#include "sensor/spectra/color_space.h"

namespace camsim {

std::array<double, 3> luminanceWeights(Chromaticity red, Chromaticity green, Chromaticity blue,
                                       Chromaticity white) {
  // Columns: each primary's XYZ at Y = 1; the scales S solve P·S = XYZ(white, Y = 1), and
  // the Y row of xyzFromRgb = P·diag(S) is S itself.
  const glm::dmat3 p(chromaticityToXyz(red), chromaticityToXyz(green), chromaticityToXyz(blue));
  const glm::dvec3 s = glm::inverse(p) * chromaticityToXyz(white);
  return {s.x, s.y, s.z};
}

std::array<double, 3> rec709LuminanceWeights() {
  return luminanceWeights({0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}, {0.3127, 0.3290});
}

namespace {

std::vector<std::string> splitNames(const std::string& selection) {
  std::vector<std::string> names;
  std::stringstream in(selection);
  for (std::string item; std::getline(in, item, ',');) names.push_back(item);
  if (!selection.empty() && selection.back() == ',') names.emplace_back();
  return names;
}

void addChannel(Image& out, const std::string& name, const std::vector<float>& values) {
  if (out.channelIndex(name) >= 0) return;
  Image next(out.width, out.height, out.channels);
  next.channels.push_back(name);
  next.pixels.resize(static_cast<size_t>(out.width) * static_cast<size_t>(out.height) *
                     next.channels.size());
  const size_t n = out.channels.size();
  for (size_t p = 0; p < values.size(); ++p) {
    for (size_t c = 0; c < n; ++c) next.pixels[p * (n + 1) + c] = out.pixels[p * n + c];
    next.pixels[p * (n + 1) + n] = values[p];
  }
  out = std::move(next);
}

std::vector<float> channelValues(const Image& image, int c) {
  return image.channel(c).pixels;
}

}  // namespace

Image selectMtfChannels(const Image& image, const std::string& selection,
                        const std::array<double, 3>& yWeights, const std::string& source) {
  const int r = image.channelIndex("R"), g = image.channelIndex("G"), b = image.channelIndex("B");
  const bool rgb = r >= 0 && g >= 0 && b >= 0;
  std::vector<std::string> names;
  for (const std::string& name : splitNames(selection)) {
    if (name == "all" && rgb)
      names.insert(names.end(), {"R", "G", "B", "Y"});
    else if (name == "all" && image.channelCount() == 1)
      names.emplace_back("Y");
    else
      names.push_back(name);
  }
  if (names.empty()) names.emplace_back("");
  Image out(image.width, image.height, {});
  for (const std::string& name : names) {
    if (const int c = image.channelIndex(name); c >= 0) {
      addChannel(out, name, channelValues(image, c));
    } else if (name == "Y" && rgb) {
      std::vector<float> y(static_cast<size_t>(image.width) * static_cast<size_t>(image.height));
      for (int py = 0; py < image.height; ++py)
        for (int px = 0; px < image.width; ++px)
          y[static_cast<size_t>(py) * static_cast<size_t>(image.width) + static_cast<size_t>(px)] =
              static_cast<float>(yWeights[0] * static_cast<double>(image.at(px, py, r)) +
                                 yWeights[1] * static_cast<double>(image.at(px, py, g)) +
                                 yWeights[2] * static_cast<double>(image.at(px, py, b)));
      addChannel(out, "Y", y);
    } else if (name == "Y" && image.channelCount() == 1) {
      addChannel(out, "Y", channelValues(image, 0));
    } else {
      std::string have;
      for (const std::string& n : image.channels) have += (have.empty() ? "" : ", ") + n;
      throw InputError(
          {source, 0, 0}, "channel",
          "no channel '" + name + "' (R, G, B, Y, all or one of the image's: " + have + ")");
    }
  }
  return out;
}

namespace {

MtfImage fromPng(const std::filesystem::path& path, bool linear) {
  const PngImage png = readPng(path);
  MtfImage out;
  out.format = "png";
  out.encoding = linear ? "linear" : "sRGB decoded";
  out.yWeights = rec709LuminanceWeights();
  const bool grey = png.channels <= 2;
  out.image =
      grey ? Image(png.width, png.height, {"Y"}) : Image(png.width, png.height, {"R", "G", "B"});
  const double scale = 1.0 / ((1 << png.bitDepth) - 1);
  const int kept = out.image.channelCount();
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x)
      for (int c = 0; c < kept; ++c) {
        const size_t i =
            (static_cast<size_t>(y) * static_cast<size_t>(png.width) + static_cast<size_t>(x)) *
                static_cast<size_t>(png.channels) +
            static_cast<size_t>(c);
        const double v = png.samples[i] * scale;
        out.image.at(x, y, c) = static_cast<float>(linear ? v : srgbDecode(v));
      }
  return out;
}

}  // namespace

MtfImage readMtfImage(const std::filesystem::path& path, bool pngIsLinear) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({path.string(), 0, 0}, "", "cannot open the image");
  unsigned char magic[8] = {};
  in.read(reinterpret_cast<char*>(magic), sizeof magic);
  const bool exr = in.gcount() >= 4 && magic[0] == 0x76 && magic[1] == 0x2f && magic[2] == 0x31 &&
                   magic[3] == 0x01;
  const bool png =
      in.gcount() == 8 && magic[0] == 0x89 && magic[1] == 'P' && magic[2] == 'N' && magic[3] == 'G';
  if (png) return fromPng(path, pngIsLinear);
  if (!exr) throw InputError({path.string(), 0, 0}, "", "not an OpenEXR or PNG file");
  ExrFile file = readExr(path);
  MtfImage out;
  out.format = "exr";
  out.encoding = "linear";
  out.image = std::move(file.image);
  out.yWeights = file.chromaticities
                     ? luminanceWeights(file.chromaticities->red, file.chromaticities->green,
                                        file.chromaticities->blue, file.chromaticities->white)
                     : rec709LuminanceWeights();
  return out;
}

const MtfChannel& MtfMeasurement::reference() const {
  CAMSIM_CHECK(!channels.empty());
  for (const char* name : {"Y", "G"})
    for (const MtfChannel& c : channels)
      if (c.name == name) return c;
  return channels.front();
}

MtfMeasurement measureMtf(const Image& image, const EdgeRoi& roi, const SfrOptions& options) {
  MtfMeasurement m;
  m.source = options.source;
  m.roi = roi;
  m.options = options;
  m.imageWidth = image.width;
  m.imageHeight = image.height;
  for (int c = 0; c < image.channelCount(); ++c) {
    SfrOptions o = options;
    o.source = options.source + " (channel " + image.channels[static_cast<size_t>(c)] + ")";
    m.channels.push_back(
        {image.channels[static_cast<size_t>(c)], measureSfr(image.channel(c), roi, o)});
  }
  return m;
}

double MtfMeasurement::fieldHeightPx() const {
  const double dx = roi.x + 0.5 * roi.width - 0.5 * imageWidth;
  const double dy = roi.y + 0.5 * roi.height - 0.5 * imageHeight;
  return std::hypot(dx, dy);
}

double MtfMeasurement::relativeFieldHeight() const {
  const double halfDiagonal = 0.5 * std::hypot(imageWidth, imageHeight);
  return halfDiagonal > 0.0 ? fieldHeightPx() / halfDiagonal : 0.0;
}

std::string formatMtfCsv(const MtfMeasurement& m) {
  std::ostringstream out;
  const bool mm = m.options.pixelPitchM > 0.0;
  out << "frequency_cy_px" << (mm ? ",frequency_cy_mm" : "");
  for (const MtfChannel& c : m.channels) out << ",mtf_" << c.name;
  out << "\n";
  if (m.channels.empty()) return out.str();
  const SfrResult& first = m.channels.front().sfr;
  const std::vector<double> perMm = first.frequencyPerMm(m.options.pixelPitchM);
  for (size_t k = 0; k < first.frequency.size(); ++k) {
    out << formatNumber(first.frequency[k], 8);
    if (mm) out << "," << formatNumber(perMm[k], 8);
    for (const MtfChannel& c : m.channels) out << "," << formatNumber(c.sfr.mtf[k], 6);
    out << "\n";
  }
  return out.str();
}

namespace {

std::string optionalNumber(const std::optional<double>& v, double scale = 1.0) {
  return v ? formatNumber(*v * scale, 6) : "null";
}

}  // namespace

std::string formatMtfJson(const MtfMeasurement& m) {
  const double pitchMm = m.options.pixelPitchM * 1e3;
  const bool mm = pitchMm > 0.0;
  JsonObject roi, units, root;
  roi.set("x", static_cast<double>(m.roi.x)).set("y", static_cast<double>(m.roi.y));
  roi.set("width", static_cast<double>(m.roi.width))
      .set("height", static_cast<double>(m.roi.height));
  units.set("frequency", "cycles/pixel along the edge normal (Nyquist 0.5)")
      .set("frequency_mm", "cycles/mm (cycles/pixel / pixel pitch)")
      .set("angle", "degrees from the image axis the edge runs along")
      .set("position", "pixels, image coordinates (x right, y down, pixel i spans [i, i+1])")
      .set("mtf",
           "normalised to 1 at zero frequency; includes everything in the image, "
           "pixel aperture too");
  const MtfChannel& ref = m.reference();
  const MtfChannel* green = nullptr;
  for (const MtfChannel& c : m.channels)
    if (c.name == "G") green = &c;
  std::vector<JsonObject> channels;
  for (const MtfChannel& c : m.channels) {
    const SfrResult& s = c.sfr;
    JsonObject j;
    j.set("name", c.name).setJson("mtf50_cy_px", optionalNumber(s.mtf50));
    if (mm) j.setJson("mtf50_cy_mm", optionalNumber(s.mtf50, 1.0 / pitchMm));
    j.set("mtf_at_nyquist", s.mtfAtNyquist)
        .set("angle_deg", s.angleDeg)
        .set("slope", s.slope)
        .set("edge_x_px", s.edgeX)
        .set("edge_y_px", s.edgeY);
    if (green)
      j.set("misregistration_px",
            s.vertical ? s.edgeX - green->sfr.edgeX : s.edgeY - green->sfr.edgeY);
    j.set("edge_fit", s.fit)
        .set("rows_used", static_cast<double>(s.rowsUsed))
        .set("empty_bins", static_cast<double>(s.emptyBins))
        .set("bin_offset_rms_px", s.binOffsetRmsPx)
        .set("phases_per_pixel", s.phasesPerPixel)
        .set("contrast", s.contrast)
        .set("warnings", s.warnings);
    channels.push_back(j);
  }
  root.set("format", "camsim-mtf").set("version", 1.0).set("source", m.source);
  root.set("method",
           "ISO 12233:2017 e-SFR (slanted edge) as Burns' sfrmat4: per-row centroid "
           "of the Hamming-windowed derivative, polynomial edge fit, 4x "
           "oversampled ESF, central-difference LSF with its correction, Hamming "
           "window, DFT normalised at DC");
  JsonObject field;
  field.set("image_width_px", static_cast<double>(m.imageWidth))
      .set("image_height_px", static_cast<double>(m.imageHeight))
      .set("relative_height", m.relativeFieldHeight())
      .set("height_px", m.fieldHeightPx());
  if (mm) field.set("height_mm", m.fieldHeightPx() * pitchMm);
  units.set("field",
            "the ROI centre's distance from the image centre; relative: over the "
            "half diagonal (0 centre, 1 corner)");
  root.set("roi", roi).set("field", field).set("units", units);
  root.set("edge_orientation", ref.sfr.vertical ? "vertical" : "horizontal")
      .set("edge_angle_deg", ref.sfr.angleDeg)
      .set("fit_order", static_cast<double>(m.options.fitOrder))
      .set("oversampling", static_cast<double>(kSfrOversampling));
  if (mm) root.set("pixel_pitch_um", pitchMm * 1e3).set("nyquist_cy_mm", kNyquist / pitchMm);
  root.set("channels", channels);
  return root.str() + "\n";
}

std::string formatMtfSummary(const MtfMeasurement& m) {
  std::ostringstream out;
  const double pitchMm = m.options.pixelPitchM * 1e3;
  const MtfChannel& ref = m.reference();
  out << "e-SFR (ISO 12233:2017) of " << m.source << ", ROI " << m.roi.x << "," << m.roi.y << ","
      << m.roi.width << "," << m.roi.height << ": "
      << (ref.sfr.vertical ? "vertical" : "horizontal") << " edge at "
      << formatFixed(ref.sfr.angleDeg, 2) << "°, " << ref.sfr.rowsUsed
      << (ref.sfr.vertical ? " rows" : " columns") << " along it; field height "
      << formatFixed(m.relativeFieldHeight(), 2);
  if (pitchMm > 0.0) out << " (" << formatNumber(m.fieldHeightPx() * pitchMm, 3) << " mm)";
  out << "\n";
  for (const MtfChannel& c : m.channels) {
    out << "  " << c.name << std::string(c.name.size() < 6 ? 6 - c.name.size() : 1, ' ') << "MTF50 "
        << (c.sfr.mtf50 ? formatFixed(*c.sfr.mtf50, 4) + " cy/px" : std::string("> 1 cy/px"));
    if (pitchMm > 0.0 && c.sfr.mtf50)
      out << " (" << formatFixed(*c.sfr.mtf50 / pitchMm, 1) << " cy/mm)";
    out << ", MTF at Nyquist " << formatFixed(c.sfr.mtfAtNyquist, 3) << "\n";
    for (const std::string& w : c.sfr.warnings) out << "    warning: " << w << "\n";
  }
  return out.str();
}

std::string formatMtfFieldsCsv(const std::vector<MtfMeasurement>& regions) {
  std::ostringstream out;
  out << "region,roi_x,roi_y,roi_width,roi_height,relative_field_height,field_height_px,"
         "field_height_mm,channel,mtf50_cy_px,mtf50_cy_mm,mtf_at_nyquist\n";
  for (size_t r = 0; r < regions.size(); ++r) {
    const MtfMeasurement& m = regions[r];
    const double pitchMm = m.options.pixelPitchM * 1e3;
    const auto orEmpty = [](bool has, double v) { return has ? formatNumber(v, 6) : ""; };
    for (const MtfChannel& c : m.channels) {
      out << r + 1 << "," << m.roi.x << "," << m.roi.y << "," << m.roi.width << "," << m.roi.height
          << "," << formatNumber(m.relativeFieldHeight(), 6) << ","
          << formatNumber(m.fieldHeightPx(), 6) << ","
          << orEmpty(pitchMm > 0.0, m.fieldHeightPx() * pitchMm) << "," << c.name << ","
          << orEmpty(c.sfr.mtf50.has_value(), c.sfr.mtf50.value_or(0.0)) << ","
          << orEmpty(c.sfr.mtf50.has_value() && pitchMm > 0.0,
                     c.sfr.mtf50.value_or(0.0) / (pitchMm > 0.0 ? pitchMm : 1.0))
          << "," << formatNumber(c.sfr.mtfAtNyquist, 6) << "\n";
    }
  }
  return out.str();
}

}  // namespace camsim
