# simlab on Slurm: a one-node cluster started here from Debian's packages (munge, slurmctld and slurmd on
# localhost, every file of theirs in this test's folder) grades the sample class through the job array of
# `simlab slurm grade --submit` (three shards, then the assembly), and measures the apple's quick trade study
# through `simlab slurm study trade --submit`. The gradebook is the one a single machine writes
# (cli/grade-sample-class's); the study's trade.csv has the single machine's points, all but the timings (the
# apple handout's run's). Skipped, in one line, where no cluster can be
# started: not root, or the packages are missing (scripts/install-deps --with-slurm installs them).
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

# An sbatch that refuses in two lines: simlab's error is one line, the two joined (never a literal "\n").
mkdir -p "$work/fake-bin"
printf '#!/bin/sh\necho "sbatch: error: Batch job submission failed:" >&2\necho "Invalid partition name specified" >&2\nexit 1\n' \
  >"$work/fake-bin/sbatch"
chmod +x "$work/fake-bin/sbatch"
run_capture refused env PATH="$work/fake-bin:$PATH" "$SIMLAB" slurm grade apple "$BIN_DIR/../sample-class/apple" \
  --out "$work/refused" --tasks 2 --submit
check "sbatch's refusal: one line, its lines joined" \
  bash -c "test $(status_of refused) -ne 0 && test \$(wc -l <'$work/refused.err') -eq 1 &&
           grep -q 'sbatch refused the job: sbatch: error: Batch job submission failed:; Invalid partition name specified\$' '$work/refused.err' &&
           ! grep -q '[\\]n' '$work/refused.err'"

if [[ $(id -u) -ne 0 ]]; then echo "skipped: starting slurmd needs root"; exit 77; fi
for tool in munged slurmctld slurmd sbatch squeue sinfo; do
  if ! command -v "$tool" >/dev/null; then
    echo "skipped: $tool is not installed (scripts/install-deps --with-slurm installs munge and Slurm)"
    exit 77
  fi
done

cluster=$work/cluster
mkdir -p "$cluster/state" "$cluster/spool"
stop_cluster() {
  local pids=() f
  for f in "$cluster"/slurmd.pid "$cluster"/slurmctld.pid "$cluster"/munged.pid; do
    [[ -s $f ]] && pids+=("$(cat "$f")")
  done
  [[ ${#pids[@]} -eq 0 ]] && return
  kill "${pids[@]}" 2>/dev/null
  for _ in $(seq 1 100); do kill -0 "${pids[@]}" 2>/dev/null || return; sleep 0.1; done
  kill -9 "${pids[@]}" 2>/dev/null
}
trap 'stop_cluster; rm -rf "$work"' EXIT

# munge: a key of its own, a socket in this folder.
dd if=/dev/urandom of="$cluster/munge.key" bs=1024 count=1 status=none
chmod 0400 "$cluster/munge.key"
munged --force --key-file="$cluster/munge.key" --socket="$cluster/munge.socket" --pid-file="$cluster/munged.pid" \
  --log-file="$cluster/munged.log" --seed-file="$cluster/munged.seed"
check "munged starts with a key of its own" bash -c "echo hello | munge -S '$cluster/munge.socket' | unmunge -S '$cluster/munge.socket' >/dev/null"

host=$(hostname -s)
port=$((20000 + RANDOM % 20000))
export SLURM_CONF=$cluster/slurm.conf
cat >"$SLURM_CONF" <<CONF
ClusterName=simlabtest
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$cluster/munge.socket
CredType=cred/munge
StateSaveLocation=$cluster/state
SlurmdSpoolDir=$cluster/spool
SlurmctldPidFile=$cluster/slurmctld.pid
SlurmdPidFile=$cluster/slurmd.pid
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmctldLogFile=$cluster/slurmctld.log
SlurmdLogFile=$cluster/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SlurmdParameters=config_overrides
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=simlab Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
slurmctld -f "$SLURM_CONF" && slurmd -f "$SLURM_CONF"
for _ in $(seq 1 120); do
  [[ $(sinfo -h -o %t 2>/dev/null) == idle ]] && break
  sleep 0.5
done
check "the one-node cluster comes up (node $host idle)" test "$(sinfo -h -o %t 2>/dev/null)" = idle
if [[ $(sinfo -h -o %t 2>/dev/null) != idle ]]; then tail -n 5 "$cluster"/slurmctld.log "$cluster"/slurmd.log; finish; fi

# wait_for JOB...: until squeue lists none of them (15 minutes at most).
wait_for() {
  local ids
  ids=$(IFS=,; echo "$*")
  for _ in $(seq 1 1800); do
    [[ -z $(squeue -h -j "$ids" 2>/dev/null) ]] && return 0
    sleep 0.5
  done
  return 1
}
jobs_of() { sed -n 's/^Submitted job \([0-9]*\) .* and job \([0-9]*\),.*/\1 \2/p' "$1"; }

# The sample class, with an object cache of its own: nothing comes from an earlier grading. One machine's gradebook
# of it is cli/grade-sample-class's ($FIXTURES/apple-graded).
class=$BIN_DIR/../sample-class/apple
students=$(ls "$class" | wc -l)
start=$(date +%s%N)
run_capture submit env SIMLAB_CACHE="$work/cache-cluster" "$SIMLAB" slurm grade apple "$class" --out "$work/grades" \
  --tasks 3 --jobs 1 --submit
read -r array assemble < <(jobs_of submit.out)
check "simlab slurm grade --submit submits the array and the assembly" test -n "${array:-}" -a -n "${assemble:-}"
check "the jobs end" wait_for "${array:-0}" "${assemble:-0}"
cluster_s=$(( ($(date +%s%N) - start) / 1000000 ))
logs=$work/grades/slurm/logs
check "each of the 3 tasks graded its share" \
  test "$(cat "$logs"/grade-*.out 2>/dev/null | grep -c 'once every shard has finished')" -eq 3
check "the assembly graded nothing again" grep -q "^0 graded, $students up to date and kept" "$logs"/assemble-*.out
check "the cluster's gradebook is one machine's" cmp -s "$work/grades/gradebook.csv" "$FIXTURES/apple-graded/gradebook.csv"
check "and so is the summary" cmp -s "$work/grades/summary.csv" "$FIXTURES/apple-graded/summary.csv"
echo "sample class of $students on a one-node cluster (3 tasks, submission to assembled gradebook):" \
     "$((cluster_s / 1000)).$(printf %03d $((cluster_s % 1000))) s"

# The apple's quick study: 9 parts (one per integrator) over 3 tasks, then trade.csv from them. One machine's is
# the apple handout's run (handouts/apple, $FIXTURES/handouts/apple), of the finished file: the reference's points.
run_capture study_submit "$SIMLAB" slurm study trade apple --quick --no-plots --output "$work/study" --tasks 3 --submit
read -r array assemble < <(jobs_of study_submit.out)
check "simlab slurm study trade --submit submits the array and the assembly" test -n "${array:-}" -a -n "${assemble:-}"
check "the study's jobs end" wait_for "${array:-0}" "${assemble:-0}"
check "the 9 parts are measured" test "$(ls "$work"/study/parts/apple.*.json 2>/dev/null | wc -l)" -eq 9
# Columns 1-15: everything but the seconds, the repeats and the message (which may name a time).
check "trade.csv has the single machine's points" \
  cmp -s <(cut -d, -f1-15 "$work/study/trade.csv") <(cut -d, -f1-15 "$FIXTURES/handouts/apple/solution-tree/study/trade.csv")
finish
