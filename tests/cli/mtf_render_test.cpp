// `camsim mtf` on a render (issue 39): scenes/slanted_edge.yaml — a backlit edge tilted 5°,
// 1 m from a 6 mm f/2 thin lens focused at 2 m, on 3 µm photosites — rendered by the built
// binary, then measured. Its points blur into uniform discs of diameter
//   c = A·f·|s − s_f| / (s·(s_f − f)) = 3 mm · 6 mm · 1 m / (1 m · 1.994 m) = 9.03 µm = 3.01 px,
// and camsim's film integrates each photosite's area, so the expected MTF is
//   2J₁(πcf)/(πcf) · sinc(f cos 5°) · sinc(f sin 5°)   (tests/support/slanted_edge_image.h)
// within 0.02 to Nyquist. The same scene without its aperture (a pinhole) leaves a perfect
// edge: the photosite's sinc alone, times the sinc(f/4) of ISO's ¼-px bins, which the
// measurement leaves in and which a blurred edge hides (0.974 at Nyquist).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "tests/support/mtf_csv.h"
#include "tests/support/run_command.h"
#include "tests/support/slanted_edge_image.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace mtf_render_test {

namespace fs = std::filesystem;
using test::quote;
using test::RunResult;

// Renders `sceneText` as slanted_edge.yaml in `dir` and measures its luminance in the ROI
// through the edge; the MTF CSV.
test::MtfCsv renderAndMeasure(const fs::path& dir, const std::string& sceneText) {
  test::writeFile(dir / "slanted_edge.yaml", sceneText);
  RunResult r = test::runCamsim("render " + quote((dir / "slanted_edge.yaml").string()) +
                                    " --reproducible -o " + quote((dir / "render").string()),
                                dir);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  r = test::runCamsim("mtf " + quote((dir / "render" / "slanted_edge.exr").string()) +
                          " --roi 48,8,64,104 --channel Y --pitch-um 3 -o " +
                          quote((dir / "mtf").string()),
                      dir, "CAMSIM_PYTHON=/nonexistent/python3");
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("vertical edge at 5.00°"), std::string::npos) << r.out;
  return test::readMtfCsv(dir / "mtf" / "mtf.csv");
}

// The largest |MTF_Y − expected(f)| up to Nyquist.
template <typename Expected>
double worstError(const test::MtfCsv& csv, Expected expected) {
  EXPECT_EQ(csv.columns.back(), "mtf_Y");
  double worst = 0.0;
  for (const std::vector<double>& row : csv.rows)
    if (row[0] <= 0.5 + 1e-12) worst = std::max(worst, std::abs(row.back() - expected(row[0])));
  return worst;
}

std::string sceneText() {
  return test::readFile(fs::path(CAMSIM_SOURCE_DIR) / "scenes" / "slanted_edge.yaml");
}

TEST(MtfRender, DefocusedEdgeThroughTheThinLensIsTheDiscTimesThePhotosite) {
  test::TempDir dir;
  const test::MtfCsv csv = renderAndMeasure(dir.path(), sceneText());
  test::SyntheticEdge e;  // the reference: disc of c px, pixel-area-integrated, 5°
  e.blur = test::EdgeBlur::kDisc;
  e.size = 0.003 * 0.006 * 1.0 / (1.0 * (2.0 - 0.006)) / 3e-6;
  e.areaIntegrated = true;
  const double err = worstError(csv, [&](double f) { return test::expectedEdgeMtf(e, f); });
  std::printf("  rendered defocus disc (d = %.3f px): max |MTF error| to Nyquist %.4f\n", e.size,
              err);
  EXPECT_LT(err, 0.02);
}

TEST(MtfRender, PinholeEdgeIsThePhotositeAperture) {
  std::string text = sceneText();
  const size_t at = text.find("  aperture: {");
  ASSERT_NE(at, std::string::npos);
  text.erase(at, text.find('\n', at) - at);  // a pinhole: everything sharp
  test::TempDir dir;
  const test::MtfCsv csv = renderAndMeasure(dir.path(), text);
  test::SyntheticEdge e;  // a perfect step, pixel-area-integrated
  e.size = 0.0;
  e.areaIntegrated = true;
  const double err = worstError(csv, [&](double f) {
    return test::expectedEdgeMtf(e, f) * test::sincPi(f / 4.0);  // ISO's ¼-px bins
  });
  std::printf("  rendered pinhole edge: max |MTF error| to Nyquist %.4f\n", err);
  EXPECT_LT(err, 0.02);
}

}  // namespace mtf_render_test
}  // namespace camsim
