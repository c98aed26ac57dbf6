# shellcheck shell=bash
# The one way tests start, wait for and stop processes, on this machine's network (host "-") or in a
# namespaced host of lab.sh. lib.sh sources it; its `start NAME CMD...` is `lab_start NAME - -- CMD...`.
#   lab_start LOGNAME HOST [--monotonic SECONDS] -- CMD...
#                             starts CMD in the background in HOST's network namespace (HOST "-" =
#                             the machine's own network namespace; any other host and --monotonic
#                             need lab.sh), with --monotonic inside a new time namespace whose
#                             CLOCK_MONOTONIC is the host's + SECONDS (integer, may be negative; the
#                             kernel refuses offsets that would put the clock below 0 or above 2^62
#                             ns (~146 years): reported with a clear message and status 1;
#                             CLOCK_BOOTTIME and /proc/uptime are not shifted). Output (stdout and
#                             stderr) in $tmp/LOGNAME.log. CMD runs in a session of its own
#                             (setsid): the session id is the pid lab_pid prints, and lab_stop,
#                             lab_kill and the cleanup signal the whole session. A LOGNAME may be
#                             started again once its session is over (its log starts anew).
#   lab_pid LOGNAME           prints the session leader's pid (ip netns exec and unshare exec or
#                             fork: with --monotonic the leader is `unshare`, CMD is its child).
#   lab_pids LOGNAME          prints the pids of all live processes of that session.
#   lab_kill LOGNAME [SIGNAL] sends SIGNAL (default KILL: a crash) to the whole session, no waiting.
#   lab_wait LOGNAME [SECONDS]
#                             waits (default 30 s) for the leader (so CMD) to exit; returns CMD's
#                             exit status, or 124 if it was still running after SECONDS.
#   lab_wait_log LOGNAME REGEX [SECONDS]
#                             waits (default 10 s) until $tmp/LOGNAME.log has a line matching the
#                             extended REGEX; on timeout prints the log to stderr and returns 1.
#   lab_stop LOGNAME          SIGTERM to the session, waits up to $LAB_STOP_GRACE (default 5)
#                             seconds for all its processes to end, then SIGKILL (with a message on
#                             stderr); reaps the leader. Returns 0 once the session is empty (1 if
#                             processes survive SIGKILL). CMD's status: lab_status LOGNAME.
#   lab_status LOGNAME        prints the leader's exit status once lab_wait/lab_stop reaped it
#                             (143 = ended by SIGTERM, 137 = SIGKILL).
#   lab_fail MESSAGE          FAIL: MESSAGE, each started process's state and log tail; exit 1.
#   lab_keep_logs             copy $tmp to $NETMC_KEEP_LOGS (if set) when the test ends.
#   lab_exec HOST [--monotonic SECONDS] -- CMD...
#                             runs CMD in the foreground in HOST's namespace; returns its status.
#   lab__stop_sessions        (the cleanup's first step, on exit) SIGTERM to every session started
#                             here, a common grace of $LAB_STOP_GRACE seconds, then SIGKILL: returns
#                             1 if a process had to be killed or survived (the test then fails:
#                             netmc's programs end on SIGTERM).

declare -A lab__pid=() lab__state=() lab__status=()
declare -A lab__inode=()  # lab.sh: namespace inode -> name (kept after deletion, for the final check)
lab__order=()             # LOGNAMEs in start order

lab__err() { echo "$*" >&2; return 1; }

