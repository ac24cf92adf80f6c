#!/usr/bin/env bash
# pmrender on a real Slurm: starts a private munged, slurmctld and slurmd on localhost (generated
# configuration, state, logs and sockets in a temporary folder, free ports picked now, run as the
# current user), submits a 3-task job array for 6 frames with `pmrender farm slurm --submit`, kills
# one task mid-frame, checks that `frames check` names its missing frame, requeues it, and checks
# that the sequence completes, that `frames check` passes, that no temporary or frame claim is
# left, and that every frame is bit-identical (every layer) to one single-process render. Missing
# Slurm or munge binaries are a failure, not a skip: CI installs them (.ci/install-deps). Every
# daemon is stopped on exit, also on failure or timeout.
#
# usage: slurm_localhost_test.sh PMRENDER_BINARY ANIMATION_DATA_DIR
set -euo pipefail

readonly TIME_LIMIT=240  # seconds for the whole test; a watchdog ends it after that
PMRENDER=$(realpath "$1")
DATA=$(realpath "$2")
export PATH="$PATH:/usr/sbin:/sbin"

say() { printf '[slurm test %s] %s\n' "$(date +%T)" "$*"; }
fail() { say "FAIL: $*"; exit 1; }

for tool in munged slurmctld slurmd sbatch squeue scontrol scancel sinfo python3; do
  command -v "$tool" >/dev/null || fail "$tool not found: install slurm-wlm, slurm-client and munge (.ci/install-deps)"
done

