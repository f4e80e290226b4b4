#!/usr/bin/env bash
# The Slurm route of runout sweep, on a real single-node Slurm started here (Debian's
# slurm-wlm and munge: munged, slurmctld and slurmd on this host with a generated slurm.conf,
# state, ports and key of their own in a temporary folder), stopped at the end. The tiny sweep
# is submitted with `sbatch --wait` as a job array, gathered, and its results.csv must be the
# bytes of the same sweep run locally. Exit 77 (skipped) when slurm-wlm or munge is missing.
set -uo pipefail
bin=$1 src=$2
for tool in munged slurmctld slurmd sbatch sinfo; do
  command -v "$tool" >/dev/null || { echo "skipped: $tool not installed (apt-get install slurm-wlm munge)"; exit 77; }
done
d=$(mktemp -d)
host=$(hostname -s)
port=$((20000 + RANDOM % 20000))
cleanup() {
  for p in "$d/slurmd.pid" "$d/slurmctld.pid" "$d/munged.pid"; do [ -s "$p" ] && kill "$(cat "$p")" 2>/dev/null; done
  sleep 1
  rm -rf "$d"
}
trap cleanup EXIT
mkdir -p "$d/spool" "$d/state"
dd if=/dev/urandom of="$d/munge.key" bs=1024 count=1 status=none && chmod 400 "$d/munge.key"
munged --force --key-file="$d/munge.key" --socket="$d/munge.socket" --pid-file="$d/munged.pid" \
  --log-file="$d/munged.log" --seed-file="$d/munge.seed" || { echo "FAIL munged did not start"; exit 1; }
cat >"$d/slurm.conf" <<CONF
ClusterName=runouttest
SlurmctldHost=$host
SlurmUser=$(id -un)
SlurmdUser=$(id -un)
AuthType=auth/munge
AuthInfo=socket=$d/munge.socket
CredType=cred/munge
StateSaveLocation=$d/state
SlurmdSpoolDir=$d/spool
SlurmctldPidFile=$d/slurmctld.pid
SlurmdPidFile=$d/slurmd.pid
SlurmctldLogFile=$d/slurmctld.log
SlurmdLogFile=$d/slurmd.log
SlurmctldPort=$port
SlurmdPort=$((port + 1))
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
NodeName=$host CPUs=$(nproc) State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$d/slurm.conf
slurmctld -f "$SLURM_CONF" && slurmd -f "$SLURM_CONF" || { echo "FAIL slurm did not start"; tail -5 "$d"/*.log; exit 1; }
for _ in $(seq 30); do sinfo -h -o %t 2>/dev/null | grep -q idle && break; sleep 1; done
sinfo -h -o %t | grep -q idle || { echo "FAIL the node never became idle: $(sinfo 2>&1)"; tail -5 "$d/slurmctld.log"; exit 1; }

sweep=$src/examples/sweeps/tiny.toml
"$bin" sweep "$sweep" --out "$d/local" --jobs 2 --cache-dir "$d/cache" 2>/dev/null || { echo "FAIL local sweep"; exit 1; }
"$bin" sweep "$sweep" --out "$d/slurm" --emit slurm --cache-dir "$d/cache" >/dev/null || { echo "FAIL --emit slurm"; exit 1; }
timeout 600 sbatch --wait "$d/slurm/sweep.sbatch" || { echo "FAIL sbatch"; cat "$d"/slurm/cases/slurm-*.log; exit 1; }
"$bin" sweep "$sweep" --out "$d/slurm" --gather 2>/dev/null || { echo "FAIL gather: not every case ran"; exit 1; }
cmp "$d/slurm/results.csv" "$d/local/results.csv" || { echo "FAIL the Slurm results.csv differs from the local one"; exit 1; }
echo "slurm route: $(ls "$d"/slurm/cases/slurm-*.log | wc -l) array tasks, results.csv identical to the local sweep"
