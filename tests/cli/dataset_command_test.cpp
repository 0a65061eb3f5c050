// `camsim dataset` (cli/dataset_command.cpp, integrator/dataset/dataset_run.cpp) on the real
// binary:
//  - shards 0..N−1 together write exactly the items of an unsharded run, byte for byte, each
//    item once in the index;
//  - a bad manifest exits 2 naming the manifest's file:line and writes nothing;
//  - SIGKILL mid-item, then --resume: every item done once, byte-identical to a clean run,
//    no temporary left; a second --resume renders nothing; a changed base scene renders
//    again; SIGTERM exits 143;
//  - SIGKILL exactly between an item's rename and its index line (the fault-injection point
//    CAMSIM_TEST_KILL_AFTER_RENAME), then --resume: the index lists every item once, in item
//    order, and --status agrees;
//  - a second run of a running shard, or a run with another shard count, exits 2 naming the
//    folder and its lock; the first completes, each item once; another shard of the same
//    run goes on beside it;
//  - the shard from Slurm's and Kubernetes' environment variables, and its errors.
#include "cli/dataset_command.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <set>

#include "cli/args.h"
#include "tests/support/child_process.h"
#include "tests/support/env_guard.h"
#include "tests/support/run_command.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

namespace fs = std::filesystem;
using test::readFile;
using test::writeFile;

// A small scene with a sensor (noise on): each item is a fraction of a second.
std::string baseScene(int spp) {
  return "format: camsim-scene/1\nname: probe\nrender: {spp: " + std::to_string(spp) +
         "}\n"
         "camera: {position: [0, 0, -3], look_at: [0, 0, 0], resolution: [24, 24], "
         "focal_length_mm: 0.05, shutter: {open: 0, close: 0.01}}\n"
         "sensor: {model: smartphone-1.4um, iso: 200, noise: full}\n"
         "materials: {grey: {type: diffuse, reflectance: 0.5}}\n"
         "shapes:\n"
         "  - {name: lamp, type: sphere, centre: [0, 2, 0], radius: 0.5, emission: {luminance: "
         "20000}}\n"
         "  - {name: ball, type: sphere, centre: [0, 0, 0], radius: 1, material: grey}\n";
}

const char* kManifest =
    "format: camsim-dataset/1\nscene: base.yaml\nseed: 11\n"
    "random:\n  count: 6\n  draw:\n"
    "    camera.position: {orbit: {centre: [0, 0, 0], radius: [2.5, 3.5], azimuth_deg: [-40, "
    "40]}}\n"
    "    sensor.iso: {choice: [100, 400]}\n";

// Every file under dir (relative path → content), temporaries included.
std::map<std::string, std::string> tree(const fs::path& dir, bool withIndex = false) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    const std::string rel = fs::relative(e.path(), dir).string();
    if (!withIndex && rel == "index.jsonl") continue;
    files[rel] = readFile(e.path());
  }
  return files;
}

std::multiset<std::string> indexItems(const fs::path& dir, const std::string& status) {
  std::multiset<std::string> items;
  std::istringstream in(readFile(dir / "index.jsonl"));
  for (std::string line; std::getline(in, line);)
    if (line.find("\"status\": \"" + status + "\"") != std::string::npos)
      items.insert(line.substr(0, line.find(',')));
  return items;
}

class DatasetCommand : public testing::Test {
 protected:
  void SetUp() override {
    writeFile(dir_.path() / "base.yaml", baseScene(4));
    writeFile(manifest_, kManifest);
  }
  test::RunResult run(const std::string& args) {
    return test::runCamsim("dataset " + test::quote(manifest_.string()) + " " + args, dir_.path());
  }
  test::TempDir dir_;
  fs::path manifest_ = dir_.path() / "sweep.yaml";
};

TEST_F(DatasetCommand, ShardsTogetherWriteExactlyTheItemsOfOneRun) {
  const fs::path whole = dir_.path() / "whole", parts = dir_.path() / "parts";
  const auto r = run("-o " + whole.string() + " --threads 2");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (int k = 0; k < 4; ++k) {
    const auto s = run("-o " + parts.string() + " --shard " + std::to_string(k) + "/4 --threads 1");
    ASSERT_EQ(s.exitCode, 0) << s.err;
  }
  const auto a = tree(whole), b = tree(parts);
  ASSERT_EQ(a.size(), b.size());
  // dataset.json, .camsim-lock + per item 6 outputs, scene, params, item
  EXPECT_EQ(a.size(), 2u + 6u * 9u);
  for (const auto& [name, content] : a) {
    ASSERT_TRUE(b.count(name)) << name;
    EXPECT_TRUE(b.at(name) == content) << name << " differs";
  }
  const auto done = indexItems(parts, "done");
  EXPECT_EQ(done.size(), 6u);
  EXPECT_EQ(std::set<std::string>(done.begin(), done.end()).size(), 6u);  // no item twice
}

