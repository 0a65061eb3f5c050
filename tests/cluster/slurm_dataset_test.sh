#!/bin/bash
# camsim dataset on a real single-node Slurm (scripts/slurm/start_cluster.sh), as README's
# test command runs it (scripts/test.sh, stage "slurm"; needs root):
#   1. a 4-task array (scripts/slurm/camsim_array.sbatch) over a 12-item manifest completes,
#      its files byte-identical to a local run, every item done once;
#   2. one task cancelled mid-run (scancel: SIGTERM, camsim exits 143, the task ends
#      CANCELLED) and then requeued (scontrol requeue) finishes with nothing lost: the item
#      in progress is dropped and rendered again when the task runs again;
#   3. a manifest with a bad key fails every task with exit code 2, none restarted, nothing
#      written.
# Fails, saying why, if the cluster cannot start. Usage: slurm_dataset_test.sh CAMSIM [WORKDIR]
set -uo pipefail
camsim=$(realpath "${1:?usage: slurm_dataset_test.sh CAMSIM [WORKDIR]}")
root=$(cd "$(dirname "$0")/../.." && pwd)
work=${2:-$(mktemp -d /tmp/camsim_slurm_test_XXXXXX)}
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
fail() { echo "slurm test: FAILED: $*" >&2; exit 1; }
say() { echo "slurm test: $*" >&2; }
start=$(date +%s)

# The cluster is stopped at the end if this test started it.
if ! pgrep -x slurmctld >/dev/null; then
  trap '"$root/scripts/slurm/stop_cluster.sh" >/dev/null 2>&1' EXIT
fi
"$root/scripts/slurm/start_cluster.sh" >cluster.log 2>&1 || { cat cluster.log >&2; fail "the Slurm cluster did not start (above)"; }
export SLURM_CONF=${CAMSIM_SLURM_DIR:-/tmp/camsim-slurm}/slurm.conf

cat >base.yaml <<'YAML'
format: camsim-scene/1
name: probe
render: {spp: 1024}
camera: {position: [0, 0, -3], look_at: [0, 0, 0], resolution: [32, 32], focal_length_mm: 0.07, shutter: {open: 0, close: 0.01}}
sensor: {model: smartphone-1.4um, iso: 200, noise: full}
materials: {grey: {type: diffuse, reflectance: 0.5}}
shapes:
  - {name: lamp, type: sphere, centre: [0, 2, 0], radius: 0.5, emission: {luminance: 20000}}
  - {name: ball, type: sphere, centre: [0, 0, 0], radius: 1, material: grey}
YAML
cat >m.yaml <<'YAML'
format: camsim-dataset/1
scene: base.yaml
seed: 4
random:
  count: 12
  draw:
    camera.position: {orbit: {centre: [0, 0, 0], radius: [2.5, 3.5], azimuth_deg: [-40, 40]}}
    sensor.iso: {choice: [100, 400]}
YAML
"$camsim" dataset m.yaml -o local --threads 1 2>local.log || fail "the local run failed: $(tail -3 local.log)"

# 1 + 2: the array, task 2 requeued once it has finished an item.
mkdir -p slurm-logs
job=$(MANIFEST=$PWD/m.yaml OUT=$PWD/cluster CAMSIM=$camsim sbatch --parsable "$root/scripts/slurm/camsim_array.sbatch") ||
  fail "sbatch refused the array"
