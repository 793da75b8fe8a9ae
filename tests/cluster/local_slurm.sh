# shellcheck shell=bash
# A throwaway Slurm cluster on localhost, and waiting for its jobs: sourced by
# tests/cluster/test_cluster.sh (make test-cluster) and tests/cluster/tier_cluster.sh (make
# studies-cluster). Its own munged, slurmctld and NODES slurmd daemons (one per node, each started
# with -N <node> on its own port: Debian's slurmd supports several on one host), everything in
# $TMP/cluster, stopped and removed by `cleanup` (the caller's EXIT trap).
#
# The caller sets LOG_NAME (the prefix of every line), PACKAGES (Debian packages to install if
# missing), SLURM_TIMEOUT (seconds a wait_jobs may take) and TMP (made by it).

log() { printf '%s: %s\n' "$LOG_NAME" "$*"; }
die() {
  printf '%s: FAILED: %s\n' "$LOG_NAME" "$*" >&2
  exit 1
}
# Microseconds since the epoch; the seconds, to a tenth, from one such time stamp to another, and
# from one to now.
now_us() { echo "${EPOCHREALTIME/./}"; }
seconds_between() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f", (b - a) / 1e6 }'; }
since() { seconds_between "$1" "$(now_us)"; }

# --- packages ------------------------------------------------------------------------------------