TEST_F(DatasetCommand, ABadManifestExitsTwoNamingItsLineAndWritesNothing) {
  writeFile(manifest_, std::string(kManifest) + "    camera.f_number: {uniform: [-2, 1]}\n");
  const fs::path out = dir_.path() / "out";
  const auto r = run("-o " + out.string());
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find(manifest_.string() + ":9:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("camera.f_number"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(DatasetCommand, KilledMidItemResumesWithNothingLostOrTwice) {
  writeFile(dir_.path() / "base.yaml", baseScene(2048));  // ~0.5-1 s per item
  const fs::path clean = dir_.path() / "clean", out = dir_.path() / "out";
  ASSERT_EQ(run("-o " + clean.string()).exitCode, 0);
  {
    test::Child child({"dataset", manifest_.string(), "-o", out.string(), "--threads", "1"},
                      dir_.path() / "killed");
    // Kill it while an item is in progress: after two items are done, once the third's
    // temporary folder exists (between two items there is none to clean up, and on a loaded
    // machine the kill could land there).
    const auto itemInProgress = [&] {
      std::error_code ec;
      for (fs::recursive_directory_iterator it(out, ec), end; !ec && it != end; it.increment(ec))
        if (it->path().filename().string().find(".camsim-tmp-") != std::string::npos) return true;
      return false;
    };
    while (child.running() && child.secondsSinceStart() < 120 &&
           !(indexItems(out, "done").size() >= 2 && itemInProgress()))
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    ASSERT_TRUE(child.running()) << "finished before it could be killed";
    child.signal(SIGKILL);
    ASSERT_TRUE(child.wait(std::chrono::seconds(10)));
  }
  const auto r = run("-o " + out.string() + " --resume");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("removed"), std::string::npos) << "no temporary was left? " << r.err;
  const auto a = tree(clean), b = tree(out);
  ASSERT_EQ(a.size(), b.size());
  for (const auto& [name, content] : a) {
    ASSERT_TRUE(b.count(name)) << name;
    EXPECT_TRUE(b.at(name) == content) << name << " differs";
  }
  for (const auto& [name, content] : b)
    EXPECT_EQ(name.find("camsim-tmp"), std::string::npos) << name;
  const auto done = indexItems(out, "done");
  EXPECT_EQ(done.size(), 6u);
  EXPECT_EQ(std::set<std::string>(done.begin(), done.end()).size(), 6u);

  // Up to date: nothing rendered. A changed base scene: every item again.
  const auto again = run("-o " + out.string() + " --resume");
  EXPECT_NE(again.err.find("0 rendered, 6 up to date"), std::string::npos) << again.err;
  writeFile(dir_.path() / "base.yaml", baseScene(8));
  const auto changed = run("-o " + out.string() + " --resume");
  EXPECT_NE(changed.err.find("6 rendered, 0 up to date"), std::string::npos) << changed.err;
  const auto status = test::runCamsim("dataset --status " + out.string(), dir_.path());
  EXPECT_EQ(status.exitCode, 0);
  EXPECT_NE(status.out.find("6 items: 6 done, 0 failed, 0 missing"), std::string::npos)
      << status.out;
}

// The pictures' OCIO config is part of an item's hash by its content (its text and its
// search_path's files), also when $OCIO names it (found by probing: --resume kept pictures
// made through another config).
TEST_F(DatasetCommand, AnotherOcioConfigRendersAgainOnResume) {
  const fs::path out = dir_.path() / "out";
  ASSERT_EQ(run("-o " + out.string() + " --item 0 --threads 1").exitCode, 0);
  const fs::path luts = fs::path(CAMSIM_SOURCE_DIR) / "luts";
  fs::copy(luts / "looks", dir_.path() / "looks");
  writeFile(dir_.path() / "same.ocio", readFile(luts / "config.ocio"));
  writeFile(dir_.path() / "other.ocio", readFile(luts / "config.ocio") + "\n# another config\n");
  test::EnvGuard ocio("OCIO");
  ocio.set((dir_.path() / "same.ocio").string());  // the same content elsewhere: up to date
  auto r = run("-o " + out.string() + " --item 0 --resume --threads 1");
  EXPECT_NE(r.err.find("0 rendered, 1 up to date"), std::string::npos) << r.err;
  // A file of its search_path (a look) edited in place: the pictures may differ.
  const fs::path look = dir_.path() / "looks" / "camsim_warm.cdl";
  writeFile(look, readFile(look) + "\n");
  r = run("-o " + out.string() + " --item 0 --resume --threads 1");
  EXPECT_NE(r.err.find("1 rendered, 0 up to date"), std::string::npos) << r.err;
  ocio.set((dir_.path() / "other.ocio").string());
  r = run("-o " + out.string() + " --item 0 --resume --threads 1");
  EXPECT_NE(r.err.find("1 rendered, 0 up to date"), std::string::npos) << r.err;
}

