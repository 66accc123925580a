#!/usr/bin/env bash
# Runs every libFuzzer target of a fuzz build for SECONDS each (or until RUNS executions), from
# its seed corpus: fuzz/corpus/<t> (hand-written), the generated seeds (uwgrasp_fuzz_seeds, with
# the small real clouds of ../shared/data) and fuzz/regressions/<t> (inputs that once failed).
# Fails on the first crash, leak, timeout, out-of-memory or failed invariant, naming the input.
# Usage: fuzz/run.sh BUILD_DIR SECONDS [RUNS] [--jobs N] [TARGET...]   (RUNS 0: no limit;
#        N targets at a time, default 1)
# FUZZ_SEED=N fixes libFuzzer's random seed (CI sets it, so a CI run repeats a local one of the
# same length); unset, every run explores differently.
# Writes BUILD_DIR/fuzz/summary.tsv: target, executions, coverage, features, exec/s, corpus size.
set -euo pipefail
build=$(cd "$1" && pwd); seconds=$2; runs=${3:-0}; shift 3 2>/dev/null || shift $#
jobs=1
if [[ ${1:-} == --jobs ]]; then jobs=$2; shift 2; fi
src=$(cd "$(dirname "$0")/.." && pwd)
data="$src/../shared/data"
out="$build/fuzz"
[[ -x "$out/uwgrasp_fuzz_seeds" ]] || { echo "fuzz/run.sh: $out/uwgrasp_fuzz_seeds not built (cmake --build $build --target fuzz)" >&2; exit 2; }
targets=("$@")
if [[ ${#targets[@]} -eq 0 ]]; then
  for f in "$out"/fuzz_*; do targets+=("${f##*/fuzz_}"); done
fi

rm -rf "$out/seeds"
if [[ -d "$data" ]]; then "$out/uwgrasp_fuzz_seeds" "$out/seeds" "$data"
else echo "fuzz/run.sh: $data absent, seeds without the real clouds"; "$out/uwgrasp_fuzz_seeds" "$out/seeds"; fi

dict_of() {
  case $1 in
    pcd) echo pcd ;; ply) echo ply ;; config|scene|truth) echo yaml ;;
    grasps_json) echo json ;; camera|stereo) echo calib ;; *) echo "" ;;
  esac
}
max_len_of() { case $1 in pcd|ply) echo 65536 ;; *) echo 16384 ;; esac; }

# intercept_tls_get_addr=0 as in .ci/run: GCC 12's runtime misreads some dynamic TLS blocks.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:intercept_tls_get_addr=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# run_one TARGET: fuzzes it, then writes $out/TARGET.row (its summary) or $out/TARGET.failed.
run_one() {
  local t=$1 bin="$out/fuzz_$1" work="$out/corpus/$1" log="$out/$1.log" d seeds=() args
  rm -f "$out/$t.row" "$out/$t.failed"
  mkdir -p "$work" "$out/artifacts"
  for d in "$src/fuzz/corpus/$t" "$out/seeds/$t" "$src/fuzz/regressions/$t"; do [[ -d $d ]] && seeds+=("$d"); done
  args=(-max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len="$(max_len_of "$t")"
        -print_final_stats=1 -artifact_prefix="$out/artifacts/$t-")
  [[ $runs -gt 0 ]] && args+=(-runs="$runs")
  [[ -n ${FUZZ_SEED:-} ]] && args+=(-seed="$FUZZ_SEED")
  d=$(dict_of "$t"); [[ -n $d ]] && args+=(-dict="$src/fuzz/dict/$d.dict")
  if ! "$bin" "${args[@]}" "$work" "${seeds[@]}" >"$log" 2>&1; then
    { echo "fuzz $t: FAILED; from $log:"
      grep -E "ERROR|SUMMARY|Test unit written|deadly|leak|timeout|out-of-memory|terminate|what\(\)" "$log" | tail -8
    } >"$out/$t.failed"
    return
  fi
  local execs speed last
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  speed=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  last=$(grep -E '^#[0-9]+' "$log" | tail -1)
  printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$t" "$execs" "$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"$last")" \
    "$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$last")" "$speed" "$(sed -n 's/.* corp: \([0-9]*\).*/\1/p' <<<"$last")" \
    >"$out/$t.row"
}

for t in "${targets[@]}"; do
  [[ -x "$out/fuzz_$t" ]] || { echo "fuzz/run.sh: no fuzz target $t in $out" >&2; exit 2; }
done
echo "fuzz: ${#targets[@]} targets, ${seconds} s each${runs:+ (at most $runs runs)}, $jobs at a time"
for t in "${targets[@]}"; do
  while [[ $(jobs -rp | wc -l) -ge $jobs ]]; do wait -n || true; done
  run_one "$t" &
done
wait
status=0
printf 'target\texecutions\tcoverage\tfeatures\texec_per_s\tcorpus\n' >"$out/summary.tsv"
for t in "${targets[@]}"; do
  if [[ -f "$out/$t.failed" ]]; then cat "$out/$t.failed" >&2; status=1
  elif [[ -f "$out/$t.row" ]]; then cat "$out/$t.row" >>"$out/summary.tsv"
  else echo "fuzz $t: no result" >&2; status=1; fi
done
awk -F'\t' '{ printf "%-12s %12s %9s %9s %11s %7s\n", $1, $2, $3, $4, $5, $6 }' "$out/summary.tsv"
[[ $status -eq 0 ]] && echo "fuzz: 0 crashes, leaks, timeouts or failed invariants"
exit $status
