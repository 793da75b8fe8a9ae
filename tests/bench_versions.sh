#!/usr/bin/env bash
# make bench-versions: ns per particle-step of each method for each kernel version this machine
# can run, beside the lean loop (tests/lean_step.cpp) compiled for the same instruction set, and
# their ratio (lean / version: how many times faster the version is). Runs are interleaved (each
# round runs every method on every binary once) and the best of ROUNDS rounds is kept, pinned to
# one core when taskset is there. Prints a Markdown table, also written to BUILD/bench_versions.md.
#
# Usage: tests/bench_versions.sh BUILD_DIR   (environment: ROUNDS, default 3; PARTICLE_STEPS,
# default 2e7 per run; METHODS, default "gimp mpm bspline2 bspline3", the
# bases the lean loop has)
set -euo pipefail

BUILD=${1:?usage: bench_versions.sh BUILD_DIR}
ROUNDS=${ROUNDS:-3}
PARTICLE_STEPS=${PARTICLE_STEPS:-2e7}
read -r -a METHODS <<<"${METHODS:-gimp mpm bspline2 bspline3}"
RATIO_FAST=6 RATIO_PORTABLE=4.5 SPLINE_OVER_GIMP=2
ARCH=$(sed -n 's/^MPMSTAB_ARCH:STRING=//p' "$BUILD/CMakeCache.txt")

# version binary : lean binary, for the versions built here.
PAIRS=("default:native")
[[ -x $BUILD/tests/bench_version_avx2 ]] && PAIRS+=("avx2:x86-64-v3")
[[ -n $ARCH ]] && PAIRS+=("portable:$ARCH")
PIN=()
command -v taskset >/dev/null && PIN=(taskset -c 0)

declare -A BEST ISA
run() { # binary key: one run per method, keep the best
  local method ns isa
  while read -r method ns isa; do
    local k="$2/$method"
    if [[ -z ${BEST[$k]:-} ]] || awk -v a="$ns" -v b="${BEST[$k]}" 'BEGIN { exit !(a < b) }'; then
      BEST[$k]=$ns
    fi
    ISA[$2]=$isa
  done < <("${PIN[@]}" "$BUILD/tests/$1" --particle-steps "$PARTICLE_STEPS" "${METHODS[@]}")
}
for ((round = 1; round <= ROUNDS; round++)); do
  for pair in "${PAIRS[@]}"; do
    run "bench_version_${pair%%:*}" "${pair%%:*}"
    run "bench_lean_${pair##*:}" "lean-${pair##*:}"
  done
done

# Each version's ratios, computed once for the table and the verdicts below: lean / version for
# every method, and each B-spline's cost over GIMP's.
declare -A LEAN_OVER SPLINE_OVER
quotient() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.17g", a / b }'; }
for pair in "${PAIRS[@]}"; do
  v=${pair%%:*} l=${pair##*:}
  for m in "${METHODS[@]}"; do
    if [[ -n ${BEST[$v/$m]:-} && -n ${BEST[lean-$l/$m]:-} ]]; then
      LEAN_OVER[$v/$m]=$(quotient "${BEST[lean-$l/$m]}" "${BEST[$v/$m]}")
    fi
  done
  for spline in bspline2 bspline3; do
    if [[ -n ${BEST[$v/$spline]:-} && -n ${BEST[$v/gimp]:-} ]]; then
      SPLINE_OVER[$v/$spline]=$(quotient "${BEST[$v/$spline]}" "${BEST[$v/gimp]}")
    fi
  done
done

cpu=$(lscpu | sed -n 's/^Model name: *//p' | head -1)
cores=$(nproc)
flags=$(grep -m1 -o -w 'avx512f' /proc/cpuinfo || true)
{
  echo "Machine: $cpu, $cores cores, $([[ -n $flags ]] && echo "with AVX-512" || echo "without AVX-512")."
  echo "ns per particle-step, best of $ROUNDS interleaved runs of $PARTICLE_STEPS particle-steps"
  echo "(the paper's bar, E = 64, A = 0.015, dt = 1e-6, 100 cells x 2 particles)."
  echo
  header="| method |"
  rule="|---|"
  for pair in "${PAIRS[@]}"; do
    v=${pair%%:*} l=${pair##*:}
    header+=" $v (${ISA[$v]}) | lean loop (-march=$l) | lean / $v |"
    rule+="---|---|---|"
  done
  echo "$header"
  echo "$rule"
  for m in "${METHODS[@]}"; do
    row="| $m |"
    for pair in "${PAIRS[@]}"; do
      v=${pair%%:*} l=${pair##*:}
      row+=$(awk -v a="${BEST[$v/$m]}" -v b="${BEST[lean-$l/$m]}" -v r="${LEAN_OVER[$v/$m]:-}" \
        'BEGIN { printf " %.2f | %.2f | %.1fx |", a, b, r }')
    done
    echo "$row"
  done
  for spline in bspline2 bspline3; do
    [[ -n ${SPLINE_OVER[default/$spline]:-} ]] || continue
    row="| $spline / gimp |"
    for pair in "${PAIRS[@]}"; do
      row+=$(awk -v r="${SPLINE_OVER[${pair%%:*}/$spline]:-}" 'BEGIN { printf " %.2fx | | |", r }')
    done
    echo "$row"
  done
  # The targets: GIMP and MPM at least RATIO_FAST times faster than their lean loop in the
  # default and AVX2 versions and RATIO_PORTABLE in the portable one; each B-spline at most
  # SPLINE_OVER_GIMP times GIMP's cost in every version.
  echo
  for pair in "${PAIRS[@]}"; do
    v=${pair%%:*}
    target=$([[ $v == portable ]] && echo "$RATIO_PORTABLE" || echo "$RATIO_FAST")
    for m in gimp mpm; do
      [[ -n ${LEAN_OVER[$v/$m]:-} ]] || continue
      awk -v r="${LEAN_OVER[$v/$m]}" -v t="$target" -v what="$v $m" \
        'BEGIN { printf "- %s: lean / version %.1fx, target at least %sx: %s\n", what, r, t, (r >= t ? "met" : "**not met**") }'
    done
    for spline in bspline2 bspline3; do
      [[ -n ${SPLINE_OVER[$v/$spline]:-} ]] || continue
      awk -v r="${SPLINE_OVER[$v/$spline]}" -v t="$SPLINE_OVER_GIMP" -v what="$v $spline" \
        'BEGIN { printf "- %s: %.2fx GIMP, target at most %sx: %s\n", what, r, t, (r <= t ? "met" : "**not met**") }'
    done
  done
} | tee "$BUILD/bench_versions.md.tmp"
mv "$BUILD/bench_versions.md.tmp" "$BUILD/bench_versions.md"
