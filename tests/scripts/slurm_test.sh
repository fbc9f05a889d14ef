#!/usr/bin/env bash
# The Slurm backend against a real Slurm: munged, slurmctld and slurmd started here on localhost ports
# with a generated slurm.conf and all state in WORKDIR, a small sweep run through sbatch --array and
# compared with the local backend, a cancelled array task turned into failed rows with Slurm's state,
# --resume resubmitting only missing cells. Every daemon started is stopped by its pid.
#   slurm_test.sh VOBENCH WORKDIR
set -euo pipefail
vobench=$1 work=$2
skip() { echo "SKIPPED: $*"; exit 77; }

[ "$(id -u)" -eq 0 ] || skip "needs root to start slurmd (run make test as root, as CI does)"
need=()
for p in slurmctld slurmd slurm-client munge; do
  dpkg-query -W -f='${Status}' "$p" 2> /dev/null | grep -q "install ok installed" || need+=("$p")
done
if [ ${#need[@]} -gt 0 ]; then
  echo "installing ${need[*]}"
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${need[@]}" > /dev/null 2>&1 ||
    { DEBIAN_FRONTEND=noninteractive apt-get update -qq > /dev/null 2>&1 &&
      DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${need[@]}" > /dev/null 2>&1; } ||
    skip "could not install ${need[*]} from Debian"
fi

rm -rf "$work" && mkdir -p "$work"/{state,spool,log,munge} && cd "$work"
chmod 711 munge
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill "$pid" 2> /dev/null || true; done
  for pid in "${pids[@]}"; do
    for _ in $(seq 50); do kill -0 "$pid" 2> /dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2> /dev/null || true
  done
}
trap cleanup EXIT

mungekey -c -k munge/munge.key -b 1024 > /dev/null 2>&1 || dd if=/dev/urandom of=munge/munge.key bs=128 count=1 2> /dev/null
chmod 400 munge/munge.key
munged -F -f --key-file="$work/munge/munge.key" --socket="$work/munge/munge.sock" --pid-file="$work/munge/munged.pid" \
  --seed-file="$work/munge/seed" --log-file="$work/log/munged.log" > log/munged.out 2>&1 &
pids+=($!)

free_port() { python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }
node=$(hostname -s)
ctld_port=$(free_port) d_port=$(free_port)
cat > slurm.conf << CONF
ClusterName=vobench-test
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$d_port
AuthType=auth/munge
AuthInfo=socket=$work/munge/munge.sock
CredType=cred/munge
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
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
MinJobAge=600
NodeName=$node NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=vobench Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$work/slurm.conf
for _ in $(seq 50); do [ -S munge/munge.sock ] && break; sleep 0.1; done
slurmctld -D -f "$SLURM_CONF" > log/slurmctld.out 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" -N "$node" > log/slurmd.out 2>&1 &
pids+=($!)
up=0
for _ in $(seq 60); do
  if sinfo -h -o %T 2> /dev/null | grep -q idle; then up=1; break; fi
  sleep 0.5
done
if [ $up -eq 0 ]; then
  tail -n 20 log/*.out log/*.log 2> /dev/null || true
  skip "the Slurm daemons did not come up on this machine"
fi
echo "slurmctld and slurmd up on $node (ports $ctld_port, $d_port)"

export VOBENCH_PLUGIN_PATH=
"$vobench" -q synth --sensor kinect1 --trajectory speed2 --frames 8 --out seq > /dev/null
cat > sweep.yaml << 'YAML'
name: slurm vs local
datasets:
  - {name: tiny, reader: tum, path: seq}
algorithms:
  - {plugin: put_vo}
  - {plugin: orb_matching}
  - {plugin: constant_pose}
repeats: 2
YAML

echo "== the same sweep, local and through sbatch --array"
"$vobench" -q run sweep.yaml --out local -j 2 > local.log 2>&1
"$vobench" -q run sweep.yaml --out slurm --backend slurm --chunk 2 --poll 1 > slurm.log 2>&1 || { cat slurm.log; exit 1; }
python3 - << 'PY'
import json, filecmp
cells = json.load(open("local/cells.json"))
assert [c["id"] for c in cells] == [c["id"] for c in json.load(open("slurm/cells.json"))]
for c in cells:
    i = c["id"]
    assert filecmp.cmp(f"local/runs/{i}/trajectory.txt", f"slurm/runs/{i}/trajectory.txt", shallow=False), i
    a, b = json.load(open(f"local/runs/{i}/run.json")), json.load(open(f"slurm/runs/{i}/run.json"))
    assert a["status"] == b["status"] == "ok" and a["evaluation"] == b["evaluation"], i
jobs = json.load(open("slurm/slurm/jobs.json"))
assert len(jobs) == 1 and jobs[0]["tasks"] == 3 and jobs[0]["collected"], jobs
print(f"{len(cells)} cells: the Slurm backend's results equal the local backend's")
PY
test -s slurm/report.html

echo "== a cancelled array task becomes failed rows with Slurm's state; --detach, collect, --resume"
out=$("$vobench" -q run sweep.yaml --out detached --backend slurm --chunk 1 --array-limit 1 --detach)
job=$(echo "$out" | sed -n 's/^Submitted Slurm job \([0-9]*\).*/\1/p')
[ -n "$job" ] || { echo "FAIL: no job id in: $out"; exit 1; }
# One task at a time: once the first cell is done, cancel the job; the tasks still queued are CANCELLED.
for _ in $(seq 300); do [ "$(ls detached/runs 2> /dev/null | grep -vc '^\.' || true)" -ge 1 ] && break; sleep 0.1; done
scancel "$job"
"$vobench" -q collect detached --poll 1 > collect.log 2>&1 || true
python3 - "$job" << 'PY'
import json, sys
job = sys.argv[1]
lb = json.load(open("detached/leaderboard.json"))
fails = lb["failures"]
cells = sum(len(e["cells"]) for e in lb["entries"])
assert cells == 6 and 1 <= len(fails) <= 5, (cells, fails)
for f in fails:
    assert f"slurm array task {job}_" in f["reason"] and "CANCELLED" in f["reason"], f["reason"]
print(f"{len(fails)} cells of cancelled tasks are failed rows, e.g.: {fails[0]['reason']}")
PY
victim=$(python3 -c 'import json; print(json.load(open("detached/leaderboard.json"))["failures"][0]["id"])')
rm -rf "detached/runs/$victim"
"$vobench" -q run sweep.yaml --out detached --backend slurm --resume --poll 1 > resume.log 2>&1 || true
test "$(ls detached/slurm/batch-*.txt | wc -l)" -eq 2
newest=$(ls -t detached/slurm/batch-*.txt | head -1)
test "$(wc -l < "$newest")" -eq 1 || { echo "FAIL: --resume resubmitted $(wc -l < "$newest") cells, expected 1"; cat "$newest"; exit 1; }
test "$(cat "$newest")" = "$victim"
test -s "detached/runs/$victim/run.json"
echo "--resume resubmitted only the missing cell"