install_missing_packages() {
  local missing=() p
  for p in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing+=("$p")
  done
  [[ ${#missing[@]} -eq 0 ]] && return
  log "installing missing Debian packages: ${missing[*]}"
  local sudo=()
  [[ $(id -u) -ne 0 ]] && sudo=(sudo)
  "${sudo[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq --no-install-recommends \
    "${missing[@]}"
}

# --- the cluster -----------------------------------------------------------------------------------

TMP=""
SLURMCTLD_PID=""
SLURMD_PIDS=()
JOB_IDS=()
# Set while a failure may be the cluster's: the daemons' logs are then printed.
SHOW_CLUSTER_LOGS=0

print_cluster_logs() {
  local f
  for f in "$TMP"/cluster/slurmctld.log "$TMP"/cluster/slurmd*.log "$TMP"/cluster/munged.log; do
    [[ -f $f ]] || continue
    printf '\n----- %s (last 40 lines) -----\n' "$f" >&2
    tail -n 40 "$f" >&2
  done
}

stop_pid() { # pid: TERM, up to 5 s, then KILL
  local pid=$1 i
  [[ -n $pid ]] && kill -0 "$pid" 2>/dev/null || return 0
  kill "$pid" 2>/dev/null || true
  for ((i = 0; i < 50; i++)); do
    kill -0 "$pid" 2>/dev/null || return 0
    sleep 0.1
  done
  kill -9 "$pid" 2>/dev/null || true
}

cleanup() {
  local status=$?
  local pid
  set +e
  # Printing to a closed pipe must not cut the clean-up short.
  trap '' PIPE
  if [[ -n $TMP && -d $TMP ]]; then
    if [[ -n $SLURMCTLD_PID ]] && kill -0 "$SLURMCTLD_PID" 2>/dev/null; then
      ((${#JOB_IDS[@]})) && scancel "${JOB_IDS[@]}" 2>/dev/null
      scontrol shutdown >/dev/null 2>&1
    fi
    for pid in "${SLURMD_PIDS[@]}"; do stop_pid "$pid"; done
    stop_pid "$SLURMCTLD_PID"
    [[ -S $TMP/cluster/munge.socket ]] && munged -s -S "$TMP/cluster/munge.socket" >/dev/null 2>&1
    ((status != 0 && SHOW_CLUSTER_LOGS)) && print_cluster_logs
    if [[ ${KEEP_TMP:-0} == 1 ]]; then
      log "kept $TMP"
    else
      rm -rf "$TMP"
    fi
  fi
  exit "$status"
}

# A TCP port nobody listens on, other than those given.
free_port() {
  local used port
  used=$(ss -Hltn | awk '{ sub(/.*:/, "", $4); print $4 }')
  for port in $(shuf -i 20000-60000 -n 100); do
    grep -qx "$port" <<<"$used" && continue
    [[ " $* " == *" $port "* ]] && continue
    echo "$port"
    return
  done
  die "no free TCP port found"
}

# The nodes: one named after the host with all its CPUs (NODES=1), or NODES nodes node1, node2, ...
# sharing them (CPUS_PER_NODE each, default nproc / NODES), each its own slurmd on its own port.
# CLUSTER_NODES gets their names.
CLUSTER_NODES=()

node_lines() { # host cpus-per-node first-port
  local i
  if ((NODES == 1)); then
    echo "NodeName=$1 NodeAddr=127.0.0.1 CPUs=$2 State=UNKNOWN"
    return
  fi
  for ((i = 1; i <= NODES; i++)); do
    echo "NodeName=node$i NodeHostname=$1 NodeAddr=127.0.0.1 Port=$(($3 + i - 1)) CPUs=$2 State=UNKNOWN"
  done
}

# NODES (default 1) slurmd nodes on localhost, each with CPUS_PER_NODE CPUs.
start_cluster() {
  local dir=$TMP/cluster host cpus ctld_port slurmd_port i state node idle
  NODES=${NODES:-1}
  host=$(hostname)
  cpus=${CPUS_PER_NODE:-$(($(nproc) / NODES > 0 ? $(nproc) / NODES : 1))}
  mkdir -p "$dir/state"
  # munged refuses a socket directory that others cannot traverse only with a warning; be exact.
  chmod 711 "$TMP" "$dir"

  dd if=/dev/urandom of="$dir/munge.key" bs=1024 count=1 status=none
  chmod 400 "$dir/munge.key"
  munged -f --key-file="$dir/munge.key" --socket="$dir/munge.socket" \
    --pid-file="$dir/munged.pid" --seed-file="$dir/munge.seed" --log-file="$dir/munged.log" ||
    die "munged did not start (log: $(cat "$dir/munged.log" 2>/dev/null))"

  ctld_port=$(free_port)
  # The nodes' ports: a free one and those after it.
  slurmd_port=$(free_port "$ctld_port")
  for ((i = 1; i < NODES; i++)); do
    ss -Hltn | awk '{ print $4 }' | grep -q ":$((slurmd_port + i))\$" &&
      die "port $((slurmd_port + i)) is in use; run again"
  done
  if ((NODES == 1)); then
    CLUSTER_NODES=("$host")
  else
    for ((i = 1; i <= NODES; i++)); do CLUSTER_NODES+=("node$i"); done
  fi
  cat >"$dir/slurm.conf" <<EOF
ClusterName=mpmstab-test
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/munge
AuthInfo=socket=$dir/munge.socket
CredType=cred/munge
StateSaveLocation=$dir/state
# %n: the node's name, so that each slurmd has its own files.
SlurmdSpoolDir=$dir/spool-%n
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd-%n.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd-%n.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
ReturnToService=2
MailProg=/bin/true
SchedulerType=sched/backfill
# Schedule every second (the default is a minute), so that the merge job starts as soon as the
# array it depends on has completed; cancel a job whose dependency can no longer be satisfied.
SchedulerParameters=sched_interval=1,bf_interval=1
DependencyParameters=kill_invalid_depend
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
JobCompType=jobcomp/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
$(node_lines "$host" "$cpus" "$slurmd_port")
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
  export SLURM_CONF=$dir/slurm.conf

  slurmctld -D -f "$SLURM_CONF" </dev/null >"$dir/slurmctld.out" 2>&1 &
  SLURMCTLD_PID=$!
  for node in "${CLUSTER_NODES[@]}"; do
    slurmd -D -N "$node" -f "$SLURM_CONF" </dev/null >"$dir/slurmd-$node.out" 2>&1 &
    SLURMD_PIDS+=($!)
  done

  for ((i = 0; i < 600; i++)); do
    state=$(sinfo -h -N -o '%N %T' 2>/dev/null || true)
    idle=$(awk '$2 == "idle"' <<<"$state" | wc -l)
    ((idle == NODES)) && return
    kill -0 "$SLURMCTLD_PID" 2>/dev/null || die "slurmctld exited: $(cat "$dir/slurmctld.out")"
    for node in "${!SLURMD_PIDS[@]}"; do
      kill -0 "${SLURMD_PIDS[$node]}" 2>/dev/null ||
        die "slurmd ${CLUSTER_NODES[$node]} exited: $(cat "$dir/slurmd-${CLUSTER_NODES[$node]}.out")"
    done
    sleep 0.1
  done
  die "the Slurm nodes ${CLUSTER_NODES[*]} are not all idle after 60 s (states: '${state:-unknown}')"
}

# --- Slurm jobs ----------------------------------------------------------------------------------

# One line per job (an array: one per task): "<id> <JobState> <ExitCode> <Reason> <StdOut>".
job_lines() {
  scontrol show job -o "$1" 2>/dev/null |
    awk '{ id = array = task = state = code = reason = out = "?"
           for (i = 1; i <= NF; i++) {
             split($i, kv, "=")
             if (kv[1] == "JobId") id = kv[2]
             else if (kv[1] == "ArrayJobId") array = kv[2]
             else if (kv[1] == "ArrayTaskId") task = kv[2]
             else if (kv[1] == "JobState") state = kv[2]
             else if (kv[1] == "ExitCode") code = kv[2]
             else if (kv[1] == "Reason") reason = kv[2]
             else if (kv[1] == "StdOut") out = substr($i, 8)
           }
           if (array != "?") id = array "_" task
           print id, state, code, reason, out }'
}

print_job_logs() {
  local id line out
  for id in "$@"; do
    while read -r line; do
      printf '%s\n' "$line" >&2
      out=${line##* }
      if [[ -f $out ]]; then
        printf -- '----- %s -----\n' "$out" >&2
        cat "$out" >&2
      fi
    done < <(job_lines "$id")
  done
}

# Waits until every job given (every task of an array) has completed with exit code 0:0; fails as
# soon as one has ended otherwise or can never start.
wait_jobs() {
  local deadline=$((SECONDS + SLURM_TIMEOUT)) lines id
  while :; do
    lines=$(for id in "$@"; do job_lines "$id"; done)
    for id in "$@"; do
      grep -q "^${id}[_ ]" <<<"$lines" || die "Slurm does not know job $id"
    done
    if awk '($2 == "COMPLETED" && $3 != "0:0") || $2 ~ /^(FAILED|CANCELLED|TIMEOUT|NODE_FAIL|OUT_OF_MEMORY|BOOT_FAIL|DEADLINE|PREEMPTED)$/ || $4 == "DependencyNeverSatisfied" { bad = 1 }
            END { exit !bad }' <<<"$lines"; then
      print_job_logs "$@"
      die "a Slurm job did not complete with exit code 0 (jobs $*)"
    fi
    awk '$2 != "COMPLETED" { running = 1 } END { exit !running }' <<<"$lines" || return 0
    if ((SECONDS >= deadline)); then
      print_job_logs "$@"
      die "Slurm jobs $* still running after ${SLURM_TIMEOUT} s"
    fi
    sleep 0.5
  done
}

# --- records ---------------------------------------------------------------------------------------

# The keys of the cases cached in the given output folders, sorted.
cached_keys() {
  local d
  for d in "$@"; do
    if [[ -d $d/cache ]]; then
      # the records, <16 hex digits of the key>.json (not the machine's timings.json)
      find "$d/cache" -maxdepth 1 -regextype posix-extended -regex '.*/[0-9a-f]{16}\.json' \
        -printf '%f\n'
    fi
  done | sed 's/\.json$//' | sort
}
