#!/usr/bin/env bash
# Batch on a real Slurm: starts munged, slurmctld and slurmd on localhost (loopback only, config,
# key, state and logs in a temporary folder, no system file touched), runs the batch test dataset
# (tests/batch/make_test_dataset.sh: 6 phantoms + 1 broken case) once locally and once as a Slurm
# job array (`jawmesh batch --slurm --submit`), waits for the array with a bounded timeout, and
# checks with `jawmesh batch --status` that the 6 cases are ok with outputs identical to the local
# batch's (same files, sizes and checksums; the timed records run.json and report.json's "seconds"
# aside) and that the broken case is reported with the reader's message. Everything it started is
# stopped at the end, also on failure.
#   usage: tests/slurm/slurm_batch_test.sh [jawmesh binary (default build/cli/jawmesh)]
# Needs root (slurmd runs jobs as root here) and the Debian packages slurmctld, slurmd, munge
# (`bash quickstart.sh slurm-test` installs them and builds first). About 3-5 minutes on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/../.."
jawmesh=$(realpath "${1:-build/cli/jawmesh}")
timeout_s=${JAWMESH_SLURM_TIMEOUT:-1200}
[ "$(id -u)" -eq 0 ] || { echo "slurm test: must run as root (slurmd starts the jobs)" >&2; exit 2; }
for tool in munged slurmctld slurmd sbatch squeue python3; do
  command -v "$tool" > /dev/null || { echo "slurm test: $tool not found (bash quickstart.sh slurm-test installs it)" >&2; exit 2; }
done

work=$(mktemp -d /tmp/jawmesh-slurm-test.XXXXXX)
chmod 700 "$work"
pids=()
cleanup() {
  local status=$?
  for pidfile in "$work"/run/slurmd.pid "$work"/run/slurmctld.pid "$work"/munge/munged.pid; do
    [ -f "$pidfile" ] && kill "$(cat "$pidfile")" 2> /dev/null || true
  done
  sleep 1
  if [ $status -ne 0 ]; then
    echo "slurm test FAILED; daemon logs:" >&2
    tail -n 30 "$work"/run/*.log "$work"/munge/munged.log 2> /dev/null >&2 || true
    echo "work folder kept: $work" >&2
  else
    rm -rf "$work"
  fi
}
trap cleanup EXIT

free_port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])'; }

echo "== munge"
mkdir -p "$work/munge" "$work/run" "$work/state" "$work/spool"
chmod 700 "$work/munge"
dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$work/munge/munge.key"
munged --force --key-file="$work/munge/munge.key" --socket="$work/munge/munge.socket" \
  --pid-file="$work/munge/munged.pid" --log-file="$work/munge/munged.log" --seed-file="$work/munge/munged.seed"

echo "== slurm (config in $work/slurm.conf)"
cpus=$(nproc)
memory_mb=$(awk '/MemTotal/ {print int($2 / 1024 * 0.8)}' /proc/meminfo)
cat > "$work/slurm.conf" <<CONF
ClusterName=jawmeshtest
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$work/munge/munge.socket
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/run/slurmctld.pid
SlurmdPidFile=$work/run/slurmd.pid
SlurmctldLogFile=$work/run/slurmctld.log
SlurmdLogFile=$work/run/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SlurmdParameters=config_overrides
ReturnToService=2
MpiDefault=none
NodeName=localhost NodeHostname=$(hostname) NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$memory_mb State=UNKNOWN
PartitionName=batch Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$work/slurm.conf"
slurmctld -i
slurmd -N localhost
for _ in $(seq 60); do
  sinfo -h -o %T 2> /dev/null | grep -qE '^idle' && break
  sleep 1
done
sinfo -h -o %T | grep -qE '^idle' || { echo "slurm test: the node did not come up: $(sinfo 2>&1)" >&2; exit 1; }
sinfo

echo "== dataset"
dataset="$work/dataset"
bash tests/batch/make_test_dataset.sh "$jawmesh" "$dataset"
config=tests/batch/fast_phantom.json

echo "== local batch"
set +e
"$jawmesh" batch "$dataset" -o "$work/local" --config "$config"
local_status=$?
set -e
[ $local_status -ne 0 ] || { echo "slurm test: the local batch must fail (broken case)" >&2; exit 1; }

echo "== slurm batch"
start=$(date +%s)
submitted=$("$jawmesh" batch "$dataset" -o "$work/slurm" --config "$config" --slurm --cpus 1 --time 30 --submit)
echo "$submitted"
job=$(echo "$submitted" | sed -n 's/^submitted job \([0-9]*\).*/\1/p')
[ -n "$job" ] || { echo "slurm test: no job id in: $submitted" >&2; exit 1; }
while [ -n "$(squeue -h -j "$job" 2> /dev/null)" ]; do
  if [ $(( $(date +%s) - start )) -gt "$timeout_s" ]; then
    echo "slurm test: job $job still running after ${timeout_s} s" >&2
    squeue >&2
    scancel "$job" || true
    exit 1
  fi
  sleep 5
done
echo "array finished in $(( $(date +%s) - start )) s"

set +e
"$jawmesh" batch --status "$work/slurm"
status_status=$?
set -e
[ $status_status -ne 0 ] || { echo "slurm test: --status must fail (broken case)" >&2; exit 1; }

echo "== compare"
python3 - "$work/local" "$work/slurm" "$job" <<'PY'
import json, os, sys
local, slurm, job = sys.argv[1], sys.argv[2], sys.argv[3]
def load(folder):
    return json.load(open(os.path.join(folder, "manifest.json")))
lm, sm = load(local), load(slurm)
assert lm["options_hash"] == sm["options_hash"], "different options"
def by_name(m):
    return {(t["case"], t["jaw"]): t for t in m["tasks"]}
lt, st = by_name(lm), by_name(sm)
assert lt.keys() == st.keys(), (lt.keys(), st.keys())
ok = [k for k, t in st.items() if t["status"] == "ok"]
failed = [k for k, t in st.items() if t["status"] == "failed"]
assert sorted(ok) == [("Patient_%d" % k, "mandible") for k in range(1, 7)], st
assert failed == [("Patient_7", "mandible")], failed
broken = st[("Patient_7", "mandible")]
assert "mandible.stl" in broken["error"], broken["error"]
assert broken["error"] == lt[("Patient_7", "mandible")]["error"], (broken["error"], lt[("Patient_7", "mandible")]["error"])
timed = {"run.json", "report/report.json"}  # records with timings; report.json is compared without them
for key in ok:
    t = st[key]
    assert t["log"] == "logs/slurm-%s_%d.log" % (job, list(st).index(key)), t["log"]
    assert os.path.getsize(os.path.join(slurm, t["log"])) > 0, t["log"]
    files, reports = [], []
    for folder in (local, slurm):
        jaw_dir = os.path.join(folder, key[0], key[1])
        stamp = json.load(open(os.path.join(jaw_dir, "outputs.json")))
        files.append({f["path"]: (f["bytes"], f["checksum"]) for f in stamp["files"] if f["path"] not in timed})
        report = json.load(open(os.path.join(jaw_dir, "report", "report.json")))
        report.pop("seconds")
        reports.append(report)
    assert files[0] == files[1], "%s: outputs differ between the local and the Slurm batch" % (key,)
    assert reports[0] == reports[1], "%s: evaluation reports differ" % (key,)
    assert any(p.endswith(".msh") for p in files[0]), files[0]
print("slurm test: 6 cases ok with outputs identical to the local batch; broken case reported: " + broken["error"])
PY
