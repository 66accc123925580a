#!/usr/bin/env bash
# Interrupted runs leave every output either as it was or complete, and no temporary file:
# `experiments` and `simulate` are killed (SIGINT, SIGTERM) at random moments, and at the moment
# a temporary output file appears (mid-write), over a folder that
# holds the outputs of an earlier run; afterwards each file must be the earlier one or a whole
# new one (a PNG ends in IEND, a CSV or report has the earlier run's number of lines; same seed,
# so only timings may differ) and no .NAME.tmp-PID file may remain.
source "$(dirname "$0")/cli_lib.sh"
KILLS=${4:-8}

complete() {  # complete NEW OLD: the same file, or a whole one of its kind
  local new=$1 old=$2
  cmp -s "$new" "$old" && return 0
  case $new in
    *.png) [[ "$(tail -c 8 "$new" | od -An -tx1 | tr -d ' \n')" == "49454e44ae426082" ]] ;;
    *.pcd) [[ $(stat -c %s "$new") -eq $(stat -c %s "$old") ]] ;;
    *) [[ $(wc -l <"$new") -eq $(wc -l <"$old") && -z "$(tail -c 1 "$new" | tr -d '\n')" ]] ;;
  esac
}

check_folder() {  # check_folder RUN REF what
  local run=$1 ref=$2 what=$3 f
  local tmp; tmp=$(find "$run" -name '.*.tmp-*' | head -3)
  [[ -z $tmp ]] && ok || bad "$what: temporary files left: $tmp"
  for f in "$ref"/*; do
    [[ -f $f ]] || continue
    local n="$run/${f##*/}"
    if [[ ! -e $n ]]; then bad "$what: ${f##*/} disappeared"; continue; fi
    complete "$n" "$f" && ok || bad "$what: ${f##*/} is partial ($(stat -c %s "$n") bytes, earlier $(stat -c %s "$f"))"
  done
}

# kill_at RUN_DIR REF_DIR WHEN SIGNAL ARGS...: copy the earlier outputs, start, signal, check.
# WHEN is seconds, or "write": the moment a temporary output file appears (mid-write).
mid_write=0
kill_at() {
  local run=$1 ref=$2 when=$3 sig=$4; shift 4
  rm -rf "$run"; cp -r "$ref" "$run"
  "$BIN" "$@" --out "$run" >/dev/null 2>&1 &
  local pid=$!
  if [[ $when == write ]]; then
    while kill -0 "$pid" 2>/dev/null && ! compgen -G "$run/.*.tmp-*" >/dev/null; do :; done
    kill -"$sig" "$pid" 2>/dev/null && mid_write=$((mid_write + 1))
  else
    sleep "$when"; kill -"$sig" "$pid" 2>/dev/null
  fi
  wait "$pid" 2>/dev/null
  check_folder "$run" "$ref" "$* killed by SIG$sig at $when"
}

EXP=(experiments --study judged --scenes barbell ring --water coastal --iterations 1 --robust 0 --no-calibration --seed 3)
SIM=(simulate --scene thesis --sensor stereo --water turbid --seed 3)
start=$(date +%s.%N)
"$BIN" "${EXP[@]}" --out "$T/exp_ref" >/dev/null 2>&1 || bad "reference experiments run"
exp_s=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')
start=$(date +%s.%N)
"$BIN" "${SIM[@]}" --out "$T/sim_ref" >/dev/null 2>&1 || bad "reference simulate run"
sim_s=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')
RANDOM=7  # reproducible kill moments
for ((k = 0; k < KILLS; k++)); do
  sig=TERM; ((k % 2)) && sig=INT
  kill_at "$T/exp" "$T/exp_ref" "$(awk -v s="$exp_s" -v r=$RANDOM 'BEGIN { printf "%.2f", s * r / 32768 }')" $sig "${EXP[@]}"
  kill_at "$T/sim" "$T/sim_ref" "$(awk -v s="$sim_s" -v r=$RANDOM 'BEGIN { printf "%.2f", s * r / 32768 }')" $sig "${SIM[@]}"
  kill_at "$T/sim" "$T/sim_ref" write $sig "${SIM[@]}"
  kill_at "$T/exp" "$T/exp_ref" write $sig "${EXP[@]}"
done
# The polling must have caught runs in the middle of writing a file, or the test proves little.
[[ $mid_write -ge $KILLS ]] && ok || bad "only $mid_write of $((2 * KILLS)) runs were killed mid-write"
# A run left to finish over the earlier outputs replaces them whole.
rm -rf "$T/exp"; cp -r "$T/exp_ref" "$T/exp"
"$BIN" "${EXP[@]}" --out "$T/exp" >/dev/null 2>&1 || bad "uninterrupted experiments run"
check_folder "$T/exp" "$T/exp_ref" "uninterrupted run"
finish
