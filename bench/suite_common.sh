# The plumbing the benchmark suites share (bench/run_suite.sh, bench/radiosity_suite.sh,
# bench/multi_gpu_suite.sh): finding the pmrender binary, the environment report, one timed
# `pmrender bench` run and the bench scenes with a moving light or camera. Sourced, not
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

# Per scene: how far its light and its camera move over one second (24 frames), in scene units.
suite_light_motion() {
  case $1 in cornell-mcguire) echo "0.6, 0, 0" ;; sponza) echo "8, 0, 0" ;; conference|conference-69k) echo "600, 0, 0" ;;
    sibenik) echo "8, 0, 0" ;; *) return 1 ;; esac
}
suite_camera_motion() {
  case $1 in cornell-mcguire) echo "0.5, 0.2, -0.5" ;; sponza) echo "4, 1, 0" ;; conference|conference-69k) echo "-200, 0, 100" ;;
    sibenik) echo "4, 1, 1" ;; *) return 1 ;; esac
}

# suite_vector_of NAME FILE: the [x, y, z] after the first "NAME": [ ... ] in FILE (within its line).
suite_vector_of() { grep -o "\"$1\": *\[[^]]*\]" "$2" | head -n 1 | sed 's/.*\[//; s/\]//'; }
suite_add() {  # suite_add "x, y, z" "dx, dy, dz"
  awk -v a="$1" -v b="$2" 'BEGIN { split(a, p, ","); split(b, q, ","); printf "%g, %g, %g", p[1] + q[1], p[2] + q[2], p[3] + q[3] }'
}
# suite_animated_scene SCENE KIND DIR [FRAMES]: writes DIR/SCENE-KIND.json and prints its path: the
# bench scene with its light (KIND light) or its camera (KIND camera) moving linearly over frames
# 0..FRAMES (default 24) by the scene's motion, and held after.
suite_animated_scene() {
  local s=$1 kind=$2 src=$suite_dir/scenes/$1.json dst=$3/$1-$2.json track frames=${4:-24}
  local end_time; end_time=$(awk -v f="$frames" 'BEGIN { printf "%g", f / 24 }')
  local light camera
  light=$(grep -o '"lights": *\[{ *"name": *"[^"]*"' "$src" | sed 's/.*"name": *"//; s/"$//')
  if [ "$kind" = light ]; then
    local from; from=$(suite_vector_of position "$src")  # the light's is the first "position"
    track="\"lights\": { \"$light\": { \"position\": { \"interpolation\": \"linear\", \"keys\": [
      { \"time\": 0, \"value\": [$from] }, { \"time\": $end_time, \"value\": [$(suite_add "$from" "$(suite_light_motion "$s")")] } ] } } }"
  else
    camera=$(sed -n '/"camera"/,/}/p' "$src")
    local from; from=$(echo "$camera" | grep -o '"position": *\[[^]]*\]' | sed 's/.*\[//; s/\]//')
    track="\"camera\": { \"position\": { \"interpolation\": \"linear\", \"keys\": [
      { \"time\": 0, \"value\": [$from] }, { \"time\": $end_time, \"value\": [$(suite_add "$from" "$(suite_camera_motion "$s")")] } ] } }"
  fi
  # Mesh paths relative to bench/scenes become absolute; the animation goes before the last brace.
  sed "s#\"file\": *\"\([^/\"][^\"]*\)\"#\"file\": \"$suite_dir/scenes/\1\"#" "$src" | sed '$ d' |
    sed '$ s/$/,/' >"$dst"
  printf '  "animation": { "frame_rate": 24, "frames": [0, %d],\n    %s }\n}\n' "$frames" "$track" >>"$dst"
  echo "$dst"
}
