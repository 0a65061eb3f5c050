// The printed reports of bench_limit.h (tables for the terminal and the limit CSV).
#include <cstdio>
#include <sstream>

#include "integrator/measure/bench_limit.h"
#include "integrator/measure/bench_metrics.h"

namespace camsim {
namespace {

double share(std::uint64_t part, std::uint64_t whole) {
  return whole ? 100.0 * static_cast<double>(part) / static_cast<double>(whole) : 0.0;
}

std::uint64_t countOf(const RayCounts& c, int kind) {
  return kind == 0 ? c.camera : kind == 1 ? c.bounce : c.shadow;
}

}  // namespace

std::string formatLimitTable(const std::vector<LimitResult>& results) {
  std::ostringstream out;
  char line[320];
  std::snprintf(line, sizeof line, "%-13s %9s %4s %9s %22s %22s %22s %11s %11s %6s %12s\n", "scene",
                "size", "spp", "rays", "camera: share, raw/s", "bounce: share, raw/s",
                "shadow: share, raw/s", "raw mix/s", "tracer/s", "ratio", "rounds");
  out << line;
  for (const LimitResult& r : results) {
    std::string kinds[kRayKindCount];
    for (int k = 0; k < kRayKindCount; ++k) {
      char cell[64];
      std::snprintf(cell, sizeof cell, "%5.1f%% %10s",
                    share(countOf(r.capture.rays, k), r.capture.rays.total()),
                    formatRate(r.byKind[static_cast<std::size_t>(k)].raysPerSecond()).c_str());
      kinds[k] = cell;
    }
    const std::string size = formatSize(r.resolution.x, r.resolution.y);
    std::snprintf(
        line, sizeof line, "%-13s %9s %4d %9llu %22s %22s %22s %11s %11s %6.3f  %5.3f–%5.3f\n",
        r.scene.c_str(), size.c_str(), r.spp, static_cast<unsigned long long>(r.recorded),
        kinds[0].c_str(), kinds[1].c_str(), kinds[2].c_str(),
        formatRate(r.mix.raysPerSecond()).c_str(), formatRate(r.tracerRaysPerSecond()).c_str(),
        r.ratio(), r.roundRatioLow, r.roundRatioHigh);
    out << line;
    if (r.dropped > 0)
      out << "  (" << r.dropped
          << " rays past the recorder's limit were not recorded: the replay is a subset)\n";
    if (r.recorded + r.dropped != r.capture.rays.total())
      out << "  warning: recorded " << r.recorded + r.dropped << " rays but the render counted "
          << r.capture.rays.total() << "\n";
  }
  return out.str();
}

std::string formatLimitCsv(const std::vector<LimitResult>& results) {
  std::ostringstream out;
  out << "scene,kind,width,height,spp,threads,rays,share,raw_rays_per_s,tracer_rays_per_s,ratio,"
         "round_ratio_min,round_ratio_max\n";
  auto g = [](double v) { return formatNumber(v, 9); };
  for (const LimitResult& r : results) {
    const std::string size = std::to_string(r.resolution.x) + "," + std::to_string(r.resolution.y);
    out << csvField(r.scene) << ",mix," << size << "," << r.spp << "," << r.threads << ","
        << r.recorded << ",1," << g(r.mix.raysPerSecond()) << "," << g(r.tracerRaysPerSecond())
        << "," << g(r.ratio()) << "," << g(r.roundRatioLow) << "," << g(r.roundRatioHigh) << "\n";
    for (int k = 0; k < kRayKindCount; ++k) {
      const ReplayResult& rep = r.byKind[static_cast<std::size_t>(k)];
      out << csvField(r.scene) << "," << rayKindName(static_cast<RayKind>(k)) << "," << size << ","
          << r.spp << "," << r.threads << "," << rep.rays << ","
          << g(share(countOf(r.capture.rays, k), r.capture.rays.total()) / 100.0) << ","
          << g(rep.raysPerSecond()) << ",,,,\n";
    }
  }
  return out.str();
}

std::string formatScaling(const std::string& scene, const ScalingResult& s) {
  std::ostringstream out;
  char line[256];
  const double speed = s.many.seconds > 0.0 ? s.one.seconds / s.many.seconds : 0.0;
  const double raw =
      s.rawOne.raysPerSecond() > 0.0 ? s.rawMany.raysPerSecond() / s.rawOne.raysPerSecond() : 0.0;
  out << "thread scaling, " << scene << " (" << formatSize(s.resolution.x, s.resolution.y)
      << ", Sobol', " << s.spp << " spp):\n";
  std::snprintf(line, sizeof line, "  %-22s %10s %12s %12s\n", "", "1 thread",
                std::to_string(s.threads).append(" threads").c_str(), "speed-up");
  out << line;
  std::snprintf(line, sizeof line, "  %-22s %9.3fs %11.3fs %11.2fx  (efficiency %.0f%%)\n",
                "tracer render, wall", s.one.seconds, s.many.seconds, speed,
                100.0 * speed / s.threads);
  out << line;
  std::snprintf(
      line, sizeof line,
      "  %-22s %9.3fs %11.3fs %11.2fx  (the work %d threads add; wall speed-up needs idle cores)\n",
      "tracer render, CPU-s", s.cpuOne, s.cpuMany, s.cpuOne > 0.0 ? s.cpuMany / s.cpuOne : 0.0,
      s.threads);
  out << line;
  std::snprintf(line, sizeof line, "  %-22s %10s %12s %11.2fx  (efficiency %.0f%%)\n",
                "raw replay, rays/s", formatRate(s.rawOne.raysPerSecond()).c_str(),
                formatRate(s.rawMany.raysPerSecond()).c_str(), raw, 100.0 * raw / s.threads);
  out << line;
  return out.str();
}

std::string formatMotionOverhead(const std::string& scene, const MotionOverhead& m) {
  std::ostringstream out;
  char line[256];
  out << "motion-blur overhead, " << scene << " (" << formatSize(m.resolution.x, m.resolution.y)
      << ", Sobol', " << m.spp << " spp; moving: " << m.timeSteps << " Embree time steps; "
      << m.rounds << " rounds):\n";
  std::snprintf(line, sizeof line, "  %-40s %9s %11s %12s %13s %11s\n", "variant", "seconds",
                "rays/s", "time ratio", "rounds", "per-ray");
  out << line;
  const double baseRate = m.still.raysPerSecond();
  const struct {
    const char* name;
    const RenderStats* stats;
    const std::vector<double>* ratios;  // null: the static render, every ratio's base
  } rows[] = {{"static (every motion at its first key)", &m.still, nullptr},
              {"static, time sampled anyway", &m.stillTimeSampled, &m.stillTimeSampledRatios},
              {"moving (as in the scene)", &m.moving, &m.movingRatios}};
  for (const auto& row : rows) {
    const double rate = row.stats->raysPerSecond();
    const RatioSpread ratio = row.ratios ? spreadOf(*row.ratios) : RatioSpread{1.0, 1.0, 1.0};
    char range[32];  // 13 columns wide, as the header
    if (row.ratios)
      std::snprintf(range, sizeof range, "%7.3f–%.3f", ratio.low, ratio.high);
    else
      std::snprintf(range, sizeof range, "%13s", "(base)");
    std::snprintf(line, sizeof line, "  %-40s %9.3f %11s %12.3f %s %11.3f\n", row.name,
                  row.stats->seconds, formatRate(rate).c_str(), ratio.median, range,
                  rate > 0.0 ? baseRate / rate : 0.0);
    out << line;
  }
  out << "  seconds: the fastest of the rounds; time ratio: the median over the rounds of\n"
         "  seconds ÷ that round's static render, rounds: their range; per-ray: static rays/s ÷\n"
         "  rays/s of the fastest renders\n";
  return out.str();
}

std::string formatMeshBuild(const MeshBuildResult& m) {
  std::ostringstream out;
  char line[256];
  out << "mesh build: generated torus, " << m.triangles << " triangles (binary PLY, "
      << formatNumber(m.plyMegabytes, 3) << " MB):\n";
  std::snprintf(line, sizeof line, "  load (scene loader + PLY parse)   %8.3f s\n", m.loadSeconds);
  out << line;
  const auto perTriangle = [&](std::int64_t bytes) {
    return m.triangles ? static_cast<double>(bytes) / static_cast<double>(m.triangles) : 0.0;
  };
  std::snprintf(
      line, sizeof line,
      "  Scene build (mesh + Embree BVH)   %8.3f s   resident set grew %.1f bytes/triangle "
      "(camsim's mesh copy + Embree's touched pages); Embree holds %.1f, peak %.1f\n",
      m.sceneSeconds, m.rssBytesPerTriangle, perTriangle(m.sceneEmbreeBytes),
      perTriangle(m.sceneEmbreePeakBytes));
  out << line;
  std::snprintf(line, sizeof line,
                "  Scene build, the mesh moving      %8.3f s   Embree holds %.1f bytes/triangle, "
                "peak %.1f (an instance of one pose, BVH at the Scene's quality)\n",
                m.movingSceneSeconds, perTriangle(m.movingEmbreeBytes),
                perTriangle(m.movingEmbreePeakBytes));
  out << line;
  for (const auto& [name, probe] :
       {std::pair<const char*, const MeshBuildProbe*>{"medium", &m.embreeMedium},
        std::pair<const char*, const MeshBuildProbe*>{"high", &m.embreeHigh}}) {
    std::snprintf(line, sizeof line,
                  "  bare Embree, %-6s quality      %8.3f s   Embree holds %.1f bytes/triangle "
                  "(memory monitor: "
                  "BVH incl. reserved blocks; arrays shared), peak %.1f\n",
                  name, probe->buildSeconds, probe->bytesPerTriangle(),
                  perTriangle(probe->bytesPeak));
    out << line;
  }
  return out.str();
}

std::string formatTextureLoad(const TextureLoadResult& t) {
  char line[320];
  const double texels = static_cast<double>(t.size) * t.size;
  std::snprintf(line, sizeof line,
                "texture load: %d x %d random-colour 8-bit sRGB PNG: decode %.3f s, uplift %.3f s "
                "(%.2f CPU-us per "
                "texel); round-trip RGB error max %.1e\n",
                t.size, t.size, t.decodeSeconds, t.upliftSeconds, 1e6 * t.upliftCpuSeconds / texels,
                t.maxRgbError);
  return line;
}

}  // namespace camsim
