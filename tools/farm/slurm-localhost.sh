#!/usr/bin/env bash
# A real render farm on this machine: Debian's Slurm (slurmctld + slurmd on localhost,
# munge for authentication) runs glint as job arrays — the tiles of an image, then the
# frames of an animation — and the results are checked byte for byte against the same
# renders made in one process. Starts every daemon it needs in a scratch folder (no
# system configuration is touched) and stops them on exit, also on failure.
# Usage: tools/farm/slurm-localhost.sh [GLINT]   (default: the release build in CARGO_TARGET_DIR
# or target/, else the debug build, else one built now with cargo build --locked)
# Exit code 0 when the farm's images equal the single renders; docs/farm.md.
set -euo pipefail
cd "$(dirname "$0")/../.."
repo=$PWD
target=${CARGO_TARGET_DIR:-$repo/target}
if [ $# -ge 1 ]; then
  glint=$1
elif [ -x "$target/release/glint" ]; then
  glint=$target/release/glint
else
  [ -x "$target/debug/glint" ] || cargo build --locked --bin glint
  glint=$target/debug/glint
fi
glint=$(realpath "$glint")

if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends \
    slurmctld slurmd slurm-client munge >/dev/null
fi

work=$(mktemp -d /tmp/glint-slurm.XXXXXX)
chmod 700 "$work"
pids=()
stop() {
  local code=$?
  [ -n "${SLURM_CONF:-}" ] && scancel --quiet --user="$(id -un)" 2>/dev/null || true
  for ((k = ${#pids[@]} - 1; k >= 0; k--)); do kill "${pids[k]}" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
  [ "$code" -ne 0 ] && tail -n 20 "$work"/*.log 2>/dev/null >&2
  rm -rf "$work"
  exit "$code"
}
trap stop EXIT

# munge: its own key, socket and files.
mkdir -p "$work/munge" "$work/spool" "$work/state" "$work/out" "$work/logs"
chmod 700 "$work/munge"
dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$work/munge/munge.key"
socket=$work/munge/munge.socket
munged --foreground --force --key-file="$work/munge/munge.key" --socket="$socket" \
  --pid-file="$work/munge/munged.pid" --log-file="$work/munge.log" \
  --seed-file="$work/munge/munged.seed" >>"$work/munge.log" 2>&1 &
pids+=($!)

host=$(hostname -s)
user=$(id -un)
cat >"$work/slurm.conf" <<CONF
ClusterName=glintfarm
SlurmctldHost=$host
SlurmctldPort=${GLINT_SLURMCTLD_PORT:-16817}
SlurmdPort=${GLINT_SLURMD_PORT:-16818}
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
AuthInfo=socket=$socket
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
ReturnToService=2
SlurmdTimeout=60
NodeName=$host CPUs=$(nproc) State=UNKNOWN
PartitionName=glint Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$work/slurm.conf
for _ in $(seq 50); do [ -S "$socket" ] && break; sleep 0.1; done
slurmctld -D -i -f "$SLURM_CONF" >>"$work/slurmctld.log" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" >>"$work/slurmd.log" 2>&1 &
pids+=($!)
for _ in $(seq 120); do
  state=$(sinfo -h -n "$host" -o %t 2>/dev/null || true)
  [ "$state" = idle ] && break
  sleep 0.5
done
[ "$state" = idle ] || { echo "slurm: node $host is '$state', not idle" >&2; exit 1; }
echo "slurm: slurmctld and slurmd up on $host ($(sinfo --version))"

out=$work/out
common=(--backend cpu --aa adaptive --threads 1)
tiles=4
# The tiles as a job array (one task per tile; the index from SLURM_ARRAY_TASK_ID).
sbatch --wait --quiet --array=0-$((tiles - 1)) --cpus-per-task=1 --chdir="$repo" \
  --output="$work/logs/tile-%a.log" --wrap \
  "$glint render scenes/demo.lua ${common[*]} --width 96 --height 64 --tile auto/$tiles --skip-existing -o $out/demo.png"
$glint assemble "$out"/demo-tile-*-of-$tiles.png -o "$out/demo-farm.png"
$glint render scenes/demo.lua "${common[@]}" --width 96 --height 64 -o "$out/demo-single.png" 2>/dev/null
cmp "$out/demo-farm.png" "$out/demo-single.png"
echo "slurm: $tiles tiles of scenes/demo.lua assembled = the single render, byte for byte"

# The frames as a job array (the frame from SLURM_ARRAY_TASK_ID), against one --frames run.
frames=(--frames 1-3 --width 48 --height 27)
sbatch --wait --quiet --array=0-2 --cpus-per-task=1 --chdir="$repo" \
  --output="$work/logs/frame-%a.log" --wrap \
  "$glint render scenes/scrabble-orbit.lua ${common[*]} ${frames[*]} --frame auto -o $out/orbit.png"
mkdir "$out/single"
$glint render scenes/scrabble-orbit.lua "${common[@]}" "${frames[@]}" -o "$out/single/orbit.png" 2>/dev/null
for n in 0001 0002 0003; do cmp "$out/orbit-$n.png" "$out/single/orbit-$n.png"; done
echo "slurm: 3 frames of scenes/scrabble-orbit.lua from the array = the single --frames run, byte for byte"