// --status reads the record runDataset writes (found by probing: "items": 1e8 kept it
// counting past SIGTERM, 9e18 grew its list of missing items without end).
TEST_F(DatasetCommand, StatusRefusesARecordItDidNotWrite) {
  const fs::path out = dir_.path() / "out";
  ASSERT_EQ(run("-o " + out.string() + " --item 0 --threads 1").exitCode, 0);
  const std::string record = readFile(out / "dataset.json");
  std::string more = record;
  const std::string six = "\"items\": 6";
  more.replace(more.find(six), six.size(), "\"items\": 100000000");
  writeFile(out / "dataset.json", more);
  auto st = test::runCamsim("dataset --status " + out.string(), dir_.path());
  EXPECT_EQ(st.exitCode, 2) << st.out << st.err;
  EXPECT_NE(st.err.find("key 'items'"), std::string::npos) << st.err;
  std::string other = record;
  const std::string format = "camsim-dataset-output/1";
  other.replace(other.find(format), format.size(), "camsim-dataset-output/9");
  writeFile(out / "dataset.json", other);
  st = test::runCamsim("dataset --status " + out.string(), dir_.path());
  EXPECT_EQ(st.exitCode, 2) << st.out << st.err;
  EXPECT_NE(st.err.find("key 'format'"), std::string::npos) << st.err;
}

TEST_F(DatasetCommand, SigtermStopsWithExitCode143AndTheItemInProgressDropped) {
  writeFile(dir_.path() / "base.yaml", baseScene(4096));
  const fs::path out = dir_.path() / "out";
  test::Child child({"dataset", manifest_.string(), "-o", out.string(), "--threads", "1"},
                    dir_.path() / "term");
  ASSERT_TRUE(child.workFor(1.0, 60.0));
  child.signal(SIGTERM);
  const auto status = child.wait(std::chrono::seconds(60));
  ASSERT_TRUE(status);
  EXPECT_EQ(test::exitCode(*status), 143) << child.err();
  for (const auto& [name, content] : tree(out))
    EXPECT_EQ(name.find("camsim-tmp"), std::string::npos) << name;
  const auto st = test::runCamsim("dataset --status " + out.string(), dir_.path());
  EXPECT_EQ(st.exitCode, 1) << st.out;  // not all done
  EXPECT_NE(st.out.find("missing"), std::string::npos) << st.out;
}

// SIGTERM while the items are checked (before anything is written) stops at once (found by
// probing: the check of every item ran on, minutes for a large manifest, then wrote).
TEST_F(DatasetCommand, SigtermDuringTheItemCheckStopsWithNothingWritten) {
  std::string many = kManifest;
  many.replace(many.find("count: 6"), 8, "count: 20000");
  writeFile(manifest_, many);
  const fs::path out = dir_.path() / "out";
  test::Child child({"dataset", manifest_.string(), "-o", out.string(), "--threads", "1"},
                    dir_.path() / "term");
  ASSERT_TRUE(child.workFor(0.5, 60.0));
  child.signal(SIGTERM);
  const auto status = child.wait(std::chrono::seconds(20));  // the whole check: minutes
  ASSERT_TRUE(status) << "still checking 20 s after SIGTERM";
  EXPECT_EQ(test::exitCode(*status), 143) << child.err();
  EXPECT_NE(child.err().find("interrupted while checking the items (nothing written)"),
            std::string::npos)
      << child.err();
  EXPECT_FALSE(fs::exists(out / "dataset.json"));
}

// The items of index.jsonl's done lines, in the file's order.
std::vector<std::string> doneOrder(const fs::path& dir) {
  std::vector<std::string> items;
  std::istringstream in(readFile(dir / "index.jsonl"));
  for (std::string line; std::getline(in, line);)
    if (line.find("\"status\": \"done\"") != std::string::npos)
      items.push_back(line.substr(0, line.find(',')));
  return items;
}

