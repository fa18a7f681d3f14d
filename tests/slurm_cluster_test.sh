#!/usr/bin/env bash
# End-to-end test of scripts/slurm/animate.sbatch on a one-node Slurm cluster started here:
# munged, slurmctld and slurmd from a generated slurm.conf in a temporary folder; a job array
# renders frames 0-5 of a scene in three tasks of two; they must be, byte for byte, the frames
# of a local `lightcone animate`. Exits 77 (skipped, with the reason) where the daemons cannot
# start: no Slurm or munge installed, or not root.
#   slurm_cluster_test.sh LIGHTCONE_BINARY SOURCE_DIR
set -euo pipefail
lightcone=$1
source_dir=$2
skip() { echo "SKIP: $*"; exit 77; }
for program in munged mungekey slurmctld slurmd sbatch sinfo scontrol; do
  command -v "$program" >/dev/null 2>&1 || [ -x "/usr/sbin/$program" ] ||
    skip "$program is not installed (Debian: apt-get install slurm-wlm munge)"
done
[ "$(id -u)" -eq 0 ] || skip "slurmd must run as root to start jobs"
export PATH="$PATH:/usr/sbin"

dir=$(mktemp -d /tmp/lightcone-slurm-XXXXXX)
cleanup() {
  scontrol shutdown >/dev/null 2>&1 || true
  for pidfile in "$dir"/slurmctld.pid "$dir"/slurmd.pid "$dir"/munged.pid; do
    [ -f "$pidfile" ] && kill "$(cat "$pidfile")" 2>/dev/null || true
  done
  sleep 1
  rm -rf "$dir"
}
trap cleanup EXIT
mkdir -p "$dir/state" "$dir/spool" "$dir/frames" "$dir/local"
host=$(hostname -s)
port=$((20000 + RANDOM % 20000))

# munge: its own key, socket and files.
mungekey --create --keyfile="$dir/munge.key" --force >/dev/null 2>&1 ||
  dd if=/dev/urandom of="$dir/munge.key" bs=1024 count=1 status=none
chmod 600 "$dir/munge.key"
munged --key-file="$dir/munge.key" --socket="$dir/munge.socket" --pid-file="$dir/munged.pid" \
  --log-file="$dir/munged.log" --seed-file="$dir/munged.seed" --force ||
  skip "munged does not start: $(tail -n 3 "$dir/munged.log" 2>/dev/null)"

cpus=$(nproc)
memory=$(( $(awk '/MemTotal/ {print $2}' /proc/meminfo) / 1024 / 2 ))
cat >"$dir/slurm.conf" <<CONF
ClusterName=lightcone-test
SlurmctldHost=$host
SlurmUser=root
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
AuthInfo=socket=$dir/munge.socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
NodeName=$host CPUs=$cpus RealMemory=$memory State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$dir/slurm.conf"
slurmctld -f "$SLURM_CONF" || skip "slurmctld does not start: $(tail -n 5 "$dir/slurmctld.log")"
slurmd -f "$SLURM_CONF" || skip "slurmd does not start: $(tail -n 5 "$dir/slurmd.log")"
for _ in $(seq 60); do
  state=$(sinfo -h -o %T 2>/dev/null || true)
  [ "$state" = "idle" ] && break
  sleep 0.5
done
[ "$state" = "idle" ] ||
  skip "the node did not come up ($state): $(tail -n 5 "$dir/slurmd.log" "$dir/slurmctld.log")"

scene="$source_dir/scenes/rocket.json"
options=(--fps 4 --width 96 --height 54 --samples 1)
# Three tasks of two frames each: frames 0-5.
(cd "$dir" && FRAMES_PER_TASK=2 LIGHTCONE="$lightcone" sbatch --wait --array=0-2 \
  --cpus-per-task=1 "$source_dir/scripts/slurm/animate.sbatch" "$scene" "$dir/frames" \
  "${options[@]}") || { cat "$dir"/lightcone-animate-*.log; exit 1; }
"$lightcone" animate "$scene" --frames 0-5 -o "$dir/local/frame-%04d.png" "${options[@]}" --quiet
for i in 0 1 2 3 4 5; do
  name=$(printf 'frame-%04d.png' "$i")
  cmp "$dir/frames/$name" "$dir/local/$name" || { echo "frame $i differs"; exit 1; }
done
echo "the Slurm array's 6 frames are the local ones"
