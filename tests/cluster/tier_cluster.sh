#!/usr/bin/env bash
# A whole tier run as one Slurm job array on a throwaway cluster on this machine (make
# studies-cluster NODES=1|2, make reproduce-cluster): the tier must come out byte for byte as
# committed in results/, and its wall time on that many nodes is then recorded in
# results/cluster_timings.json (mpmstab cluster-time), which results/performance.md shows.
#
# Starts NODES slurmd nodes on localhost (tests/cluster/local_slurm.sh), writes the tier's job
# array over its cases, the array over the follow-up runs their records decide, and the render
# job (mpmstab slurm --tier TIER) into a temporary folder, submits them with an empty cache and a
# scratch results folder, waits for each, and compares every file the render wrote with
# the committed one: byte for byte, except that the reports' relative links to the checkout
# (../experiments/..., ../docs/...) are those of a folder outside it. cache/ (the records and the
# machine's timings) is not compared. The scratch folder starts with the committed reports of the
# other tier's experiments, copied from results/, since the index (results/README.md) covers both
# tiers; they are not compared.
#
# Environment: MPMSTAB (default build/mpmstab); TIER (studies or paper, default studies); NODES
# (default 1); JOBS, the array tasks run at once and the CPUs of the cluster (default 1: on a
# shared machine one heavy process at a time): one node of JOBS CPUs, or NODES nodes of
# max(1, JOBS / NODES) CPUs each; SHARDS (default 8); RESULTS_DIR, the scratch results folder
# (default in the temporary folder; it must not exist); SLURM_TIMEOUT (seconds per wait, default
# 3600); KEEP_TMP=1 keeps the temporary folder.
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd -P)
MPMSTAB=$(realpath -m "${MPMSTAB:-$ROOT/build/mpmstab}")
TIER=${TIER:-studies}
NODES=${NODES:-1}
JOBS=${JOBS:-1}
SHARDS=${SHARDS:-8}
SLURM_TIMEOUT=${SLURM_TIMEOUT:-3600}
PACKAGES=(slurm-wlm munge iproute2)
LOG_NAME="$TIER-cluster"
# shellcheck source=tests/cluster/local_slurm.sh
source "$ROOT/tests/cluster/local_slurm.sh"

[[ $TIER == studies || $TIER == paper ]] || die "TIER must be studies or paper, not '$TIER'"
[[ $NODES =~ ^[1-9][0-9]?$ && $JOBS =~ ^[1-9][0-9]*$ && $SHARDS =~ ^[1-9][0-9]*$ ]] ||
  die "NODES (1-99), JOBS and SHARDS must be positive integers"
if ((NODES == 1)); then
  CPUS_PER_NODE=$JOBS
else
  CPUS_PER_NODE=$((JOBS / NODES > 0 ? JOBS / NODES : 1))
fi

# The file as committed, with the relative links of a report in OUT to the checkout made those
# of one in results/ (../).
normalized() { # file
  sed "s|$LINK_PREFIX/|../|g" "$1"
}