TEST_F(DatasetCommand, KilledBetweenAnItemsRenameAndItsIndexLineLosesNoLine) {
  const fs::path clean = dir_.path() / "clean", out = dir_.path() / "out";
  ASSERT_EQ(run("-o " + clean.string() + " --threads 1").exitCode, 0);
  {
    test::EnvGuard kill("CAMSIM_TEST_KILL_AFTER_RENAME");
    kill.set("2");
    test::Child child({"dataset", manifest_.string(), "-o", out.string(), "--threads", "1"},
                      dir_.path() / "killed");
    const auto status = child.wait(std::chrono::seconds(120));
    ASSERT_TRUE(status);
    ASSERT_EQ(test::exitCode(*status), -SIGKILL) << child.err();
  }
  // Exactly between the two steps: item 2 in place, its line not written.
  ASSERT_TRUE(fs::is_regular_file(out / "items" / "000002" / "item.json"));
  EXPECT_EQ(doneOrder(out), (std::vector<std::string>{"{\"item\": 0", "{\"item\": 1"}));
  const auto before = test::runCamsim("dataset --status " + out.string(), dir_.path());
  EXPECT_EQ(before.exitCode, 1) << before.out;
  EXPECT_NE(before.out.find("6 items: 3 done, 0 failed, 3 missing"), std::string::npos)
      << before.out;
  EXPECT_NE(before.out.find("done but not in index.jsonl (a run was killed before writing "
                            "their lines; --resume adds them): 2\n"),
            std::string::npos)
      << before.out;

  const auto r = run("-o " + out.string() + " --resume --threads 1");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("index.jsonl: added the lines of up-to-date items 2 "), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("3 rendered, 3 up to date"), std::string::npos) << r.err;
  std::vector<std::string> inOrder;
  for (int i = 0; i < 6; ++i) inOrder.push_back("{\"item\": " + std::to_string(i));
  EXPECT_EQ(doneOrder(out), inOrder);  // each once, in item order
  const std::string index = readFile(out / "index.jsonl");
  const auto line2 = index.substr(index.find("{\"item\": 2,"));
  EXPECT_NE(line2.substr(0, line2.find('\n')).find("\"seconds\": null, \"render_seconds\": null"),
            std::string::npos)
      << line2;
  const auto a = tree(clean), b = tree(out);
  ASSERT_EQ(a.size(), b.size());
  for (const auto& [name, content] : a) {
    ASSERT_TRUE(b.count(name)) << name;
    EXPECT_TRUE(b.at(name) == content) << name << " differs";
  }
  const auto after = test::runCamsim("dataset --status " + out.string(), dir_.path());
  EXPECT_EQ(after.exitCode, 0) << after.out;
  EXPECT_EQ(after.out, out.string() + ": 6 items: 6 done, 0 failed, 0 missing\n");
  // Never a line twice: a second resume adds none.
  const auto again = run("-o " + out.string() + " --resume --threads 1");
  EXPECT_NE(again.err.find("0 rendered, 6 up to date"), std::string::npos) << again.err;
  EXPECT_EQ(again.err.find("added the lines"), std::string::npos) << again.err;
  EXPECT_EQ(doneOrder(out), inOrder);
}

