#!/usr/bin/env bash
# A Slurm job array on this host: munged, slurmctld and slurmd (Debian's munge and slurm-wlm) are
# started by this test with a private key, socket, slurm.conf and state under a temp dir, inside a
# network namespace of its own (only lo, so the daemons, which bind the wildcard address, are
# reachable on loopback only and never clash with a system-wide Slurm). Each of 3 array tasks runs
# `netmc sweep --shard K/3`; `netmc sweep merge` joins the parts, which must equal (cmp) the
# unsharded sweep of the same grid.
# Usage: slurm_array.sh BUILD_DIR
set -euo pipefail

build=$(cd "${1:?usage: slurm_array.sh BUILD_DIR}" && pwd)
netmc=$build/client/netmc
grid=(--delay-max 1ms:8ms:4 --seeds 1..3 --iterations 3)
tasks=3

if [[ -z ${NETMC_SLURM_NETNS:-} ]]; then
  [[ $(id -u) -eq 0 ]] || { echo "skipped: needs root (munged, slurmctld, slurmd)"; exit 77; }
  for t in munged slurmctld slurmd sbatch squeue sinfo scontrol scancel ip unshare; do
    command -v "$t" >/dev/null ||
      { echo "skipped: $t not found (apt-get install slurm-wlm munge iproute2)"; exit 77; }
  done
  [[ -x $netmc ]] || { echo "FAIL: $netmc not built"; exit 1; }
  unshare --net true 2>/dev/null ||
    { echo "skipped: cannot make a network namespace (unshare --net)"; exit 77; }
  # Same process (unshare execs), now in a network namespace of its own.
  NETMC_SLURM_NETNS=1 exec unshare --net -- bash "$0" "$build"
fi
ip link set lo up
# glibc's getaddrinfo(AF_INET, AI_ADDRCONFIG), which Slurm uses, finds nothing while 127.0.0.1 is
# the only IPv4 address: a second loopback address on lo (still only inside this namespace).
ip addr add 127.0.0.2/8 dev lo

tmp=$(mktemp -d "${TMPDIR:-/tmp}/netmc-slurm.XXXXXX")
chmod 700 "$tmp"
myns=$(readlink /proc/$$/ns/net)
declare -A pids=()   # name -> pid of every daemon started here
jobid=

