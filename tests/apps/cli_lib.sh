# Shared by the CLI tests: `expect`, counting, a scratch folder $T (removed on exit).
set -u
BIN=$1 DATA=$2 SRC=$3
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fails=0 passes=0
# expect CODE WORD -- ARGS...: exit code CODE, stderr one line containing WORD, nothing in $T/out.
expect() {
  local code=$1 word=$2; shift 3
  rm -rf "$T/out"
  "$BIN" "$@" >"$T/stdout" 2>"$T/stderr"
  local got=$? lines
  last_code=$got
  lines=$(wc -l <"$T/stderr")
  if [[ $got -ne $code ]] || { [[ -n $word ]] && ! grep -q -- "$word" "$T/stderr"; } || [[ $lines -gt 1 ]] ||
     [[ -e "$T/out" && -n "$(ls -A "$T/out" 2>/dev/null)" ]]; then
    echo "FAIL: uwgrasp $* -> exit $got (want $code), stderr: $(cat "$T/stderr")"
    fails=$((fails + 1))
  else
    passes=$((passes + 1))
  fi
}

# ok: count a passed check; bad DETAIL: a failed one (printed).
ok() { passes=$((passes + 1)); }
bad() { echo "FAIL: $1"; fails=$((fails + 1)); }

finish() {
  echo "$passes passed, $fails failed"
  [[ $fails -eq 0 ]]
}