job=${job%%;*}
say "submitted array $job (4 tasks)"
requeued=0
for _ in $(seq 600); do
  if [ "$requeued" = 0 ] && [ -f cluster/index.jsonl ] && grep -q '"shard": "2/4"' cluster/index.jsonl; then
    # The operator's way: scancel the running task (SIGTERM: camsim stops, exit 143, the
    # task ends CANCELLED and stays so), then requeue it by hand; it resumes.
    scancel "${job}_2" || fail "scancel ${job}_2 refused"
    say "cancelled task ${job}_2 mid-run after its first item ($(($(date +%s) - start)) s)"
    for _ in $(seq 120); do
      scontrol show job "${job}_2" | grep -q "JobState=CANCELLED" && break
      sleep 0.5
    done
    scontrol show job "${job}_2" | grep -q "JobState=CANCELLED" ||
      fail "task ${job}_2 did not end CANCELLED: $(scontrol show job "${job}_2" | grep -o 'JobState=[A-Z]*')"
    scontrol requeue "${job}_2" || fail "scontrol requeue of the cancelled task ${job}_2 refused"
    requeued=1
    say "task ${job}_2 CANCELLED, then requeued ($(($(date +%s) - start)) s)"
  fi
  [ -z "$(squeue -h -j "$job" 2>/dev/null)" ] && break
  sleep 0.5
done
[ -z "$(squeue -h -j "$job")" ] || fail "the array did not finish in 300 s: $(squeue -j "$job")"
[ "$requeued" = 1 ] || fail "task 2 finished before it could be requeued"
for t in 0 1 2 3; do
  state=$(scontrol show job "${job}_$t" | grep -o 'JobState=[A-Z]*\|ExitCode=[0-9:]*\|Restarts=[0-9]*' | tr '\n' ' ')
  say "task $t: $state"
  grep -q "JobState=COMPLETED" <<<"$state" || fail "task $t did not complete: $state"
done
restarts=$(scontrol show job "${job}_2" | grep -o 'Restarts=[0-9]*')
[ "$restarts" = "Restarts=1" ] || fail "task 2 was not restarted once ($restarts)"
grep -l "exit 143\|SIGTERM" slurm-logs/*_"$job"_2.out >/dev/null || fail "task 2's log shows no SIGTERM"
diff -r -x index.jsonl local cluster >diff.txt || fail "the cluster's files differ from the local run: $(head -5 diff.txt)"
done_lines=$(grep -c '"status": "done"' cluster/index.jsonl)
distinct=$(grep '"status": "done"' cluster/index.jsonl | cut -d, -f1 | sort -u | wc -l)
[ "$done_lines" = 12 ] && [ "$distinct" = 12 ] || fail "index: $done_lines done lines, $distinct distinct items (expected 12, 12)"
[ -z "$(find cluster -name '*camsim-tmp*')" ] || fail "temporaries left: $(find cluster -name '*camsim-tmp*')"
say "array: 12 items byte-identical to the local run, each done once; task 2 cancelled, requeued and resumed ($(($(date +%s) - start)) s so far)"

# 3: a bad key fails every task with exit 2 and no restart.
sed 's/sensor.iso:/sensor.isoo:/' m.yaml >bad.yaml
job=$(MANIFEST=$PWD/bad.yaml OUT=$PWD/bad CAMSIM=$camsim sbatch --parsable "$root/scripts/slurm/camsim_array.sbatch") || fail "sbatch refused"
job=${job%%;*}
for _ in $(seq 240); do [ -z "$(squeue -h -j "$job")" ] && break; sleep 0.5; done
for t in 0 1 2 3; do
  state=$(scontrol show job "${job}_$t" | grep -o 'JobState=[A-Z]*\|ExitCode=[0-9:]*\|Restarts=[0-9]*' | tr '\n' ' ')
  grep -q "JobState=FAILED" <<<"$state" && grep -q "ExitCode=2:0" <<<"$state" && grep -q "Restarts=0" <<<"$state" ||
    fail "bad manifest, task $t: $state (expected FAILED, exit 2, no restart)"
done
grep -q "bad.yaml:.*sensor.isoo" slurm-logs/*_"$job"_0.out || fail "the log does not name the bad key: $(tail -2 slurm-logs/*_"$job"_0.out)"
[ ! -e bad ] || fail "a bad manifest wrote $(ls bad)"
say "bad key: 4 tasks FAILED with exit 2, none restarted, nothing written"
say "passed in $(($(date +%s) - start)) s"