# lab__command HOST MONO CMD...: fills the array lab__cmd with the full command line.
lab__command() {
  local host=$1 mono=$2 ns
  shift 2
  lab__cmd=()
  if [ "$host" != - ]; then
    declare -F lab_ns >/dev/null || { lab__err "lab: host '$host' needs lab.sh (source it after lib.sh)"; return 1; }
    ns=$(lab_ns "$host") || return 1
    lab__cmd+=(ip netns exec "$ns")
  fi
  if [ -n "$mono" ]; then
    [[ $mono =~ ^-?[0-9]+$ ]] || { lab__err "lab: --monotonic takes whole seconds, not '$mono'"; return 1; }
    declare -F lab_need_timens >/dev/null || { lab__err "lab: --monotonic needs lab.sh (source it after lib.sh)"; return 1; }
    lab_need_timens
    local err now
    if ! err=$(unshare --time --fork --monotonic "$mono" true 2>&1); then
      now=$(awk '{printf "%d", $1}' /proc/uptime)
      if [[ $err == *"out of range"* ]]; then
        lab__err "lab: the kernel refuses CLOCK_MONOTONIC offset $mono s: the clock in the new time" \
          "namespace must stay within [0, ~146 years]; the host's CLOCK_MONOTONIC is about $now s," \
          "so negative offsets must be >= -$now ($err)"
      else
        lab__err "lab: cannot make a time namespace with offset $mono s ($err)"
      fi
      return 1
    fi
    # --fork: offsets apply to children only; --kill-child: if unshare dies (SIGKILL), so does CMD.
    # unshare blocks SIGTERM/SIGINT itself, hence lab_stop signals the whole session.
    lab__cmd+=(unshare --time --fork --kill-child --monotonic "$mono" --)
  fi
  lab__cmd+=("$@")
}

# lab__parse_opts [--monotonic S] -- CMD...: options of lab_start / lab_exec into lab__mono;
# lab__nopts = how many words to shift to reach CMD.
lab__parse_opts() {
  lab__mono=""
  lab__nopts=0
  while [ $# -gt 0 ]; do
    case $1 in
      --monotonic) [ $# -ge 2 ] || { lab__err "lab: --monotonic needs SECONDS"; return 1; }
                   lab__mono=$2; shift 2; lab__nopts=$((lab__nopts + 2)) ;;
      --) lab__nopts=$((lab__nopts + 1)); shift
          [ $# -gt 0 ] || { lab__err "lab: no command after --"; return 1; }
          return 0 ;;
      *) lab__err "lab: unexpected '$1' (usage: ... HOST [--monotonic SECONDS] -- CMD...)"; return 1 ;;
    esac
  done
  lab__err "lab: missing -- CMD..."
  return 1
}

