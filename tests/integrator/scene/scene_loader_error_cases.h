// The scene loader's malformed-scene cases: each a scene text and where the loader must
// report the error (loaded as "test.yaml" with a temporary directory as its base). Read by
// scene_loader_test.cpp (SceneLoaderErrorTest) and, through scene_error_cases_main.cpp, by
// the Python module's tests (python/tests/test_errors.py): one list for both front ends.
#pragma once

#include <ostream>
#include <string>

namespace camsim::test {

// Lines 1–6 of most test scenes; the shapes follow from line 7.
inline const std::string kCamera =
    "camera:\n"                 // 1
    "  position: [0, 0, -1]\n"  // 2
    "  look_at: [0, 0, 0]\n";   // 3
inline const std::string kMaterials =
    "materials:\n"             // 4
    "  m: {type: diffuse}\n";  // 5
inline const std::string kPrefix = kCamera + kMaterials + "shapes:\n";
// Line 7: the value of radius is at column 47, that of material at column 60.
inline const std::string kSphere =
    "  - {type: sphere, centre: [0, 0, 0], radius: 1, material: m}\n";

inline std::string withShapes(const std::string& shapes) {
  return kPrefix + shapes;
}
// One extra camera line (line 4); the sphere is then on line 8.
inline std::string withCameraLine(const std::string& line) {
  return kCamera + line + kMaterials + "shapes:\n" + kSphere;
}
inline std::string sphereWith(const std::string& radius, const std::string& rest) {
  return withShapes("  - {type: sphere, centre: [0, 0, 0], radius: " + radius + rest + "}\n");
}
inline std::string meshWith(const std::string& vertices, const std::string& faces) {
  return withShapes("  - type: mesh\n    material: m\n    vertices: " + vertices +  // 7, 8, 9
                    "\n    faces: " + faces + "\n");                                // 10
}

struct ErrorCase {
  const char* name;
  std::string text;
  int line;
  int column;
  std::string key;
  std::string message;  // a part of the message
};

inline const ErrorCase kErrorCases[] = {
    {"SyntaxUnclosedBracket",
     withShapes("  - type: sphere\n    centre: [0, 0, 0\n    radius: 1\n    material: m\n"), 8, 13,
     "", "'[' is never closed"},
    {"SyntaxUnclosedBracketAtEnd", kCamera + kMaterials + "shapes: [\n", 6, 9, "", "never closed"},
    {"SyntaxUnclosedQuote", "name: \"box\n" + kPrefix + kSphere, 1, 7, "", "never closed"},
    {"SyntaxBadIndentation", kCamera + " up: [0, 1, 0]\n" + kMaterials + "shapes:\n" + kSphere, 4,
     2, "", "YAML syntax error"},
    {"UnknownTopLevelKey", withShapes(kSphere) + "lamps: []\n", 8, 1, "lamps", "unknown key"},
    // The name is the output files' stem: a NUL or a newline in it, or 235 bytes (its temporary
    // file's name then passed 255 bytes), failed when writing (exit 1; found by probing).
    {"NameWithAControlCharacter", "name: \"a\\nb\"\n" + kPrefix + kSphere, 1, 7, "name",
     "control characters"},
    {"NameTooLong", "name: " + std::string(235, 'a') + "\n" + kPrefix + kSphere, 1, 7, "name",
     "name is 235 bytes long; at most 128"},
    {"NameDotDot", "name: ..\n" + kPrefix + kSphere, 1, 7, "name",
     "non-empty file name: not '.' or '..'"},
    {"NameWithABackslash", "name: 'a\\b'\n" + kPrefix + kSphere, 1, 7, "name",
     "without '/' or '\\'"},
    // Two offsets that print alike named the same files: the second frame's rename failed
    // after the first's files were in place (exit 1, a half-written folder).
    {"BracketOffsetsNamingTheSameFiles",
     withShapes(kSphere) + "sensor: {model: smartphone-1.4um, bracket_ev: [0.1, 0.10000000001]}\n",
     8, 47, "sensor.bracket_ev", "name the same files (NAME_ev+0.1.dng"},
    // An ISO outside a calibrated sensor's iso_table: found when the sensor model was built,
    // with no file or line.
    {"SensorIsoOutsideItsCalibration",
     withShapes(kSphere) + "sensor: {model: eld-canon-5d4, iso: 50}\n", 8, 37, "sensor.iso",
     "ISO 50 is outside the range the sensor 'eld-canon-5d4' was calibrated at"},
    // 0 and -0 are one exposure; printed apart (_ev+0, _ev-0) they rendered it twice.
    {"BracketOffsetsZeroAndNegativeZero",
     withShapes(kSphere) + "sensor: {model: smartphone-1.4um, bracket_ev: [0, -0]}\n", 8, 47,
     "sensor.bracket_ev", "name the same files (NAME_ev+0.dng"},
    {"MisspeltShapeKey",
     withShapes(kSphere +
                "  - type: sphere\n    centre: [0, 0, 0]\n    radus: 1\n    material: m\n"),
     10, 5, "shapes[1].radus", "did you mean 'radius'"},
    {"UnknownShapeKey", sphereWith("1", ", material: m, colour: red"), 7, 63, "shapes[0].colour",
     "unknown key"},
    {"UnknownCameraKey", withCameraLine("  fov: 40\n"), 4, 3, "camera.fov", "unknown key"},
    {"WorldFromCameraProperRotationMirrors",
     "camera:\n  world_from_camera: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]\n" +
         kMaterials + "shapes:\n" + kSphere,
     2, 22, "camera.world_from_camera", "determinant +1"},
    {"ProjectionUnknownModel", withCameraLine("  projection: {model: fisheye}\n"), 4, 23,
     "camera.projection.model", "unknown projection model 'fisheye' (known: opencv,"},
    {"ProjectionSomeIntrinsics", withCameraLine("  projection: {model: equidistant, fx: 500}\n"), 4,
     15, "camera.projection", "give all four intrinsics fx, fy, cx, cy (px) or none"},
    {"ProjectionFoldingFisheye",
     withCameraLine("  projection: {model: kannala_brandt, k1: -0.5}\n"), 4, 15,
     "camera.projection.k1", "stop increasing at field angle"},
    {"ProjectionUnknownKey", withCameraLine("  projection: {model: opencv, k7: 1}\n"), 4, 31,
     "camera.projection.k7", "unknown key"},
    {"ProjectionFieldAngleOutOfRange",
     withCameraLine("  projection: {model: equidistant, max_field_angle_deg: 200}\n"), 4, 57,
     "camera.projection.max_field_angle_deg", "out of range"},
    {"ProjectionFlatPupilOfAFisheye",
     withCameraLine("  aperture: {pupil: flat}\n  projection: {model: equidistant}\n"), 5, 15,
     "camera.projection", "flat applies to the opencv model only"},
    {"ProjectionAndDistortion",
     withCameraLine("  distortion: {k1: 0.1}\n  projection: {model: opencv}\n"), 4, 15,
     "camera.distortion", "not both"},
    {"FocusInsideTheFocalLength", withCameraLine("  focus_distance_m: 0.05\n"), 4, 21,
     "camera.focus_distance_m", "must exceed 1.0001 × the focal length (0.050005 m)"},
    {"BoundPrintedAsWritten", sphereWith("1", ", emission: {scale: 1e31}"), 7, 68,
     "shapes[0].emission.scale", "out of range [0, 1e+30]"},
    {"WrongTypeStringForNumber", sphereWith("big", ", material: m"), 7, 47, "shapes[0].radius",
     "'big' is not a number"},
    {"WrongTypeNumberForList", withShapes("  - {type: sphere, centre: 5, radius: 1}\n"), 7, 28,
     "shapes[0].centre", "expected a list of 3 numbers"},
    {"NegativeRadius", sphereWith("-1", ", material: m"), 7, 47, "shapes[0].radius",
     "out of range"},
    {"RadiusUnderflowsFloat", sphereWith("1e-300", ", material: m"), 7, 47, "shapes[0].radius",
     "out of range [1e-09"},
    {"ZeroResolution", withCameraLine("  resolution: [0, 480]\n"), 4, 16, "camera.resolution[0]",
     "out of range"},
    {"ResolutionBeyondLimit", withCameraLine("  resolution: [1000000, 1000000]\n"), 4, 16,
     "camera.resolution[0]", "[1, 32768] (limit SceneLimits::kMaxResolution)"},
    {"PixelCountBeyondLimit", withCameraLine("  resolution: [20000, 20000]\n"), 4, 15,
     "camera.resolution", "SceneLimits::kMaxPixels"},
    {"NaN", withShapes("  - {type: sphere, centre: [0, .nan, 0], radius: 1, material: m}\n"), 7, 32,
     "shapes[0].centre[1]", "'.nan' is not a finite number"},
    {"Infinity", sphereWith(".inf", ", material: m"), 7, 47, "shapes[0].radius",
     "'.inf' is not a finite number"},
    {"CoordinateBeyondFloat", meshWith("[[0, 0, 0], [1e39, 0, 0], [0, 1, 0]]", "[[0, 1, 2]]"), 9,
     27, "shapes[0].vertices[1]", "within ±1e15 m"},
    {"MissingMeshFile", withShapes("  - type: mesh\n    material: m\n    file: missing.obj\n"), 9,
     11, "shapes[0].file", "not found"},
    {"MeshFileNameTooLong",  // the OS rejects the name: still "not found", not a crash
     withShapes("  - type: mesh\n    material: m\n    file: " + std::string(300, 'm') + ".obj\n"),
     9, 11, "shapes[0].file", "not found"},
    {"EmptyMesh", meshWith("[[0, 0, 0], [1, 0, 0], [0, 1, 0]]", "[]"), 10, 12, "shapes[0].faces",
     "no triangles"},
    {"FaceIndexOutOfRange", meshWith("[[0, 0, 0], [1, 0, 0], [0, 1, 0]]", "[[0, 1, 3]]"), 10, 20,
     "shapes[0].faces[0][2]", "out of range [0, 2]"},
    {"ZeroAreaMesh", meshWith("[[0, 0, 0], [1, 0, 0], [2, 0, 0]]", "[[0, 1, 2]]"), 10, 12,
     "shapes[0].faces", "zero area"},
    // Class numbers are exact in the float class.id channel to 2^24; named classes follow
    // the largest integer one (found by probing: after 4294967295 a name became class 0);
    // text that reads as another number was a class *named* "1e3" with number 1.
    {"ClassAboveTwoToThe24", sphereWith("1", ", material: m, class: 16777217"), 7, 70,
     "shapes[0].class", "out of range [1, 16777216]"},
    {"ClassReadsAsANumber", sphereWith("1", ", material: m, class: 1e3"), 7, 70, "shapes[0].class",
     "class '1e3' reads as a number"},
    {"NamedClassesPastTwoToThe24",
     withShapes("  - {type: sphere, centre: [0, 0, 0], radius: 1, material: m, class: 16777216}\n"
                "  - {type: sphere, centre: [3, 0, 0], radius: 1, material: m, class: car}\n"),
     7, 3, "shapes", "1 of them pass 16777216"},
    // Found by probing: ξ = −1 is singular (a black frame or a ring, exit 0); calibrated
    // intrinsics in the wrong unit imaged no pixel (a black frame with exports, exit 0).
    {"DoubleSphereXiMinusOne",
     withCameraLine("  projection: {model: double_sphere, xi: -1, alpha: 0.5}\n"), 4, 15,
     "camera.projection.xi", "(ξ = −1 is singular"},
    {"IntrinsicsImageNoPixel",
     kCamera +
         "  resolution: [96, 64]\n  projection: {model: equidistant, fx: 10, fy: 10, cx: 1e7, "
         "cy: 1e7}\n" +
         kMaterials + "shapes:\n" + kSphere,
     5, 15, "camera.projection", "images none of a 9 × 9 grid of the 96×64 image's pixels"},
    {"UnknownMaterial", sphereWith("1", ", material: paint"), 7, 60, "shapes[0].material",
     "no material named 'paint'"},
    {"ReflectanceAboveOne",
     kCamera + "materials:\n  m: {type: diffuse, reflectance: 1.5}\nshapes:\n" + kSphere, 5, 35,
     "materials.m.reflectance", "out of range"},
    {"UnknownIlluminant", sphereWith("1", ", emission: {spectrum: {illuminant: D99}, scale: 1}"), 7,
     84, "shapes[0].emission.spectrum.illuminant", "unknown CIE illuminant 'D99'"},
    {"LuminanceAndScale", sphereWith("1", ", emission: {luminance: 100, scale: 1}"), 7, 84,
     "shapes[0].emission.scale", "not both"},
    {"MissingCamera", kMaterials + "shapes:\n" + kSphere, 1, 1, "camera", "required key"},
    {"UnknownSampler", "render: {sampler: halton}\n" + kCamera + kMaterials + "shapes:\n" + kSphere,
     1, 19, "render.sampler", "unknown sampler 'halton' (known: sobol, independent)"},
    {"UnknownAov", "render: {aovs: [depth, flow]}\n" + kCamera + kMaterials + "shapes:\n" + kSphere,
     1, 24, "render.aovs[1]", "unknown aov 'flow' (known: depth, distance, position, normal"},
    {"AovTwice", "render: {aovs: [depth, depth]}\n" + kCamera + kMaterials + "shapes:\n" + kSphere,
     1, 24, "render.aovs[1]", "aov 'depth' is listed twice"},
    {"AdaptiveThresholdZero",
     "render: {adaptive_threshold: 0}\n" + kCamera + kMaterials + "shapes:\n" + kSphere, 1, 30,
     "render.adaptive_threshold", "(0, 1]"},
    {"AdaptiveMinSppOdd",
     "render: {adaptive_min_spp: 5}\n" + kCamera + kMaterials + "shapes:\n" + kSphere, 1, 28,
     "render.adaptive_min_spp", "adaptive_min_spp 5 is odd"},
    {"ZeroFrames", "frames: {count: 0}\n" + kCamera + kMaterials + "shapes:\n" + kSphere, 1, 17,
     "frames.count", "out of range"},
    {"UnknownFramesKey",
     "frames: {count: 2, fps: 30}\n" + kCamera + kMaterials + "shapes:\n" + kSphere, 1, 20,
     "frames.fps", "unknown key"},
    {"UnknownExport", "exports: [coco]\n" + kPrefix + kSphere, 1, 11, "exports[0]",
     "unknown export 'coco' (known: bop, kitti)"},
    {"ExportTwice", "exports: [bop, bop]\n" + kPrefix + kSphere, 1, 16, "exports[1]",
     "export 'bop' is listed twice"},
    {"BopExportNeedsAPinhole",
     "exports: [bop]\n" + withCameraLine("  projection: {model: equidistant}\n"), 1, 10, "exports",
     "needs the camera projection 'opencv' without distortion"},
    {"BopExportNeedsNoDistortion",
     "exports: [bop]\n" + withCameraLine("  projection: {model: opencv, k1: 0.1}\n"), 1, 10,
     "exports", "needs the camera projection 'opencv' without distortion"},
    {"BopExportNeedsNoDistortionBlock",
     "exports: [bop]\n" + withCameraLine("  distortion: {p1: 0.001}\n"), 1, 10, "exports",
     "needs the camera projection 'opencv' without distortion"},
    {"BopExportNeedsNoTracedLens",
     "exports: [bop]\n" + withCameraLine("  lens: {file: dgauss.50mm.dat}\n"), 1, 10, "exports",
     "export 'bop' needs the camera projection 'opencv' without distortion and no traced lens"},
    {"KittiExportNeedsAPinhole",
     "exports: [kitti]\n" + withCameraLine("  projection: {model: equidistant}\n"), 1, 10,
     "exports", "export 'kitti' needs the camera projection 'opencv' without distortion"},
    {"EmptyShapes", kCamera + kMaterials + "shapes: []\n", 6, 9, "shapes", "no shapes"},
    {"DuplicateKey",
     withShapes("  - type: sphere\n    centre: [0, 0, 0]\n    radius: 1\n    radius: 2\n"
                "    material: m\n"),
     10, 5, "shapes[0].radius", "duplicate key (first given at line 9)"},
    {"KeyWithoutValue",
     withShapes("  - type: sphere\n    centre: [0, 0, 0]\n    radius:\n    material: m\n"), 9, 5,
     "shapes[0].radius", "expected a number"},
    {"SecondDocument", withShapes(kSphere) + "---\nshapes: []\n", 9, 1, "", "one YAML document"},
    {"JsonSyntaxError",
     "{\"camera\": {\"position\": [0, 0, -1], \"look_at\": [0, 0, 0]},\n"
     " \"materials\": {\"m\": {\"type\": \"diffuse\"}},\n"
     " \"shapes\": [{\"type\": \"sphere\", \"centre\": [0, 0, 0], \"radius\": 1, "
     "\"material\": \"m\"}\n"
     "}\n",
     4, 1, "", "YAML syntax error"},
    {"JsonNegativeRadius",
     "{\"camera\": {\"position\": [0, 0, -1], \"look_at\": [0, 0, 0]},\n"
     " \"materials\": {\"m\": {\"type\": \"diffuse\"}},\n"
     " \"shapes\": [{\"type\": \"sphere\", \"centre\": [0, 0, 0], \"radius\": -1, "
     "\"material\": \"m\"}]\n"
     "}\n",
     3, 63, "shapes[0].radius", "out of range"},
    // Scenes that loaded and then aborted in Embree or an internal check (issue 34).
    {"UpIsZero", withCameraLine("  up: [0, 0, 0]\n"), 4, 7, "camera.up",
     "up must be a non-zero direction"},
    {"UpParallelToViewAfterScaling", withCameraLine("  up: [0, 0, 1e-300]\n"), 4, 7, "camera.up",
     "up is parallel to the viewing direction"},
    // A far camera position was blamed on look_at ("up is parallel to the viewing direction").
    {"CameraPositionBeyondRenderSpace",
     "camera:\n  position: [1e300, 0, -1]\n  look_at: [0, 0, 0]\n" + kMaterials + "shapes:\n" +
         kSphere,
     2, 13, "camera.position", "within ±1e15 m"},
    // The message stated only the lower end of the range.
    {"EmissionRgbAboveItsRange",
     sphereWith("1", ", emission: {spectrum: {rgb: [1e38, 0, 0]}, luminance: 1}"), 7, 77,
     "shapes[0].emission.spectrum.rgb", "must lie in [0, 1e30]"},
    // A missing lens file was "spectral table 'nosuch.dat' not found".
    {"MissingLensFile", withCameraLine("  lens: {file: nosuch.dat}\n"), 4, 16, "camera.lens.file",
     "lens file 'nosuch.dat' not found (searched: "},
    // A 1 ns exposure 1e10 s after time 0: its times run together (a failed check, exit 134).
    {"FramesTooLateForTheirExposure",
     withCameraLine("  shutter: {open: 0, close: 1e-9}\n") +
         "frames: {count: 2, first: 10000000, rate_hz: 0.001}\n",
     9, 9, "frames", "too short for the time it opens at"},
    // Found by probing: frames that overlap in time (an exposure or a rolling readout longer
    // than the frame period) rendered as if a camera could take them.
    {"FrameExposureLongerThanItsPeriod",
     withCameraLine("  shutter: {open: 0, close: 0.05}\n") + "frames: {count: 2, rate_hz: 24}\n", 9,
     9, "frames",
     "each frame's exposure, 0.05 s (camera.shutter), is longer than the frame period "
     "1/frames.rate_hz = 0.041666666666666664 s"},
    // Exposed 0.27 s at 24 fps (found by probing).
    {"LongestBracketLongerThanTheFramePeriod",
     withCameraLine("  shutter: {open: 0, close: 0.02}\n") +
         "sensor: {model: smartphone-1.4um, bracket_ev: [0, 2]}\nframes: {count: 2, rate_hz: 24}\n",
     10, 9, "frames", "the longest bracket (sensor.bracket_ev, ×4) exposes each frame for 0.08 s"},
    {"RollingReadoutLongerThanItsPeriod",
     withCameraLine("  shutter: {type: rolling, row_time: 1e-4, open: 0, close: 0.001}\n") +
         "frames: {count: 2, rate_hz: 24, shutter_angle_deg: 180}\n",
     9, 9, "frames", "the rolling shutter reads its 480 rows in 0.048"},
    // 0° → 270° about one axis was played as −90° (the quaternions' dot product was taken
    // as its absolute value; found by probing).
    {"KeyframesRotatingByMoreThan180Degrees",
     withCameraLine("  motion: [{time: 0, rotate: {axis: [0, 0, 1], angle_deg: 0}}, {time: 0.01, "
                    "rotate: {axis: [0, 0, 1], angle_deg: 270}}]\n"),
     4, 64, "camera.motion[1]", "consecutive keyframes rotate by 180° or more"},
    // 0° → 720° (cos(Δ/2) = 1) passed as no motion with the dot product (found in review).
    {"KeyframesRotatingByTwoTurns",
     withCameraLine("  motion: [{time: 0, rotate: {axis: [0, 0, 1], angle_deg: 0}}, {time: 0.01, "
                    "rotate: {axis: [0, 0, 1], angle_deg: 720}}]\n"),
     4, 64, "camera.motion[1]", "consecutive keyframes rotate by 180° or more"},
    // Every sample NaN and an exposure time of inf, exit 0 (found by probing).
    {"ShutterCurveTimeBeyondTheShuttersRange",
     withCameraLine("  shutter: {curve: [[0, 1], [1e300, 1]]}\n"), 4, 29, "camera.shutter.curve[1]",
     "time 1e+300 s is outside [-1e+06, 1e+06] s"},
    {"CameraKeyframeBeyondRenderSpace",
     withCameraLine("  motion: [{time: 0, translate: [1e19, 0, 0]}]\n"), 4, 33,
     "camera.motion[0].translate", "within ±1e15 m"},
    {"SphereRadiusBelowFloatSquare", sphereWith("1e-18", ", material: m"), 7, 47,
     "shapes[0].radius", "out of range [1e-09"},
    {"RectangleEdgeBeyondRenderSpace",
     withShapes("  - {type: rectangle, corner: [0, 0, 0], edge_u: [9.2e18, 0, 0], edge_v: [0, 1, "
                "0], material: m}\n"),
     7, 50, "shapes[0].edge_u", "within ±1e15 m"},
    {"CheckerboardChecksDenormal",
     kCamera +
         "materials:\n  m: {type: diffuse, reflectance: {checkerboard: {a: 0.8, b: 0.1, checks: "
         "5e-324}}}\nshapes:\n" +
         kSphere,
     5, 75, "materials.m.reflectance.checkerboard.checks", "0 in single precision"},
    {"SunDiscBelowRounding",
     withCameraLine("lights: [{type: distant, direction: [0, 0, 1], illuminance: 1, "
                    "angular_diameter: 1e-30}]\n"),
     4, 82, "lights[0].angular_diameter", "use 0 for parallel light"},
};

// GoogleTest prints a case by its name (found by ADL: here, beside ErrorCase).
inline void PrintTo(const ErrorCase& c, std::ostream* os) {
  *os << c.name;
}

}  // namespace camsim::test
