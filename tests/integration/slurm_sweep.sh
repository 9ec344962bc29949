#!/usr/bin/env bash
# slurm_sweep.sh CBTL DOMAINS — a sweep through a real SLURM cluster: a private single-node cluster (munged,
# slurmctld and slurmd on this machine, Debian's slurm-wlm and munge, with their own socket, ports, state and logs
# under a temporary folder) runs `cbtl sweep --emit-slurm`'s job array with sbatch; `--collect` then gives exactly
# the tables and trial files of a local run. Skips (exit 77) only where the cluster cannot start: not root, the
# packages missing, or slurmd/slurmctld refusing to run here (their logs are printed).
set -u
cbtl=$(realpath "$1")
domains=$(realpath "$2")
skip() { echo "SKIPPED: $*"; exit 77; }
[ "$(id -u)" = 0 ] || skip "the SLURM daemons need root (run make test as root, as CI does)"
for tool in munged munge slurmctld slurmd sbatch sinfo scontrol squeue; do
  command -v "$tool" >/dev/null || [ -x "/usr/sbin/$tool" ] || skip "$tool is not installed (scripts/install-deps.sh installs slurm-wlm and munge)"
done
[ -r /etc/munge/munge.key ] || skip "no munge key at /etc/munge/munge.key (the munge package makes one)"

work=$(mktemp -d /tmp/cbtl-slurm.XXXXXX)
chmod 755 "$work"
export SLURM_CONF=$work/slurm.conf
cleanup() {
  scontrol shutdown >/dev/null 2>&1
  sleep 1
  for pidfile in "$work/slurmd.pid" "$work/slurmctld.pid"; do
    [ -f "$pidfile" ] && kill "$(cat "$pidfile")" 2>/dev/null
  done
  /usr/sbin/munged --stop --socket="$work/munge/munge.sock" >/dev/null 2>&1
  rm -rf "$work"
}
trap cleanup EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
logs() { for f in "$work"/log/*.log; do echo "--- $f"; tail -n 20 "$f"; done; }

# munged on a private socket, with the machine's key.
mkdir -p "$work/munge" "$work/log" "$work/state" "$work/spool"
chmod 700 "$work/munge"
/usr/sbin/munged --force --socket="$work/munge/munge.sock" --key-file=/etc/munge/munge.key \
  --pid-file="$work/munge/munged.pid" --log-file="$work/log/munged.log" --seed-file="$work/munge/seed" ||
  skip "munged does not start: $(tail -n 5 "$work/log/munged.log" 2>/dev/null)"

# Ports of our own (another cluster on this machine keeps its own), from the process id.
port=$((20000 + ($$ % 20000) * 2))
host=$(hostname)
cpus=$(nproc)
cat >"$SLURM_CONF" <<CONF
ClusterName=cbtltest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$work/munge/munge.sock
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=2000 State=UNKNOWN
PartitionName=cbtl Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
/usr/sbin/slurmctld -i >/dev/null 2>&1 || { logs; skip "slurmctld does not start here"; }
/usr/sbin/slurmd >/dev/null 2>&1 || { logs; skip "slurmd does not start here"; }
idle=0
for _ in $(seq 60); do
  if sinfo -h -o %T 2>/dev/null | grep -qx idle; then idle=1; break; fi
  sleep 0.5
done
[ $idle = 1 ] || { sinfo; logs; skip "the node never became idle"; }

cat >"$work/sweep.json" <<JSON
{
  "name": "slurmtest",
  "defaults": {"steps": 200, "eval-every": 100, "eval-tasks": 2},
  "experiments": [
    {"name": "cooking", "program": "$domains/cooking/cooking.cbtl",
     "approaches": ["cbtl", "no-personalization"], "seeds": "0..1"},
    {"name": "replan", "program": "$domains/cooking/cooking.cbtl", "approaches": ["cbtl"], "seeds": "0..1",
     "options": {"replan": true, "unsatisfiable-stock": 0.5}}
  ],
  "plots": [{"out": "cooking.png", "results": ["cooking"]}],
  "slurm": {"cpus-per-task": 1, "mem": "500M", "time": "00:10:00", "array-limit": 2, "trials-per-task": 2}
}
JSON
cd "$work" || exit 1
"$cbtl" sweep sweep.json --out local --jobs 2 -q >local.txt 2>&1 || fail "the local sweep exited $?: $(tail -5 local.txt)"
"$cbtl" sweep sweep.json --out cluster --emit-slurm >emit.txt || fail "--emit-slurm exited $?"
grep -qxF "#SBATCH --array=0-2%2" cluster/slurmtest.sbatch || fail "the array: $(grep array cluster/slurmtest.sbatch)"
if ! timeout 300 sbatch --wait --quiet cluster/slurmtest.sbatch >sbatch.txt 2>&1; then
  fail "the job array failed: $(cat sbatch.txt)"
  squeue
  logs
  for f in cluster/slurm/*.log; do echo "--- $f"; cat "$f"; done
fi
[ "$(ls cluster/slurm/*.log 2>/dev/null | wc -l)" = 3 ] || fail "expected 3 task logs: $(ls cluster/slurm)"
"$cbtl" sweep sweep.json --out cluster --collect >cluster.txt 2>&1 || fail "--collect exited $?: $(tail -5 cluster.txt)"
for f in cooking/summary.csv replan/summary.csv $(cd local && find . -path '*/seed*/*' -type f \
  \( -name '*.csv' -o -name 'profile.json' -o -name 'complete.json' -o -name 'config.json' \) | sort); do
  cmp -s "local/$f" "cluster/$f" || fail "the cluster's $f differs from the local run's"
done
[ -s cluster/cooking.png ] || fail "--collect drew no figure"

[ "$failures" = 0 ] && echo "slurm_sweep: all checks passed ($(grep -c . cluster/cooking/summary.csv) summary rows equal)"
exit $((failures > 0))