lab_start() {
  local log=${1:-} host=${2:-}
  [ $# -ge 2 ] || { lab__err "usage: lab_start LOGNAME HOST [--monotonic SECONDS] -- CMD..."; return 1; }
  shift 2
  [[ $log =~ ^[A-Za-z0-9_.-]+$ ]] || { lab__err "lab_start: bad LOGNAME '$log'"; return 1; }
  local again=0
  if [ -n "${lab__pid[$log]+x}" ]; then
    # A name is used again once its session is over (a restarted server): the old log goes.
    [ -z "$(lab__session_members "${lab__pid[$log]}")" ] || { lab__err "lab_start: $log is still running"; return 1; }
    again=1
  fi
  lab__parse_opts "$@" || return 1
  shift "$lab__nopts"
  lab__command "$host" "$lab__mono" "$@" || return 1
  # Without job control a background child is never a process-group leader, so setsid(1) calls
  # setsid() itself and execs: $! becomes the session (and process group) id.
  local monitor=0 pid
  case $- in *m*) monitor=1; set +m ;; esac
  setsid "${lab__cmd[@]}" >"$tmp/$log.log" 2>&1 </dev/null &
  pid=$!
  [ "$monitor" -eq 0 ] || set -m
  if [ "$again" -eq 1 ]; then
    lab__reap "$log"
    unset "lab__status[$log]"
  else
    lab__order+=("$log")
  fi
  lab__pid[$log]=$pid
  lab__state[$log]=running
  local i stat
  for ((i = 0; i < 200; i++)); do   # until setsid() happened (or the process is gone)
    { read -r stat <"/proc/$pid/stat"; } 2>/dev/null || break
    stat=${stat##*) }
    read -r _ _ _ stat _ <<<"$stat"
    [ "$stat" != "$pid" ] || break
    sleep 0.01
  done
}

lab_exec() {
  local host=${1:-}
  [ $# -ge 1 ] || { lab__err "usage: lab_exec HOST [--monotonic SECONDS] -- CMD..."; return 1; }
  shift
  lab__parse_opts "$@" || return 1
  shift "$lab__nopts"
  lab__command "$host" "$lab__mono" "$@" || return 1
  "${lab__cmd[@]}"
}

lab__known() { [ -n "${lab__pid[${1:-}]+x}" ] || { lab__err "lab: nothing started as '${1:-}'"; return 1; }; }
lab_pid() { lab__known "${1:-}" && echo "${lab__pid[$1]}"; }

# lab__members_of SID...: live (non-zombie) pids whose session is one of the SIDs.
lab__members_of() {
  ps -e -o pid=,sid=,stat= | awk -v s=" $* " 'index(s, " " $2 " ") && $3 !~ /^Z/ {print $1}'
}
lab__session_members() { lab__members_of "$1"; }
lab_pids() { lab__known "${1:-}" && lab__session_members "${lab__pid[$1]}"; }

# lab__signal_session SIGNAL SID...: to the process groups SID and every other member of the sessions.
lab__signal_session() {
  local sig=$1 sid p
  shift
  for sid in "$@"; do kill -s "$sig" -- "-$sid" 2>/dev/null || true; done
  for p in $(lab__members_of "$@"); do kill -s "$sig" "$p" 2>/dev/null || true; done
}

lab_kill() {
  lab__known "${1:-}" || return 1
  lab__signal_session "${2:-KILL}" "${lab__pid[$1]}"
}

lab__now_ms() { local t=${EPOCHREALTIME/[.,]/}; echo $((t / 1000)); }

lab__alive() {
  local s
  { read -r s <"/proc/$1/stat"; } 2>/dev/null || return 1
  s=${s##*) }
  [ "${s:0:1}" != Z ]
}

lab__reap() {
  local log=$1 st=0
  [ "${lab__state[$log]}" = running ] || return 0
  wait "${lab__pid[$log]}" 2>/dev/null || st=$?
  lab__status[$log]=$st
  lab__state[$log]=reaped
}

lab_wait() {
  lab__known "${1:-}" || return 1
  local log=$1 limit=${2:-30} pid end
  pid=${lab__pid[$log]}
  end=$(($(lab__now_ms) + limit * 1000))
  while lab__alive "$pid" && [ "$(lab__now_ms)" -lt "$end" ]; do sleep 0.05; done
  lab__alive "$pid" && return 124
  lab__reap "$log"
  return "${lab__status[$log]}"
}

lab_status() { lab__known "${1:-}" && echo "${lab__status[$1]:-running}"; }

lab_wait_log() {
  local log=${1:-} re=${2:-} limit=${3:-10} end
  end=$(($(lab__now_ms) + limit * 1000))
  while :; do
    grep -Eq -- "$re" "$tmp/$log.log" 2>/dev/null && return 0
    [ "$(lab__now_ms)" -lt "$end" ] || break
    sleep 0.05
  done
  echo "lab_wait_log: no line matching /$re/ in $log.log after $limit s:" >&2
  cat "$tmp/$log.log" >&2 2>/dev/null || true
  return 1
}

# lab_fail MESSAGE: prints FAIL: MESSAGE, then every lab_start'ed process's state (running, or
# its exit status: 143/137 = ended by SIGTERM/SIGKILL) and the last 10 lines of its log; exit 1.
lab_fail() {
  echo "FAIL: $*"
  local log st
  for log in "${lab__order[@]}"; do
    st=0
    lab_wait "$log" 2 || st=$?   # 2 s: a process may be shutting down
    if [ "$st" -eq 124 ]; then echo "--- $log: running"; else echo "--- $log: ended, exit status $st"; fi
    echo "--- $log.log (last 10 lines)"
    tail -n 10 "$tmp/$log.log"
  done
  exit 1
}

# lab_keep_logs: on exit, after the cleanup (the logs are complete then), copies $tmp to
# $NETMC_KEEP_LOGS if that is set.
lab_keep_logs() {
  # shellcheck disable=SC2016 # expanded when the cleanup evals it
  extra_cleanup+=('[ -z "${NETMC_KEEP_LOGS:-}" ] || { mkdir -p "$NETMC_KEEP_LOGS" && cp -r "$tmp"/. "$NETMC_KEEP_LOGS"/; }')
}

lab_stop() {
  lab__known "${1:-}" || return 1
  local log=$1 pid st=0
  pid=${lab__pid[$log]}
  lab__terminate "lab_stop: $log" "$pid" || st=$?
  lab__alive "$pid" || lab__reap "$log"
  [ "$st" -ne 2 ]
}

# lab__terminate LABEL SID...: SIGTERM to the sessions, up to $LAB_STOP_GRACE (default 5) seconds
# for all their processes to end, then SIGKILL (LABEL and the processes said on stderr). Returns 0
# if all ended on SIGTERM, 1 if some had to be killed, 2 if some survive SIGKILL (3 s).
lab__terminate() {
  local label=$1 grace=${LAB_STOP_GRACE:-5} left end i
  shift
  left=$(lab__members_of "$@")
  [ -n "$left" ] || return 0
  lab__signal_session TERM "$@"
  end=$(($(lab__now_ms) + grace * 1000))
  while :; do
    sleep 0.05
    left=$(lab__members_of "$@")
    [ -n "$left" ] && [ "$(lab__now_ms)" -lt "$end" ] || break
  done
  [ -n "$left" ] || return 0
  echo "$label: still running ${grace} s after SIGTERM, sending SIGKILL to:" >&2
  ps -o pid=,stat=,args= -p "$(tr '\n' ',' <<<"$left" | sed 's/,*$//')" >&2 || true
  lab__signal_session KILL "$@"
  for ((i = 0; i < 60; i++)); do
    [ -n "$(lab__members_of "$@")" ] || return 1
    sleep 0.05
  done
  return 2
}


# lab__leftovers: pids of live processes in a lab namespace (by inode, so also after deletion) or
# in the session of a lab_start process.
lab__leftovers() {
  local -A sids=() netns=()
  local log pid sid stat ino path
  for log in "${lab__order[@]}"; do sids[${lab__pid[$log]}]=1; done
  if [ "${#lab__inode[@]}" -gt 0 ]; then
    while read -r ino path; do
      path=${path#/proc/}
      netns[${path%%/*}]=$ino
    done < <(stat -L -c '%i %n' /proc/[0-9]*/ns/net 2>/dev/null || true)
  fi
  while read -r pid sid stat; do
    [[ $stat != Z* ]] || continue
    if [ -n "${sids[$sid]+x}" ]; then
      echo "$pid"
    elif [ -n "${netns[$pid]+x}" ] && [ -n "${lab__inode[${netns[$pid]}]+x}" ]; then
      echo "$pid"
    fi
  done < <(ps -e -o pid=,sid=,stat=)
}


lab__stop_sessions() {
  local - rc=0 log
  set +e
  # All sessions at once: one common grace period.
  local -a sessions=()
  for log in "${lab__order[@]}"; do sessions+=("${lab__pid[$log]}"); done
  [ "${#sessions[@]}" -gt 0 ] || return 0
  lab__terminate cleanup "${sessions[@]}" || rc=1
  for log in "${lab__order[@]}"; do lab__alive "${lab__pid[$log]}" || lab__reap "$log"; done
  return "$rc"
}
