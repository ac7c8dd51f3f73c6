#!/usr/bin/env bash
# SPDX-License-Identifier: MPL-2.0
# slurm_real.sh SWARF FIXTURES -- `swarf simulate` under a real one-node Slurm
# The test writes its own slurm.conf in a temporary folder, starts
# munged, slurmctld and slurmd itself (ports chosen free on 127.0.0.1), then
#   - `srun -n 2 --mpi=pmix swarf simulate` and an `sbatch` script running the
#     same: each grid identical voxel for voxel to one process (same_grid.py,
#     pyopenvdb), one summary printed;
#   - plain `srun -n 2 swarf simulate` (Slurm's MpiDefault=none: two
#     independent processes): refused by every task, exit 2, the fix named,
#     nothing written;
# and stops every daemon it started by its process id. Exits 77 (skipped) where
# Slurm or munge is not installed (tools/run installs slurm-wlm and munge) or
# when not root (slurmd launches the tasks as their user).
set -u
swarf=$1 fx=$2
here=$(cd "$(dirname "$0")" && pwd)
for b in munged slurmctld slurmd srun sbatch sinfo; do
  command -v "$b" > /dev/null || { echo "SKIPPED: $b not found (apt-get install slurm-wlm munge)"; exit 77; }
done
[ "$(id -u)" -eq 0 ] || { echo "SKIPPED: needs root (slurmd starts the tasks)"; exit 77; }
/usr/bin/python3 -c "import pyopenvdb" 2> /dev/null ||
  { echo "SKIPPED: pyopenvdb not found (apt-get install python3-openvdb)"; exit 77; }

T=$(mktemp -d)
chmod 755 "$T"
pids=()
stop() {
  for p in "${pids[@]}"; do kill "$p" 2> /dev/null; done
  if [ -f "$T/munged.pid" ]; then
    pids+=("$(cat "$T/munged.pid")")
    kill "${pids[-1]}" 2> /dev/null
  fi
  for p in "${pids[@]}"; do
    for _ in $(seq 50); do kill -0 "$p" 2> /dev/null || break; sleep 0.1; done
  done
  rm -rf "$T"
}
trap stop EXIT
fail=0
check() { # check COND-EXIT-STATUS WHAT
  if [ "$1" -eq 0 ]; then echo "ok   $2"; else echo "FAIL $2"; fail=1; fi
}

# munge: a key of our own, a socket in the folder
head -c 128 /dev/urandom > "$T/munge.key" && chmod 600 "$T/munge.key"
munged -f --socket="$T/munge.sock" --key-file="$T/munge.key" --pid-file="$T/munged.pid" \
  --log-file="$T/munged.log" --seed-file="$T/munged.seed" ||
  { echo "FAIL: munged did not start"; cat "$T/munged.log"; exit 1; }

read -r p1 p2 < <(/usr/bin/python3 -c "
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(('127.0.0.1', 0))
print(*[x.getsockname()[1] for x in s])")
host=$(hostname)
mkdir -p "$T/state" "$T/spool"
cat > "$T/slurm.conf" << EOF
ClusterName=swarftest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$p1
SlurmdPort=$p2
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$T/munge.sock
CredType=cred/munge
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool
SlurmctldPidFile=$T/slurmctld.pid
SlurmdPidFile=$T/slurmd.pid
SlurmctldLogFile=$T/slurmctld.log
SlurmdLogFile=$T/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
SchedulerType=sched/builtin
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
NodeName=$host NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=swarf Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$T/slurm.conf
slurmctld -D > "$T/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D > "$T/slurmd.out" 2>&1 &
pids+=($!)
up=0
for _ in $(seq 100); do
  if sinfo -h -o %t 2> /dev/null | grep -q idle; then up=1; break; fi
  sleep 0.2
done
if [ $up -eq 0 ]; then
  echo "FAIL: the node did not come up"; tail -5 "$T"/slurm*.log "$T"/*.out; exit 1
fi
echo "slurm: one node ($host) up on 127.0.0.1:$p1/$p2"

job=("$fx/demo.ngc" --stock box:0,0,-20,80,60,0 --tool T1=flat,D6,L24 --tool T2=ball,D3.175,L20
  --voxel 0.4)
"$swarf" simulate "${job[@]}" --quiet --out "$T/one.vdb" || { echo "FAIL: the one-process run"; exit 1; }

timeout 300 srun -n 2 --mpi=pmix "$swarf" simulate "${job[@]}" --out "$T/srun.vdb" \
  > "$T/srun.out" 2> "$T/srun.err"
check $? "srun -n 2 --mpi=pmix: exit 0"
check "$([ "$(grep -c '^  wrote ' "$T/srun.out")" -eq 1 ]; echo $?)" "srun -n 2 --mpi=pmix: one summary"
/usr/bin/python3 "$here/same_grid.py" "$T/one.vdb" "$T/srun.vdb"
check $? "srun -n 2 --mpi=pmix: the grid is one process's, voxel for voxel"

cat > "$T/job.sh" << EOF
#!/bin/sh
#SBATCH -n 2
srun --mpi=pmix $swarf simulate ${job[*]} --quiet --out $T/sbatch.vdb
EOF
timeout 300 sbatch --wait -o "$T/sbatch.out" "$T/job.sh" > /dev/null
check $? "sbatch (srun --mpi=pmix inside): exit 0"
/usr/bin/python3 "$here/same_grid.py" "$T/one.vdb" "$T/sbatch.vdb"
check $? "sbatch: the grid is one process's, voxel for voxel"

timeout 300 srun -n 2 "$swarf" simulate "${job[@]}" --out "$T/plain.vdb" > "$T/plain.out" \
  2> "$T/plain.err"
rc=$?
check "$([ $rc -ne 0 ]; echo $?)" "plain srun -n 2 (no PMI): refused (srun exit $rc)"
check "$([ "$(grep -c 'one of 2 tasks of a Slurm step.*srun --mpi=pmix' "$T/plain.err")" -eq 2 ]; echo $?)" \
  "plain srun -n 2: each task names the fix"
check "$([ ! -e "$T/plain.vdb" ]; echo $?)" "plain srun -n 2: nothing written"
[ $fail -eq 0 ] || { echo "srun's stderr:"; cat "$T/srun.err" "$T/plain.err"; }
exit $fail