# The experiment a committed file of results/ belongs to: the longest spec name it starts with,
# followed by '.' or '_' (nothing for the index and the machine's files).
owner() { # file
  local n own=""
  for n in "${ALL_NAMES[@]}"; do
    case $1 in "$n".* | "$n"_*) ((${#n} > ${#own})) && own=$n ;; esac
  done
  echo "$own"
}

# The scratch folder starts with the committed reports of the experiments of the other tier (not
# run here; the index, results/README.md, covers both tiers); every other file must come from
# the render. TIER_FILES gets the committed files the tier must write (its experiments' and the
# index), COPIED those copied.
prepare_scratch() { # out
  local out=$1 f own
  mapfile -t ALL_NAMES < <("$MPMSTAB" list | xargs -n 1 basename | sed 's/\.json$//')
  mapfile -t TIER_NAMES < <("$MPMSTAB" list --tier "$TIER" | xargs -n 1 basename | sed 's/\.json$//')
  TIER_FILES=() COPIED=()
  mkdir -p "$out"
  while IFS= read -r f; do
    own=$(owner "$f")
    if [[ $f == README.md || (-n $own && " ${TIER_NAMES[*]} " == *" $own "*) ]]; then
      TIER_FILES+=("$f")
    elif [[ -n $own ]]; then
      cp "$ROOT/results/$f" "$out/$f"
      COPIED+=("$f")
    fi
  done < <(git -C "$ROOT" ls-files results | sed "s|^results/||" | grep -v /)
}

# Every file the render wrote (cache/ and the folder's lock aside) is committed and byte for byte
# the same; every committed file of the tier was written.
compare_with_committed() { # out
  local out=$1 f n=0
  LINK_PREFIX=$(realpath -m --relative-to="$out" "$ROOT")
  while IFS= read -r f; do
    [[ " ${COPIED[*]} " == *" $f "* || $f == .mpmstab.lock ]] && continue
    [[ -f $ROOT/results/$f ]] || die "$out/$f was written but results/$f is not committed"
    if ! cmp -s "$ROOT/results/$f" "$out/$f"; then
      [[ $f == *.png ]] && die "$out/$f differs from results/$f"
      if ! cmp -s "$ROOT/results/$f" <(normalized "$out/$f"); then
        diff -u "$ROOT/results/$f" <(normalized "$out/$f") | head -n 40 >&2 || true
        die "$out/$f differs from results/$f"
      fi
    fi
    n=$((n + 1))
  done < <(cd "$out" && find . -path ./cache -prune -o -type f -printf '%P\n' | sort)
  for f in "${TIER_FILES[@]}"; do
    [[ -f $out/$f ]] || die "the render wrote no $out/$f (results/$f is committed)"
  done
  ((n == ${#TIER_FILES[@]})) || die "$n files written, ${#TIER_FILES[@]} expected"
  git -C "$ROOT" diff --quiet -- results ||
    log "note: results/ has uncommitted changes; compared with the files as they are"
  COMPARED=$n
}

main() {
  local t0 t_array t_follow t_end out work ids sweep_id follow_id render_id
  local array_records follow_records total_records
  cd "$ROOT"
  [[ -x $MPMSTAB ]] || die "$MPMSTAB not found; run make build first"
  install_missing_packages
  TMP=$(mktemp -d "${TMPDIR:-/tmp}/mpmstab-$TIER-cluster.XXXXXX")
  trap cleanup EXIT
  trap 'log "interrupted"; exit 130' INT TERM
  out=$(realpath -m "${RESULTS_DIR:-$TMP/results}")
  [[ -e $out ]] && die "$out exists; the scratch results folder must start empty"
  work=$TMP/slurm

  prepare_scratch "$out"
  SHOW_CLUSTER_LOGS=1
  start_cluster
  log "Slurm $(sinfo -V | awk '{ print $2 }'): ${CLUSTER_NODES[*]} idle ($NODES x $CPUS_PER_NODE CPUs, $JOBS array tasks at once), files in $TMP"
  ids=$("$MPMSTAB" slurm --tier "$TIER" --shards "$SHARDS" --throttle "$JOBS" --cpus-per-task 1 \
    --render-cpus "$CPUS_PER_NODE" --partition debug --time 04:00:00 --work "$work" \
    --out "$out" --mpmstab "$MPMSTAB" 2>&1) || die "mpmstab slurm --tier $TIER failed:"$'\n'"$ids"

  t0=$(now_us)
  ids=$(sh "$work/$TIER.submit.sh" 2>&1) || die "$work/$TIER.submit.sh failed:"$'\n'"$ids"
  sweep_id=$(awk '$1 == "sweep" { print $2 }' <<<"$ids")
  follow_id=$(awk '$1 == "follow" { print $2 }' <<<"$ids")
  render_id=$(awk '$1 == "render" { print $2 }' <<<"$ids")
  [[ $sweep_id =~ ^[0-9]+$ && $follow_id =~ ^[0-9]+$ && $render_id =~ ^[0-9]+$ ]] ||
    die "$work/$TIER.submit.sh did not print 'sweep <id>', 'follow <id>' and 'render <id>' lines:"$'\n'"$ids"
  JOB_IDS+=("$sweep_id" "$follow_id" "$render_id")
  log "$SHARDS-task array $sweep_id over the tier's cases, then $SHARDS-task array $follow_id over their follow-up runs, then render job $render_id"
  wait_jobs "$sweep_id"
  t_array=$(now_us)
  log "cases' array done in $(since "$t0") s; follow-up runs"
  wait_jobs "$follow_id"
  t_follow=$(now_us)
  log "follow-up array done in $(since "$t_array") s; rendering"
  wait_jobs "$render_id"
  t_end=$(now_us)
  SHOW_CLUSTER_LOGS=0
  tail -n 1 "$work"/logs/*-render-*.out | sed "s/^/$LOG_NAME: render: /"

  compare_with_committed "$out"
  array_records=$(cached_keys "$work"/shard-* | uniq | wc -l)
  # (a follow-up run that is also a case is copied from the cases' shards, not computed)
  follow_records=$(comm -13 <(cached_keys "$work"/shard-* | uniq) \
    <(cached_keys "$work"/follow-* | uniq) | wc -l)
  total_records=$(cached_keys "$out" | wc -l)
  log "OK: $COMPARED files of the $TIER tier byte for byte as committed (relative links aside;" \
    "${#COPIED[@]} reports of the other tier copied in first for the index);" \
    "$array_records records computed in the cases' array, $follow_records in the follow-up array," \
    "$((total_records - array_records - follow_records)) in the render"
  "$MPMSTAB" cluster-time --tier "$TIER" --nodes "$NODES" --cpus-per-node "$CPUS_PER_NODE" \
    --at-once "$JOBS" --shards "$SHARDS" \
    --array-seconds "$(seconds_between "$t0" "$t_array")" \
    --follow-seconds "$(seconds_between "$t_array" "$t_follow")" \
    --render-seconds "$(seconds_between "$t_follow" "$t_end")" \
    --seconds "$(seconds_between "$t0" "$t_end")" \
    --array-records "$array_records" --follow-records "$follow_records" \
    --render-records "$((total_records - array_records - follow_records))" \
    --out "$ROOT/results"
}

main "$@"
