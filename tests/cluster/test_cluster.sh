#!/usr/bin/env bash
# End-to-end test of running an experiment on a cluster (make test-cluster).
#
# Starts a one-node Slurm cluster on localhost (its own munged, slurmctld and slurmd, everything
# in a temporary folder removed on exit), then runs small real specs three ways and requires the
# reports to be byte for byte identical:
#   local     mpmstab sweep <spec>, unsharded, one process
#   slurm     mpmstab slurm <spec> --shards 4, the generated submit script: a job array of four
#             shards, then the merge job, which waits for the array (afterok)
#   parallel  GNU parallel runs the four shards through its ssh code path (--sshlogin :), then
#             mpmstab merge
# All runs use --timing omit, so that the reports do not carry machine measurements. It also
# checks that a merge missing a shard fails and names the missing cases, that a merge refuses
# two records of one case that disagree, and that a case lands in the same shard whatever the
# order of the cases in the spec.
#
# Environment: MPMSTAB (default build/mpmstab), KEEP_TMP=1 keeps the temporary folder.
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd -P)
MPMSTAB=$(realpath -m "${MPMSTAB:-$ROOT/build/mpmstab}")
# table2: a table report with a paper reference, 24 cases (about 1 s).
# fig2: a figure report (history records, <name>_data.csv) with a single case, so that three of
# its four shards are empty.
SPECS=(table2 fig2)
# The spec whose cases are shuffled for the shard-assignment check (no reference file, 32 cases).
SHUFFLED_SPEC=crossing
SHARDS=4
SLURM_TIMEOUT=${SLURM_TIMEOUT:-300}
# iproute2: ss, to pick free ports for the daemons.
PACKAGES=(slurm-wlm munge parallel iproute2)
LOG_NAME=test-cluster
NODES=1
# shellcheck source=tests/cluster/local_slurm.sh
source "$ROOT/tests/cluster/local_slurm.sh"

# --- report comparison ---------------------------------------------------------------------------

# The report files of a spec in a folder, as the local sweep wrote them.
report_files() { # name dir
  local f
  for f in "$2/$1.csv" "$2/$1.json" "$2/$1.md" "$2/$1_data.csv"; do
    if [[ -f $f ]]; then
      basename "$f"
    fi
  done
}

same_reports() { # name expected-dir actual-dir
  local name=$1 expected=$2 actual=$3 f n=0
  for f in $(report_files "$name" "$expected"); do
    [[ -f $actual/$f ]] || die "$actual/$f was not written"
    if ! cmp -s "$expected/$f" "$actual/$f"; then
      diff -u "$expected/$f" "$actual/$f" | head -n 40 >&2 || true
      die "$actual/$f differs from the unsharded run's $expected/$f"
    fi
    n=$((n + 1))
  done
  ((n >= 3)) || die "the unsharded run of $name wrote only $n report files in $expected"
  log "  $name: $n report files identical to the unsharded run's ($(report_files "$name" "$expected" | tr '\n' ' '| sed 's/ $//'))"
}

# The shards of a spec cover every case of the unsharded run exactly once.
shards_partition() { # name unsharded-dir shard-dir...
  local name=$1 unsharded=$2
  shift 2
  local all union
  all=$(cached_keys "$unsharded")
  union=$(cached_keys "$@")
  [[ -n $(uniq -d <<<"$union") ]] && die "$name: a case was computed in more than one shard"
  [[ $all == "$union" ]] || die "$name: the shards' cases are not those of the unsharded run"
}

# --- the checks ----------------------------------------------------------------------------------

# Specs are named relative to the repository, as a user would (the reports print the path given).
spec_path() { echo "experiments/$1.json"; }

# mpmstab sweep <spec> --timing omit <options>, its output shown only when it fails.
sweep_or_die() { # spec option...
  local spec=$1 output
  shift
  output=$("$MPMSTAB" sweep "$spec" --timing omit "$@" 2>&1) ||
    die "mpmstab sweep $spec $* failed:"$'\n'"$output"
}

# Each spec has its own folder, TMP/<name>: local/ (the unsharded run), slurm/ (the scripts, shard
# outputs and job logs), par/shard-<i>/, and merged-slurm/ and merged-parallel/. The report folders
# are siblings, since the reports link to the spec by a relative path.
run_local() {
  local name
  for name in "${SPECS[@]}"; do
    sweep_or_die "$(spec_path "$name")" --out "$TMP/$name/local"
  done
}

shard_dirs() { # dir: dir/shard-0 ... dir/shard-<SHARDS - 1>, one per line
  seq -f "$1/shard-%g" 0 $((SHARDS - 1))
}