TEST_F(DatasetCommand, ASecondRunOfARunningShardIsRefusedAndOtherShardsGoOn) {
  writeFile(dir_.path() / "base.yaml", baseScene(2048));  // ~0.5-1 s per item
  const fs::path out = dir_.path() / "out";
  test::Child first(
      {"dataset", manifest_.string(), "-o", out.string(), "--shard", "0/2", "--threads", "1"},
      dir_.path() / "first");
  // dataset.json is written once the shard is locked.
  const auto alive = [&] { return !first.wait(std::chrono::seconds(0)); };
  while (alive() && first.secondsSinceStart() < 60 && !fs::exists(out / "dataset.json"))
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_TRUE(alive()) << "ended before a second run could start: " << first.err();
  const std::string lock = (out / ".camsim-lock").string();
  for (const char* args : {"--shard 0/2", "--shard 0/2 --resume"}) {
    const auto second = run("-o " + out.string() + " " + args + " --threads 1");
    EXPECT_EQ(second.exitCode, 2) << args << ": " << second.err;
    EXPECT_NE(second.err.find("camsim: error: " + lock + ": not started: shard 0/2 of " +
                              out.string() + " is being rendered by another camsim dataset run"),
              std::string::npos)
        << args << ": " << second.err;
  }
  const auto whole = run("-o " + out.string() + " --threads 1");  // shard 0/1: overlaps both
  EXPECT_EQ(whole.exitCode, 2) << whole.err;
  EXPECT_NE(whole.err.find(lock + ": not started: a camsim dataset run with a shard count of 2"),
            std::string::npos)
      << whole.err;
  ASSERT_TRUE(alive()) << "shard 0/2 ended before shard 1/2 started: not side by side";
  const auto other = run("-o " + out.string() + " --shard 1/2 --threads 1");
  EXPECT_EQ(other.exitCode, 0) << other.err;
  const auto status = first.wait(std::chrono::seconds(120));
  ASSERT_TRUE(status);
  EXPECT_EQ(test::exitCode(*status), 0) << first.err();
  const auto done = indexItems(out, "done");
  EXPECT_EQ(done.size(), 6u);
  EXPECT_EQ(std::set<std::string>(done.begin(), done.end()).size(), 6u);
  for (const auto& [name, content] : tree(out))
    EXPECT_EQ(name.find("camsim-tmp"), std::string::npos) << name;
  const auto st = test::runCamsim("dataset --status " + out.string(), dir_.path());
  EXPECT_EQ(st.out, out.string() + ": 6 items: 6 done, 0 failed, 0 missing\n");
}

TEST(DatasetShard, FromFlagsSlurmAndKubernetes) {
  DatasetArgs a;
  a.manifest = "m.yaml";
  std::string source = "x";
  EXPECT_EQ(resolveShard(a, {}, &source).count, 1);
  EXPECT_EQ(source, "");
  const Share slurm = resolveShard(a,
                                   {{"SLURM_ARRAY_TASK_ID", "7"},
                                    {"SLURM_ARRAY_TASK_MIN", "5"},
                                    {"SLURM_ARRAY_TASK_COUNT", "4"}},
                                   &source);
  EXPECT_EQ(slurm.index, 2);
  EXPECT_EQ(slurm.count, 4);
  EXPECT_EQ(source, "SLURM_ARRAY_TASK_ID");
  EXPECT_THROW(resolveShard(a, {{"SLURM_ARRAY_TASK_ID", "9"}, {"SLURM_ARRAY_TASK_COUNT", "4"}}),
               UsageError);  // not a contiguous 0-based array
  EXPECT_THROW(resolveShard(a, {{"SLURM_ARRAY_TASK_ID", "1"}}), UsageError);
  EXPECT_THROW(resolveShard(a, {{"SLURM_ARRAY_TASK_ID", "0"}, {"SLURM_ARRAY_TASK_COUNT", "0"}}),
               UsageError);
  EXPECT_THROW(resolveShard(a, {{"JOB_COMPLETION_INDEX", "1"}}), UsageError);  // no count
  const Share k8s =
      resolveShard(a, {{"JOB_COMPLETION_INDEX", "3"}, {"CAMSIM_SHARD_COUNT", "5"}}, &source);
  EXPECT_EQ(k8s.index, 3);
  EXPECT_EQ(k8s.count, 5);
  EXPECT_EQ(source, "JOB_COMPLETION_INDEX");
  EXPECT_THROW(resolveShard(a, {{"JOB_COMPLETION_INDEX", "5"}, {"CAMSIM_SHARD_COUNT", "5"}}),
               UsageError);
  // The flag is parsed by sensor/base/share.h's parseShare, and wins over the environment.
  a = parseDatasetArgs({"dataset", "m.yaml", "--shard", "1/3"});
  ASSERT_TRUE(a.shard.has_value());
  const Share flag =
      resolveShard(a, {{"SLURM_ARRAY_TASK_ID", "0"}, {"SLURM_ARRAY_TASK_COUNT", "2"}}, &source);
  EXPECT_EQ(flag.index, 1);
  EXPECT_EQ(flag.count, 3);
  EXPECT_EQ(source, "--shard");
  for (const char* bad : {"3/3", "-1/3", "1/0", "1", "a/3", "1/3x", "/3", "1/", "1/2/3"}) {
    try {
      (void)parseDatasetArgs({"dataset", "m.yaml", "--shard", bad});
      ADD_FAILURE() << "accepted " << bad;
    } catch (const UsageError& e) {
      EXPECT_EQ(std::string(e.what()),
                std::string("--shard: expects k/M (share k of M, 0 <= k < M, 1 <= M <= "
                            "1048576), got '") +
                    bad + "'");
    }
  }
}

}  // namespace
}  // namespace camsim
