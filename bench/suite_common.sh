# The plumbing the benchmark suites share (bench/run_suite.sh, bench/radiosity_suite.sh): finding
# the pmrender binary, the environment report and one timed `pmrender bench` run. Sourced, not
# run; the suite sets suite_name and suite_dir first.

# suite_find_pmrender GIVEN: sets pmrender to GIVEN, the repository's build, or the bundle's
# bin/pmrender (sourcing the bundle's env.sh for its libraries); exits 2 when there is none.
suite_find_pmrender() {
  pmrender=$1
  if [ -z "$pmrender" ]; then
    if [ -x "$suite_dir/../build/pmrender" ]; then
      pmrender=$suite_dir/../build/pmrender
    elif [ -x "$suite_dir/../bin/pmrender" ]; then
      pmrender=$suite_dir/../bin/pmrender
      # shellcheck disable=SC1091
      source "$suite_dir/../env.sh"  # (it sets its own variable `here`)
    else
      pmrender=$(command -v pmrender || true)
    fi
  fi
  if [ -z "$pmrender" ] || [ ! -x "$pmrender" ]; then
    echo "$suite_name: no pmrender binary found (use --pmrender)" >&2
    exit 2
  fi
}

# suite_environment OUT SETTINGS: OUT/environment.txt (date, commit, host, binary, the suite's
# settings line and the devices), also printed.
suite_environment() {
  local commit=unknown
  if [ -f "$suite_dir/../COMMIT" ]; then commit=$(cat "$suite_dir/../COMMIT")
  elif git -C "$suite_dir" rev-parse --short HEAD >/dev/null 2>&1; then
    commit=$(git -C "$suite_dir" rev-parse --short HEAD)
    git -C "$suite_dir" diff --quiet HEAD -- 2>/dev/null || commit="$commit (with uncommitted changes)"
  fi
  {
    echo "date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
    echo "commit: $commit"
    echo "host: $(uname -n) ($(nproc) cores)"
    echo "pmrender: $pmrender ($("$pmrender" --version))"
    echo "suite: $2"
    echo
    "$pmrender" devices || true
  } >"$1/environment.txt"
  cat "$1/environment.txt"
}

# suite_run NAME ARGS...: one pmrender bench, text to $out/NAME.txt, JSON to $out/NAME.json; the
# text goes through the command in suite_show (default cat). Counts failures in `failed` and
# appends NAME to `runs`.
suite_run() {
  local name=$1; shift
  echo
  echo "== $name: pmrender bench $*"
  local rc=0
  "$pmrender" bench "$@" --json "$out/$name.json" >"$out/$name.txt" 2>"$out/$name.err" || rc=$?
  ${suite_show:-cat} <"$out/$name.txt" || true
  if [ "$rc" -ne 0 ]; then
    echo "FAILED (exit $rc): $(cat "$out/$name.err")"
    failed=$((failed + 1))
  fi
  [ -s "$out/$name.err" ] || rm -f "$out/$name.err"
  runs+=("$name")
}

# suite_failed_row NAME CELLS: for a run that printed no results, its summary row ("failed: " and
# the first line of its error, then CELLS empty cells), returning 0; returns 1 for a good run.
suite_failed_row() {
  grep -q '^frames per second' "$out/$1.txt" 2>/dev/null && return 1
  printf '| %s | failed: %s |%s\n' "$1" "$(head -n 1 "$out/$1.err" 2>/dev/null)" "$(printf '%*s' "$2" '' | tr ' ' '|')"
  return 0
}