# The shards were merged into <merged>: identical reports, and the records of exactly the spec's
# cases copied into merged/cache.
check_merged() { # name shard-parent merged
  local name=$1 merged=$3 shards
  mapfile -t shards < <(shard_dirs "$2")
  shards_partition "$name" "$TMP/$name/local" "${shards[@]}"
  same_reports "$name" "$TMP/$name/local" "$merged"
  [[ $(cached_keys "$merged") == "$(cached_keys "$TMP/$name/local")" ]] ||
    die "$merged/cache does not hold exactly the records of the cases of $name"
}

run_slurm() {
  local name work out sweep_id merge_id ids=()
  for name in "${SPECS[@]}"; do
    work=$TMP/$name/slurm
    out=$("$MPMSTAB" slurm "$(spec_path "$name")" --shards "$SHARDS" --partition debug \
      --time 00:10:00 --cpus-per-task 1 --timing omit --work "$work" \
      --out "$TMP/$name/merged-slurm" --mpmstab "$MPMSTAB" 2>&1) ||
      die "mpmstab slurm $name failed:"$'\n'"$out"
    out=$(sh "$work/$name.submit.sh" 2>&1) || die "$work/$name.submit.sh failed:"$'\n'"$out"
    sweep_id=$(awk '$1 == "sweep" { print $2 }' <<<"$out")
    merge_id=$(awk '$1 == "merge" { print $2 }' <<<"$out")
    [[ $sweep_id =~ ^[0-9]+$ && $merge_id =~ ^[0-9]+$ ]] ||
      die "$work/$name.submit.sh did not print 'sweep <id>' and 'merge <id>' lines:"$'\n'"$out"
    JOB_IDS+=("$sweep_id" "$merge_id")
    ids+=("$sweep_id" "$merge_id")
  done
  wait_jobs "${ids[@]}"
  for name in "${SPECS[@]}"; do
    check_merged "$name" "$TMP/$name/slurm" "$TMP/$name/merged-slurm"
  done
}

run_parallel() {
  local name spec out shards
  for name in "${SPECS[@]}"; do
    spec=$(spec_path "$name")
    # The sshlogin ':' is the local host without ssh, through the same code path as a remote one.
    out=$(parallel --sshlogin : -j 2 --halt now,fail=1 \
      "$MPMSTAB" sweep "$spec" --shard "{}/$SHARDS" --timing omit --out "$TMP/$name/par/shard-{}" \
      ::: $(seq 0 $((SHARDS - 1))) 2>&1) || die "parallel sweep of $name failed:"$'\n'"$out"
    mapfile -t shards < <(shard_dirs "$TMP/$name/par")
    out=$("$MPMSTAB" merge "$spec" "${shards[@]}" --timing omit --out "$TMP/$name/merged-parallel" \
      2>&1) || die "mpmstab merge $name failed:"$'\n'"$out"
    check_merged "$name" "$TMP/$name/par" "$TMP/$name/merged-parallel"
  done
}

# A merge without one shard exits non-zero, names each missing case and writes no report.
check_missing_shard() {
  local name=${SPECS[0]} spec dir status=0 key missing out
  spec=$(spec_path "$name")
  dir=$TMP/$name/par
  missing=$(cached_keys "$dir/shard-3")
  [[ -n $missing ]] || die "shard 3 of $name is empty; the check needs a non-empty shard"
  out=$("$MPMSTAB" merge "$spec" "$dir/shard-0" "$dir/shard-1" "$dir/shard-2" --timing omit \
    --out "$TMP/$name/merged-missing" 2>&1) || status=$?
  ((status != 0)) || die "a merge of $name without shard 3 succeeded"
  for key in $missing; do
    grep -q "$key" <<<"$out" ||
      die "a merge of $name without shard 3 does not name the missing case $key:"$'\n'"$out"
  done
  [[ -z $(report_files "$name" "$TMP/$name/merged-missing") ]] ||
    die "a merge of $name without shard 3 wrote reports"
  log "  $name: a merge without shard 3 exits $status and names its $(wc -w <<<"$missing") cases"
}

# A record edited by hand in one shard folder fails its checksum: the merge ignores it, says
# so, and takes the intact record of the same case (two intact records that disagree, as from
# two solver builds, are refused: tests/test_shards.cpp).
check_tampered_duplicate() {
  local name=${SPECS[0]} spec dir tampered key status=0 out
  spec=$(spec_path "$name")
  dir=$TMP/$name/par
  tampered=$TMP/$name/tampered
  key=$(cached_keys "$dir/shard-0" | head -n 1)
  mkdir -p "$tampered/cache"
  # The same case with another number of crossings.
  sed -E 's/"crossings": *([0-9]+)/"crossings": 1\1/' "$dir/shard-0/cache/$key.json" \
    >"$tampered/cache/$key.json"
  cmp -s "$dir/shard-0/cache/$key.json" "$tampered/cache/$key.json" &&
    die "could not alter the record $key for the tampered-duplicate check"
  out=$("$MPMSTAB" merge "$spec" "$tampered" "$dir"/shard-* --timing omit \
    --out "$TMP/$name/merged-tampered" 2>&1) || status=$?
  ((status == 0)) || die "a merge with a tampered record of case $key failed:"$'\n'"$out"
  grep -q "1 records in the folders failed their checksum or shape and were ignored" <<<"$out" ||
    die "a merge with a tampered record of case $key does not say it ignored it:"$'\n'"$out"
  same_reports "$name" "$TMP/$name/local" "$TMP/$name/merged-tampered"
  log "  $name: a merge with a tampered record of one case ignores it, says so, and its reports are the unsharded run's"
}