T=$(mktemp -d "${TMPDIR:-/tmp}/pmrender-slurm.XXXXXX")
chmod 755 "$T"
pids=()
cleanup() {
  local status=$?
  trap - EXIT INT TERM
  set +e
  if [ -n "${SLURM_CONF:-}" ] && [ -S "$T/munge/socket" ]; then
    scancel --user="$(id -un)" >/dev/null 2>&1
    for _ in $(seq 20); do [ -z "$(squeue -h 2>/dev/null)" ] && break; sleep 0.25; done
  fi
  for (( i=${#pids[@]}-1; i>=0; i-- )); do kill -TERM "${pids[i]}" 2>/dev/null; done
  for _ in $(seq 20); do
    alive=0
    for p in "${pids[@]}"; do kill -0 "$p" 2>/dev/null && alive=1; done
    [ $alive = 0 ] && break
    sleep 0.25
  done
  for p in "${pids[@]}"; do kill -KILL "$p" 2>/dev/null; done
  [ -n "${watchdog:-}" ] && kill "$watchdog" 2>/dev/null
  if [ $status -ne 0 ]; then
    for log in "$T"/log/*.log "$T"/log/*.out "$T"/munge/munged.log "$T/farm run/out frames/logs"/*.log; do
      [ -f "$log" ] && { echo "---- ${log#"$T"/} (last 25 lines)"; tail -n 25 "$log"; }
    done
  fi
  rm -rf "$T"
  exit $status
}
trap cleanup EXIT
trap 'say "FAIL: stopped by a signal (the time limit is $TIME_LIMIT s)"; exit 1' INT TERM
# The watchdog polls, so it never outlives the test by more than a second and holds no output open.
( end=$((SECONDS + TIME_LIMIT))
  while [ $SECONDS -lt $end ]; do sleep 1; kill -0 $$ 2>/dev/null || exit 0; done
  kill -TERM $$ ) >/dev/null 2>&1 &
watchdog=$!

# waits until the command succeeds, at most $1 seconds
wait_for() {
  local limit=$1; shift
  local end=$((SECONDS + limit))
  until "$@"; do
    [ $SECONDS -lt $end ] || return 1
    sleep 0.1
  done
}

# --- munge and Slurm, private to this test --------------------------------------------------
mkdir -p "$T/munge" "$T/state" "$T/spool" "$T/log"
chmod 700 "$T/munge"
head -c 1024 /dev/urandom >"$T/munge/munge.key"
chmod 600 "$T/munge/munge.key"
munged --foreground --force --key-file="$T/munge/munge.key" --socket="$T/munge/socket" \
  --pid-file="$T/munge/munged.pid" --log-file="$T/munge/munged.log" --seed-file="$T/munge/munged.seed" \
  >"$T/log/munged.out" 2>&1 &
pids+=($!)
wait_for 10 test -S "$T/munge/socket" || fail "munged did not start"

read -r ctld_port slurmd_port < <(python3 -c '
import socket
held = []
for _ in range(2):
    s = socket.socket(); s.bind(("127.0.0.1", 0)); held.append(s)
print(*(s.getsockname()[1] for s in held))')
user=$(id -un)
host=$(hostname -s)
export SLURM_CONF="$T/slurm.conf"
cat >"$SLURM_CONF" <<EOF
ClusterName=pmtest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
CredType=cred/munge
# cred_expire is also how long a requeued job waits before it may start again (default 120 s)
AuthInfo=socket=$T/munge/socket,cred_expire=10
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool
SlurmctldPidFile=$T/slurmctld.pid
SlurmdPidFile=$T/slurmd.pid
SlurmctldLogFile=$T/log/slurmctld.log
SlurmdLogFile=$T/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/builtin
SchedulerParameters=sched_interval=1
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SlurmdParameters=config_overrides
ReturnToService=2
MailProg=/bin/true
MinJobAge=600
KillWait=2
SlurmctldTimeout=30
SlurmdTimeout=30
NodeName=$host NodeAddr=127.0.0.1 CPUs=2 RealMemory=1000 State=UNKNOWN
PartitionName=farmtest Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
slurmctld -D -f "$SLURM_CONF" >"$T/log/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" -N "$host" >"$T/log/slurmd.out" 2>&1 &
pids+=($!)
node_idle() { [ "$(sinfo -h -n "$host" -o %T 2>/dev/null)" = idle ]; }
wait_for 30 node_idle || fail "the node did not become idle: $(sinfo 2>&1)"
say "slurmctld on port $ctld_port, slurmd on port $slurmd_port, node $host idle"

# --- the farm job: 6 frames, chunks of 2, paths with spaces ----------------------------------
work="$T/farm run"
mkdir -p "$work/scene"
cp "$DATA/moving_room.json" "$DATA/room.obj" "$work/scene/"
# Frames of about a second each here (PoCL), so a kill lands inside a frame.
render_options=(--backend opencl --resolution 48x36 --photons 300000 --float)
submitted=$(cd "$work" && "$PMRENDER" farm slurm scene/moving_room.json --chunk 2 --frames 0-5 "${render_options[@]}" \
  -o "out frames/f_####.exr" --script job.sh --submit)
echo "$submitted"
job=$(sed -n 's/^submitted job \([0-9][0-9]*\) .*/\1/p' <<<"$submitted")
[ -n "$job" ] || fail "no job id in: $submitted"
out="$work/out frames"
log() { echo "$out/logs/pmrender-moving-room_${job}_$1.log"; }
state() { scontrol show job "${job}_$1" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p'; }

# Task 1 renders frames 2 and 3: kill it once frame 2 is written, i.e. while frame 3 renders.
wrote_frame_2() { grep -q 'wrote .*(frame 2,' "$(log 1)" 2>/dev/null; }
wait_for 90 wrote_frame_2 || fail "task 1 never wrote frame 2"
scancel --signal=KILL --full "${job}_1"
say "killed task ${job}_1 mid-frame"
ended() { case "$(state "$1")" in COMPLETED|FAILED|CANCELLED|OUT_OF_MEMORY|NODE_FAIL|TIMEOUT) return 0;; esac; return 1; }
all_ended() { ended 0 && ended 1 && ended 2; }
wait_for 90 all_ended || fail "tasks did not end: $(squeue 2>&1)"
[ "$(state 0)" = COMPLETED ] && [ "$(state 2)" = COMPLETED ] || fail "tasks 0 and 2: $(state 0), $(state 2)"
[ "$(state 1)" != COMPLETED ] || fail "task 1 completed although it was killed"
[ -f "$out/f_0002.exr" ] || fail "frame 2 is missing after the kill"
[ ! -f "$out/f_0003.exr" ] || fail "frame 3 was already written when the kill came: frames too fast to test"

check_status=0
"$PMRENDER" frames check -o "$out/f_####.exr" --frames 0-5 --resolution 48x36 >"$T/check1.txt" || check_status=$?
cat "$T/check1.txt"
[ $check_status = 1 ] || fail "frames check after the kill exited $check_status, expected 1"
# Slurm ends a cancelled job with SIGTERM before the SIGKILL, and pmrender, stopping on SIGTERM
# once the pass in progress is done, removes its claim: frame 3 is missing, or still being
# rendered by the killed attempt (a claim) when that pass has not yet ended.
grep -Eq "^frame 3: .*: (missing|being rendered \(missing)" "$T/check1.txt" || fail "frames check did not name frame 3"
[ "$(grep -c '^frame ' "$T/check1.txt")" = 1 ] || fail "frames check named more than frame 3"

# --- requeue the killed task: it renders only what is missing --------------------------------
scontrol requeue "${job}_1"
say "requeued task ${job}_1"
completed_again() { [ "$(state 1)" = COMPLETED ]; }
wait_for 90 completed_again || fail "the requeued task did not complete: $(state 1)"
grep -q "attempt 2" "$(log 1)" || fail "the task log shows no second attempt"
grep -q "rendered 1 of 2 frames.*1 already complete" "$(log 1)" || fail "the requeued task did not resume"
grep -Eq '^[0-9-]+ [0-9:.]+ wrote .*\(frame 3, 48x36, .* ms[,)]' "$(log 1)" || fail "no timestamped per-frame line"

"$PMRENDER" frames check -o "$out/f_####.exr" --frames 0-5 --resolution 48x36 || fail "frames check after the requeue"
leftovers=$(cd "$out" && ls -A | grep -v -x -e 'f_000[0-5].exr' -e logs || true)
[ -z "$leftovers" ] || fail "unexpected files beside the frames: $leftovers"

# --- the same frames from one process, bit for bit -------------------------------------------
"$PMRENDER" render "$work/scene/moving_room.json" "${render_options[@]}" --frames 0-5 -o "$T/one/f_####.exr" -q
for f in 0 1 2 3 4 5; do
  for layer in combined direct indirect caustic; do
    "$PMRENDER" compare "$T/one/f_000$f.exr" "$out/f_000$f.exr" --metric rmse --threshold 0 --layer $layer >/dev/null ||
      fail "frame $f, layer $layer differs from the single-process render"
  done
done
say "PASS: 6 frames in 3 tasks, one killed and requeued, identical to one process ($SECONDS s)"