# Pids in this test's network namespace other than this shell: daemons, job steps, tasks.
ours() {
  local d p ns
  for d in /proc/[0-9]*; do
    p=${d#/proc/}
    [[ $p == "$$" || $p == "$BASHPID" ]] && continue
    ns=$(readlink "$d/ns/net" 2>/dev/null) || continue
    [[ $ns == "$myns" ]] || continue
    kill -0 "$p" 2>/dev/null || continue # gone since (e.g. the readlink above)
    echo "$p"
  done
}

dump_logs() {
  local f
  for f in "$tmp"/log/* "$tmp"/job/part-*.log; do
    [[ -f $f ]] || continue
    echo "---- ${f#"$tmp"/} (last 60 lines)"
    tail -n 60 "$f"
  done
}

stop_pid() {   # stop_pid NAME: SIGTERM, up to 15 s, then SIGKILL; reap it
  local pid=${pids[$1]:-} i
  [[ -n $pid ]] || return 0
  kill -TERM "$pid" 2>/dev/null || true
  for ((i = 0; i < 150; i++)); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
  kill -KILL "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
}

cleanup() {
  local rc=$? i jobs
  local -a left=()
  trap - EXIT
  set +e
  stop_pid sbatch
  # Every job of this private controller is ours: cancel them (job steps end with them).
  if [[ -n ${pids[slurmctld]:-} ]] && kill -0 "${pids[slurmctld]}" 2>/dev/null; then
    jobs=$(timeout 10 squeue -h -o %A 2>/dev/null)
    if [[ -n $jobs ]]; then
      # shellcheck disable=SC2086 # one job id a word
      timeout 20 scancel $jobs >/dev/null 2>&1
      for ((i = 0; i < 100; i++)); do
        [[ -z $(timeout 10 squeue -h -o %A 2>/dev/null) ]] && break
        sleep 0.2
      done
    fi
  fi
  stop_pid slurmd
  stop_pid slurmctld
  stop_pid munged
  for ((i = 0; i < 50; i++)); do mapfile -t left < <(ours); ((${#left[@]})) || break; sleep 0.2; done
  if ((${#left[@]})); then
    echo "FAIL: processes this test started are left:"
    for i in "${left[@]}"; do ps -o pid=,args= -p "$i"; done
    for i in "${left[@]}"; do kill -KILL "$i" 2>/dev/null; done
    rc=1
  fi
  if [[ $rc -ne 0 && $rc -ne 77 ]]; then dump_logs; fi
  rm -rf "$tmp"
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

fail() { echo "FAIL: $*"; exit 1; }

# munged: its own key, socket, pid, log and seed files.
mkdir -m 700 "$tmp/munge" "$tmp/log" "$tmp/state" "$tmp/spool" "$tmp/job"
dd if=/dev/urandom of="$tmp/munge/munge.key" bs=1 count=1024 status=none
chmod 600 "$tmp/munge/munge.key"
socket=$tmp/munge/munge.socket
munged -F --force --socket="$socket" --key-file="$tmp/munge/munge.key" \
  --pid-file="$tmp/munge/munged.pid" --log-file="$tmp/log/munged.log" \
  --seed-file="$tmp/munge/munged.seed" >>"$tmp/log/munged.log" 2>&1 &
pids[munged]=$!
for ((i = 0; i < 100; i++)); do [[ -S $socket ]] && break; sleep 0.1; done
[[ -S $socket ]] || fail "munged did not create its socket"

node=$(hostname -s)
port=$((20000 + RANDOM % 30000))
export SLURM_CONF=$tmp/slurm.conf
: >"$tmp/plugstack.conf"
cat >"$SLURM_CONF" <<EOF
ClusterName=netmc
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
AuthInfo=socket=$socket
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/log/slurmctld.log
SlurmdLogFile=$tmp/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
MailProg=/bin/true
PlugStackConfig=$tmp/plugstack.conf
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
NodeName=$node NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF

slurmctld -D -i -f "$SLURM_CONF" >>"$tmp/log/slurmctld.out" 2>&1 &
pids[slurmctld]=$!
slurmd -D -N "$node" -f "$SLURM_CONF" >>"$tmp/log/slurmd.out" 2>&1 &
pids[slurmd]=$!

state=
for ((i = 0; i < 120; i++)); do
  for d in slurmctld slurmd; do kill -0 "${pids[$d]}" 2>/dev/null || fail "$d exited"; done
  state=$(timeout 10 sinfo -h -n "$node" -o %t 2>/dev/null || true)
  [[ $state == idle ]] && break
  sleep 0.5
done
[[ $state == idle ]] || fail "node $node not idle after 60 s (state '${state}')"

# The recipe (docs): one shard per array task, then netmc sweep merge.
cat >"$tmp/job/sweep.sbatch" <<EOF
#!/bin/bash
#SBATCH --array=1-$tasks
#SBATCH --output=part-%a.log
netmc sweep ${grid[*]} -q --threads 1 \\
    --shard "\${SLURM_ARRAY_TASK_ID}/$tasks" --csv "part-\${SLURM_ARRAY_TASK_ID}.csv"
EOF
export PATH=$build/client:$PATH
cd "$tmp/job"
# In the background, so that a signal to this test is handled at once (wait returns).
timeout 300 sbatch --parsable --wait --chdir="$tmp/job" sweep.sbatch >"$tmp/sbatch.out" 2>&1 &
pids[sbatch]=$!
src=0
wait "${pids[sbatch]}" || src=$?
unset 'pids[sbatch]'
out=$(<"$tmp/sbatch.out")
jobid=$(sed -n '1s/^\([0-9][0-9]*\).*/\1/p' <<<"$out")
[[ $src -eq 0 ]] || fail "sbatch --wait exited $src: $out"
[[ -n $jobid ]] || fail "no job id from sbatch: $out"

parts=()
for ((k = 1; k <= tasks; k++)); do
  [[ -s part-$k.csv ]] || fail "array task $k wrote no part-$k.csv"
  parts+=("part-$k.csv")
done
netmc sweep merge "${parts[@]}" -o merged.csv >/dev/null
netmc sweep "${grid[@]}" -q --csv whole.csv >/dev/null
if cmp merged.csv whole.csv; then
  echo "slurm: job $jobid, $tasks array tasks, merged = unsharded ($(($(wc -l <whole.csv) - 1)) rows)"
else
  diff whole.csv merged.csv | head -20
  fail "merged parts differ from the unsharded sweep"
fi
