// Tests for `camsim bench` (cli/bench_command.cpp, integrator/measure/): the error metrics on known images, the slope
// fit on synthetic data, the CSV columns, argument parsing and the plan, and the reference
// cache (reused while the scene and its files are unchanged, invalidated when they change).
// No timing is asserted: the benchmark's numbers are measurements, not test outcomes.
#include "tests/support/env_guard.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "cli/args.h"
#include "cli/bench_command.h"
#include "integrator/measure/bench_metrics.h"
#include "integrator/measure/bench_reference.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/input_error.h"
#include "sensor/spectra/spectral_data.h"

namespace camsim {
namespace {

namespace fs = std::filesystem;

Image constantImage(int w, int h, float v) {
  Image image(w, h, {"Y"});
  for (float& p : image.pixels) p = v;
  return image;
}

// ---- metrics ---------------------------------------------------------------------------

TEST(BenchMetrics, IdenticalImagesHaveZeroError) {
  Image ref(4, 3, {"Y"});
  for (std::size_t i = 0; i < ref.pixels.size(); ++i) ref.pixels[i] = 0.1f * static_cast<float>(i);
  const ErrorMetrics e = compareImages(ref, ref, 0);
  EXPECT_EQ(e.rmse, 0.0);
  EXPECT_EQ(e.mrae, 0.0);
}

TEST(BenchMetrics, ConstantOffsetGivesTheClosedForm) {
  // r = 2 everywhere, x = r + 0.5: rMSE = 0.5² / (2² + (0.01·2)²), MRAE = 0.5 / (2 + 0.02).
  const ErrorMetrics e = compareImages(constantImage(5, 4, 2.5f), constantImage(5, 4, 2.0f), 0);
  EXPECT_NEAR(e.rmse, 0.25 / (4.0 + 0.0004), 1e-9);
  EXPECT_NEAR(e.mrae, 0.5 / 2.02, 1e-9);
}

TEST(BenchMetrics, RelativeErrorsDoNotDependOnTheFilmScale) {
  Image ref(3, 3, {"Y"}), x(3, 3, {"Y"});
  for (std::size_t i = 0; i < ref.pixels.size(); ++i) {
    ref.pixels[i] = 1.0f + static_cast<float>(i);
    x.pixels[i] = ref.pixels[i] * (i % 2 ? 1.1f : 0.95f);
  }
  const ErrorMetrics a = compareImages(x, ref, 0);
  for (float& p : ref.pixels) p *= 1e-9f;
  for (float& p : x.pixels) p *= 1e-9f;
  const ErrorMetrics b = compareImages(x, ref, 0);
  EXPECT_NEAR(b.rmse / a.rmse, 1.0, 1e-5);
  EXPECT_NEAR(b.mrae / a.mrae, 1.0, 1e-5);
}

TEST(BenchMetrics, BlackReferencePixelsAreBoundedByEpsilon) {
  // Half the pixels 0 in the reference: their error counts relative to ε = 1 % of the mean.
  Image ref(2, 1, {"Y"}), x(2, 1, {"Y"});
  ref.pixels = {0.0f, 2.0f};
  x.pixels = {0.01f, 2.0f};
  const double eps = 0.01 * 1.0;  // mean(ref) = 1
  EXPECT_NEAR(compareImages(x, ref, 0).rmse, 0.5 * (0.01 * 0.01) / (eps * eps), 1e-6);
  EXPECT_TRUE(std::isfinite(compareImages(x, ref, 0).mrae));
}

TEST(BenchMetrics, ReferenceNoiseIsTheErrorOfTheHalvesMean) {
  // a = r + d, b = r − d: (a − b)/2 = d against (a + b)/2 = r.
  const ErrorMetrics n = referenceNoise(constantImage(3, 3, 1.2f), constantImage(3, 3, 0.8f), 0);
  EXPECT_NEAR(n.rmse, 0.04 / (1.0 + 1e-4), 1e-6);
  EXPECT_NEAR(n.mrae, 0.2 / 1.01, 1e-6);
}

TEST(BenchMetrics, MismatchedImagesThrow) {
  EXPECT_THROW(compareImages(constantImage(2, 2, 1.0f), constantImage(3, 2, 1.0f), 0),
               std::invalid_argument);
  EXPECT_THROW(compareImages(constantImage(2, 2, 1.0f), constantImage(2, 2, 1.0f), 1),
               std::invalid_argument);
}

// ---- slope fit -------------------------------------------------------------------------

TEST(BenchSlope, PowerLawGivesItsExponent) {
  std::vector<double> t, e;
  for (int k = 0; k < 9; ++k) {
    t.push_back(0.01 * std::pow(2.0, k));
    e.push_back(3.0 * std::pow(t.back(), -0.5));
  }
  const SlopeFit fit = fitLogLogSlope(t, e);
  EXPECT_EQ(fit.points, 9);
  EXPECT_NEAR(fit.slope, -0.5, 1e-12);
  EXPECT_NEAR(fit.intercept, std::log10(3.0), 1e-12);
  EXPECT_NEAR(fit.r2, 1.0, 1e-12);
}

TEST(BenchSlope, NoisyPowerLawAndDegenerateInputs) {
  std::vector<double> t, e;
  for (int k = 0; k < 8; ++k) {
    t.push_back(std::pow(2.0, k));
    e.push_back(std::pow(t.back(), -1.0) * (k % 2 ? 1.1 : 0.9));  // ±10 % alternating
  }
  EXPECT_NEAR(fitLogLogSlope(t, e).slope, -1.0, 0.05);
  EXPECT_TRUE(std::isnan(fitLogLogSlope({1.0}, {1.0}).slope));
  EXPECT_TRUE(std::isnan(fitLogLogSlope({2.0, 2.0}, {1.0, 3.0}).slope));
  EXPECT_EQ(fitLogLogSlope({0.0, 1.0, -1.0}, {1.0, 0.0, 1.0}).points,
            0);  // non-positive values dropped
}

TEST(BenchSlope, RowsBelowTheReferenceFloorStayOutOfTheFit) {
  // rMSE = 1/spp against a floor of 2e-3: budgets with rMSE < 4 × 2e-3 (spp ≥ 128) are excluded.
  std::vector<BenchRow> rows;
  for (int spp = 1; spp <= 256; spp *= 2) {
    BenchRow r;
    r.scene = "s";
    r.sampler = "independent";
    r.spp = spp;
    r.seconds = 0.01 * spp;
    r.cpuSeconds = 0.02 * spp;
    r.floor.rmse = 2e-3;
    r.error.rmse = 1.0 / spp;
    rows.push_back(r);
  }
  std::vector<BenchRow*> ptrs;
  for (BenchRow& r : rows) ptrs.push_back(&r);
  const SamplerSlopes s = fitRows(ptrs);
  for (const BenchRow& r : rows) EXPECT_EQ(r.inFit, r.spp < 128) << r.spp;
  EXPECT_EQ(s.vsSpp.points, 7);
  EXPECT_NEAR(s.vsSpp.slope, -1.0, 1e-12);
  EXPECT_NEAR(s.vsSeconds.slope, s.vsSpp.slope, 1e-9);
  EXPECT_NEAR(s.vsCpuSeconds.slope, s.vsSpp.slope, 1e-9);
  EXPECT_EQ(s.scene, "s");
}

// ---- CSV -------------------------------------------------------------------------------

std::vector<std::string> splitLine(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream ss(line);
  for (std::string f; std::getline(ss, f, ',');) fields.push_back(f);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

TEST(BenchCsv, HasTheDocumentedColumns) {
  const std::vector<std::string> expected = {
      "scene",       "sampler",       "spp",          "width",    "height", "seconds",
      "cpu_seconds", "samples_per_s", "rays_per_s",   "rmse_rel", "mrae",   "ref_rmse_rel",
      "ref_mrae",    "in_fit",        "est_rmse_rel", "est_mrae"};
  EXPECT_EQ(benchCsvColumns(), expected);
  BenchRow r;
  r.scene = "cornell_box";
  r.sampler = "sobol";
  r.spp = 16;
  r.width = 128;
  r.height = 128;
  r.seconds = 2.0;
  r.samples = 1000;
  r.rays = 5000;
  r.error = {0.25, 0.5};
  r.estimate = {0.2, 0.4};
  r.inFit = true;
  std::istringstream csv(formatBenchCsv({r, r}));
  std::string header, line;
  std::getline(csv, header);
  EXPECT_EQ(splitLine(header), expected);
  int lines = 0;
  while (std::getline(csv, line)) {
    const auto f = splitLine(line);
    ASSERT_EQ(f.size(), expected.size()) << line;
    EXPECT_EQ(f[0], "cornell_box");
    EXPECT_EQ(f[2], "16");
    EXPECT_DOUBLE_EQ(std::stod(f[7]), 500.0);   // samples/s
    EXPECT_DOUBLE_EQ(std::stod(f[8]), 2500.0);  // rays/s
    EXPECT_DOUBLE_EQ(std::stod(f[9]), 0.25);
    EXPECT_EQ(f[13], "1");
    EXPECT_DOUBLE_EQ(std::stod(f[14]), 0.2);
    EXPECT_DOUBLE_EQ(std::stod(f[15]), 0.4);
    ++lines;
  }
  EXPECT_EQ(lines, 2);
}

// ---- arguments and plan ----------------------------------------------------------------

TEST(BenchArgs, DefaultsQuickAndOptions) {
  const BenchArgs d = parseBenchArgs({"bench"});
  EXPECT_FALSE(d.quick);
  EXPECT_EQ(d.outputDir, "bench-out");
  const BenchPlan p = planBench(d);
  EXPECT_EQ(p.budgets(), (std::vector<int>{1, 2, 4, 8, 16, 32, 64, 128, 256}));
  EXPECT_EQ(p.refSpp, 2048);
  EXPECT_GT(p.threads, 0);
  const BenchArgs a =
      parseBenchArgs({"bench", "--quick", "--out", "o", "--threads", "1", "--scenes",
                      "cornell_box,x/y.yaml", "--max-spp", "48", "--mesh-triangles", "0"});
  EXPECT_TRUE(a.quick);
  EXPECT_EQ(a.outputDir, "o");
  EXPECT_EQ(a.scenes, (std::vector<std::string>{"cornell_box", "x/y.yaml"}));
  const BenchPlan q = planBench(a);
  EXPECT_EQ(q.budgets(), (std::vector<int>{1, 2, 4, 8, 16, 32, 48}));
  EXPECT_EQ(q.threads, 1);
  EXPECT_EQ(q.meshTriangles, 0u);
  EXPECT_EQ(q.longSide, 64);
  EXPECT_EQ(q.featureLongSide, 64);
  EXPECT_EQ(planBench(parseBenchArgs({"bench"})).featureLongSide, 512);
  EXPECT_EQ(planBench(parseBenchArgs({"bench", "--feature-resolution", "100"})).featureLongSide,
            100);
  EXPECT_EQ(reducedResolution({512, 512}, 512), glm::ivec2(512, 512));
  EXPECT_EQ(reducedResolution({480, 270}, 128), glm::ivec2(128, 72));
  EXPECT_EQ(reducedResolution({320, 213}, 64), glm::ivec2(64, 43));
  EXPECT_EQ(benchScenePath("x/y.yaml"), fs::path("x/y.yaml"));
  EXPECT_EQ(benchScenePath("cornell_box").filename(), "cornell_box.yaml");
  EXPECT_TRUE(parseBenchArgs({"bench", "--help"}).help);
}

TEST(BenchArgs, BadUsageIsAUsageError) {
  EXPECT_THROW(parseBenchArgs({"bench", "--max-spp", "0"}), UsageError);
  EXPECT_THROW(parseBenchArgs({"bench", "--max-spp"}), UsageError);
  EXPECT_THROW(parseBenchArgs({"bench", "--scenes", "a,,b"}), UsageError);
  EXPECT_THROW(parseBenchArgs({"bench", "--threads", "x"}), UsageError);
  EXPECT_THROW(parseBenchArgs({"bench", "--frobnicate"}), UsageError);
  EXPECT_THROW(parseBenchArgs({"bench", "--out", ""}), UsageError);
  EXPECT_THROW(parseBenchArgs({"bench", "--cache", ""}), UsageError);
  EXPECT_THROW(parseBenchArgs({"bench", "stray"}), UsageError);
  // A --peer-* option without --peer (the default bench ran, silently).
  for (const char* option : {"--peer-only", "--peer-scenes=cornell_box", "--peer-rounds=2"})
    EXPECT_THROW(parseBenchArgs({"bench", option}), UsageError) << option;
  EXPECT_NO_THROW(parseBenchArgs({"bench", "--peer", "cycles", "--peer-only"}));
  try {
    (void)parseBenchArgs({"bench", "--frobnicate"});
  } catch (const UsageError& e) {
    EXPECT_EQ(std::string(e.what()), "unknown option '--frobnicate' (try 'camsim bench --help')");
  }
}

// Every integer option's range, at both ends: its bound accepted, one beyond it refused
// naming the option and the range; --help (from the same option table) states the range.
TEST(BenchArgs, EveryRangeIsCheckedAndStatedInHelp) {
  struct Range {
    const char* flag;
    std::int64_t lo, hi;
  };
  const std::string help = benchUsageText();
  for (const Range& r :
       {Range{"--threads", 1, 1024}, Range{"--max-spp", 1, 65536}, Range{"--resolution", 4, 8192},
        Range{"--feature-resolution", 4, 8192}, Range{"--ref-spp", 2, 1 << 20},
        Range{"--mesh-triangles", 0, 100000000}, Range{"--texture-size", 0, 16384}}) {
    const std::string range = "[" + std::to_string(r.lo) + ", " + std::to_string(r.hi) + "]";
    EXPECT_NE(help.find(r.flag), std::string::npos) << r.flag;
    EXPECT_NE(help.find(range), std::string::npos) << r.flag << " " << range;
    for (const std::int64_t ok : {r.lo, r.hi})
      EXPECT_NO_THROW(parseBenchArgs({"bench", r.flag, std::to_string(ok)})) << r.flag << ok;
    for (const std::int64_t bad : {r.lo - 1, r.hi + 1}) {
      try {
        (void)parseBenchArgs({"bench", r.flag, std::to_string(bad)});
        ADD_FAILURE() << r.flag << " accepted " << bad;
      } catch (const UsageError& e) {
        EXPECT_EQ(std::string(e.what()),
                  std::string(r.flag) + " must be in " + range + ", got " + std::to_string(bad));
      }
    }
  }
  const BenchArgs b = parseBenchArgs({"bench", "--ref-spp", "6", "--resolution", "32",
                                      "--texture-size", "0", "-o", "d", "--cache", "c"});
  EXPECT_EQ(b.refSpp, 6);
  EXPECT_EQ(b.resolution, 32);
  EXPECT_EQ(b.textureSize, 0);
  EXPECT_EQ(b.outputDir, "d");
  EXPECT_EQ(b.cacheDir, "c");
  for (const char* option : {"--quick", "--out", "--scenes", "--cache", "--help"})
    EXPECT_NE(help.find(option), std::string::npos) << option;
  EXPECT_NE(help.find("Usage: camsim bench"), std::string::npos) << help;
  EXPECT_NE(help.find("Speed against error"), std::string::npos) << help;
}

// ---- scratch directory --------------------------------------------------------------

TEST(BenchScratchDirectory, IsCreatedAndRemovedWithItsContents) {
  test::TempDir dir;
  fs::path made;
  {
    const BenchScratchDirectory scratch(dir.path());
    made = scratch.path();
    EXPECT_EQ(made.parent_path(), dir.path());
    ASSERT_TRUE(fs::is_directory(made));
    test::writeFile(made / "torus.ply", "x");
  }
  EXPECT_FALSE(fs::exists(made));
}

// A base that is a file (or a missing $TMPDIR): an InputError naming it (exit 2), not a
// filesystem_error (which main would report as an internal error, exit 1).
TEST(BenchScratchDirectory, AnUnusableBaseIsAnInputError) {
  test::TempDir dir;
  test::writeFile(dir.path() / "file", "x");
  try {
    const BenchScratchDirectory scratch(dir.path() / "file");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(e.where().file.find("camsim-bench-"), std::string::npos) << e.what();
    EXPECT_NE(e.message().find("cannot create"), std::string::npos) << e.what();
  }
}

// With no base given, the scratch directory goes under std::filesystem::temp_directory_path;
// an unusable $TMPDIR is an InputError naming the variable and its value.
TEST(BenchScratchDirectory, AnUnusableTmpdirIsAnInputErrorNamingIt) {
  test::TempDir dir;
  test::writeFile(dir.path() / "file", "x");
  const test::EnvGuard tmpdir("TMPDIR");  // restored however the test ends
  const std::string bad = (dir.path() / "file").string();
  tmpdir.set(bad);
  try {
    const BenchScratchDirectory scratch;
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "TMPDIR=" + bad) << e.what();
  }
  tmpdir.set(dir.path().string());  // a usable one: used
  const BenchScratchDirectory scratch;
  EXPECT_EQ(scratch.path().parent_path(), dir.path());
}

// ---- reference cache -------------------------------------------------------------------

const char* kTinyScene =
    "format: camsim-scene/1\nname: tiny\nrender: {spp: 4, max_depth: 2}\n"
    "camera: {position: [0, 0, -2], look_at: [0, 0, 0], up: [0, 1, 0], resolution: [8, 6]}\n"
    "materials: {grey: {type: diffuse, reflectance: REFL}}\n"
    "shapes:\n  - {name: tri, type: mesh, file: tri.obj, material: grey}\n"
    "  - {name: lamp, type: sphere, centre: [0, 2, -1], radius: 0.3, emission: {luminance: "
    "1000}}\n";

// The tiny scene with its grey material's reflectance set (a YAML value).
std::string tinyScene(const std::string& reflectance) {
  std::string text = kTinyScene;
  text.replace(text.find("REFL"), 4, reflectance);
  return text;
}

// The reference request for scene `text` in dir (loaded once, for the files it reads).
ReferenceRequest requestFor(const fs::path& dir, const std::string& text) {
  ReferenceRequest r;
  r.name = "tiny";
  r.sceneText = text;
  const SceneDescription d = loadSceneFromText(text, (dir / "tiny.yaml").string(), dir);
  r.inputFiles = d.inputFiles;
  r.resolution = d.camera.resolution;
  r.sceneFile = (dir / "tiny.yaml").string();
  r.spp = 4;
  r.threads = 1;
  return r;
}

ReferenceRequest tinyRequest(const fs::path& dir, const std::string& reflectance) {
  return requestFor(dir, tinyScene(reflectance));
}

// obtainReference with the request's scene built from its text.
Reference obtainTiny(const ReferenceRequest& r, const fs::path& cacheDir, std::ostream& log) {
  const Scene scene(
      loadSceneFromText(r.sceneText, r.sceneFile, fs::path(r.sceneFile).parent_path()));
  return obtainReference(r, scene, cacheDir, log);
}

TEST(BenchReference, CachedUntilTheSceneOrItsFilesChange) {
  test::TempDir dir;
  test::writeFile(dir.path() / "tri.obj", "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n");
  const fs::path cache = dir.path() / "cache";
  std::ostringstream log;
  const ReferenceRequest req = tinyRequest(dir.path(), "0.5");
  const Reference first = obtainTiny(req, cache, log);
  EXPECT_FALSE(first.fromCache);
  EXPECT_TRUE(fs::is_regular_file(first.file));
  EXPECT_EQ(first.file.filename().string().rfind("tiny-", 0), 0u);
  EXPECT_EQ(first.image.width, 8);
  EXPECT_EQ(first.image.height, 6);

  const Reference again = obtainTiny(req, cache, log);  // unchanged: reused
  EXPECT_TRUE(again.fromCache);
  EXPECT_EQ(again.file, first.file);
  EXPECT_EQ(again.image.pixels, first.image.pixels);
  EXPECT_DOUBLE_EQ(again.noise.rmse, first.noise.rmse);

  const Reference edited =
      obtainTiny(tinyRequest(dir.path(), "0.6"), cache, log);  // scene text changed
  EXPECT_FALSE(edited.fromCache);
  EXPECT_NE(edited.file, first.file);

  ReferenceRequest moreSpp = req;  // reference settings are part of the key
  moreSpp.spp = 8;
  EXPECT_NE(referenceKey(moreSpp), referenceKey(req));

  // A referenced file's content changes (same size): a new reference.
  const std::string keyBefore = referenceKey(req);
  test::writeFile(dir.path() / "tri.obj", "v -1 -1 0\nv 1 -1 0\nv 0 2 0\nf 1 2 3\n");
  const ReferenceRequest meshEdited = tinyRequest(dir.path(), "0.5");
  EXPECT_NE(referenceKey(meshEdited), keyBefore);
  EXPECT_FALSE(obtainTiny(meshEdited, cache, log).fromCache);
  EXPECT_TRUE(obtainTiny(meshEdited, cache, log).fromCache);
}

TEST(BenchReference, ADamagedCacheFileIsRenderedAgain) {
  test::TempDir dir;
  test::writeFile(dir.path() / "tri.obj", "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n");
  std::ostringstream log;
  const ReferenceRequest req = tinyRequest(dir.path(), "0.5");
  const Reference first = obtainTiny(req, dir.path(), log);
  test::writeFile(first.file, "not an exr");
  const Reference again = obtainTiny(req, dir.path(), log);
  EXPECT_FALSE(again.fromCache);
  EXPECT_TRUE(obtainTiny(req, dir.path(), log).fromCache);
}

// The key covers the files the loader read, wherever it found them: a table found through
// the scene's spectra_path (which a scan of the scene text for file names would miss, as
// the bench's key once did) changes the key when it changes.
TEST(BenchReference, TheKeyFollowsATableFoundOnTheSpectraPath) {
  test::TempDir dir;
  test::writeFile(dir.path() / "tri.obj", "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n");
  fs::create_directories(dir.path() / "tables");
  test::writeFile(dir.path() / "tables" / "grey.csv", "wavelength_nm,r\n360,0.5\n830,0.5\n");
  std::string text = tinyScene("{csv: grey.csv}");
  text.insert(text.find("render:"), "spectra_path: [tables]\n");
  const auto request = [&] { return requestFor(dir.path(), text); };
  const ReferenceRequest before = request();
  ASSERT_EQ(before.inputFiles.size(), 2u);
  EXPECT_EQ(before.inputFiles[0].filename(), "grey.csv");  // materials are read first
  EXPECT_EQ(before.inputFiles[1].filename(), "tri.obj");
  const std::string keyBefore = referenceKey(before);
  EXPECT_EQ(referenceKey(request()), keyBefore);
  test::writeFile(dir.path() / "tables" / "grey.csv", "wavelength_nm,r\n360,0.6\n830,0.6\n");
  EXPECT_NE(referenceKey(request()), keyBefore);
}

// The tables built into camsim reach no inputFiles list (scenes name illuminants, and Y
// is the CIE observer's), so the key covers their text itself.
TEST(BenchReference, TheKeyCoversTheBuiltInTables) {
  test::TempDir dir;
  test::writeFile(dir.path() / "tri.obj", "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n");
  const std::string text = referenceKeyText(tinyRequest(dir.path(), "0.5"));
  EXPECT_NE(text.find(embeddedSpectralFile("cie1931_2deg_xyz.csv")), std::string::npos);
  for (const std::string& name : cieIlluminantNames()) {
    const std::string_view table = embeddedSpectralFile("illuminants/illuminant_" + name + ".csv");
    ASSERT_FALSE(table.empty()) << name;
    EXPECT_NE(text.find(table), std::string::npos) << name;
  }
  const auto embedded = embeddedSpectralFileNames();  // the observer and every illuminant
  EXPECT_EQ(embedded.size(), 1 + cieIlluminantNames().size());
}

}  // namespace
}  // namespace camsim