# The case lines of a spec written one case per line, as experiments/*.json are.
case_lines() { # spec
  sed -n '/"cases": \[/,/^  \]/p' "$1" | grep '^ *{' | sed 's/}, *$/}/'
}

# The spec with its cases in another (fixed) order, written to stdout.
shuffle_cases() { # spec
  local spec=$1 cases
  cases=$(case_lines "$spec" | shuf --random-source=<(yes))
  sed '/"cases": \[/q' "$spec"
  sed '$!s/$/,/' <<<"$cases"
  sed -n '/"cases": \[/,$p' "$spec" | sed -n '/^  \]/,$p'
}

# A case lands in the same shard whatever the order of the spec's cases.
check_shard_order() {
  local spec shuffled="$TMP/order/$SHUFFLED_SPEC.json" i n dirs=()
  spec=$(spec_path "$SHUFFLED_SPEC")
  mkdir -p "$TMP/order"
  shuffle_cases "$spec" >"$shuffled"
  n=$(case_lines "$spec" | wc -l)
  cmp -s <(case_lines "$spec" | sort) <(case_lines "$shuffled" | sort) ||
    die "the shuffled copy of $SHUFFLED_SPEC does not have the same cases"
  cmp -s <(case_lines "$spec") <(case_lines "$shuffled") &&
    die "the shuffled copy of $SHUFFLED_SPEC has its cases in the original order"
  sweep_or_die "$spec" --out "$TMP/order/unsharded"
  for ((i = 0; i < SHARDS; i++)); do
    sweep_or_die "$spec" --shard "$i/$SHARDS" --out "$TMP/order/original/shard-$i"
    sweep_or_die "$shuffled" --shard "$i/$SHARDS" --out "$TMP/order/shuffled/shard-$i"
    [[ $(cached_keys "$TMP/order/original/shard-$i") == "$(cached_keys "$TMP/order/shuffled/shard-$i")" ]] ||
      die "shard $i/$SHARDS of $SHUFFLED_SPEC holds other cases once the spec's cases are shuffled"
    dirs+=("$TMP/order/original/shard-$i")
  done
  shards_partition "$SHUFFLED_SPEC" "$TMP/order/unsharded" "${dirs[@]}"
  log "  $SHUFFLED_SPEC: each of its $n cases lands in the same one of $SHARDS shards with the cases shuffled"
}

main() {
  local t0 t phases=()
  t0=$(now_us)
  cd "$ROOT"
  [[ -x $MPMSTAB ]] || die "$MPMSTAB not found; run make build first"
  local cmd
  for cmd in slurm merge; do
    "$MPMSTAB" "$cmd" --help >/dev/null 2>&1 || die "$MPMSTAB has no '$cmd' command"
  done
  install_missing_packages

  TMP=$(mktemp -d "${TMPDIR:-/tmp}/mpmstab-cluster.XXXXXX")
  trap cleanup EXIT
  trap 'log "interrupted"; exit 130' INT TERM

  t=$(now_us)
  SHOW_CLUSTER_LOGS=1
  start_cluster
  phases+=("cluster start $(since "$t") s")
  log "Slurm $(sinfo -V | awk '{ print $2 }') node $(hostname) idle ($(nproc) CPUs), files in $TMP"

  t=$(now_us)
  run_local
  phases+=("local $(since "$t") s")
  log "unsharded runs of ${SPECS[*]} in $TMP/<name>/local"

  t=$(now_us)
  log "Slurm: $SHARDS-task job array per spec, then the merge job"
  run_slurm
  SHOW_CLUSTER_LOGS=0
  phases+=("slurm $(since "$t") s")

  t=$(now_us)
  log "GNU parallel (--sshlogin :): $SHARDS shards per spec, then mpmstab merge"
  run_parallel
  phases+=("parallel $(since "$t") s")

  t=$(now_us)
  log "failure modes and shard assignment"
  check_missing_shard
  check_tampered_duplicate
  check_shard_order
  phases+=("checks $(since "$t") s")

  log "OK: ${SPECS[*]} sharded $SHARDS ways on Slurm and with GNU parallel, merged reports" \
    "identical to the unsharded run's; $(since "$t0") s ($(printf '%s; ' "${phases[@]}" | sed 's/; $//'))"
}

main "$@"
