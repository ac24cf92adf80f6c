#!/usr/bin/env bash
# bench/progressive_suite.sh end to end on the first OpenCL device (PoCL in CI), on the built-in
# Cornell box at 32 x 18: a reference (65536 photons a pass; the suite's 4M take 24 s a pass on
# 2 cores), two time budgets, and a summary whose rows hold numbers; a failing comparison reported
# in its row and the exit code; bad options exit 2 with one line and write nothing.
#
#   tests/bench/progressive_suite_test.sh PMRENDER
set -uo pipefail
pmrender=$1
suite=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../bench" && pwd)/progressive_suite.sh
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

"$suite" --pmrender "$pmrender" --backend opencl --scenes cornell-box --resolution 32x18 --photons 4096 \
  --reference-photons 65536 --times 0.3,1 --reference-time 1 --out "$work/out" >"$work/log" 2>&1 || { cat "$work/log"; fail "suite exit $?"; }
summary=$work/out/summary.md
[ -f "$summary" ] || fail "no summary.md"
rows=$(grep -c '^| opencl | cornell-box |' "$summary")
[ "$rows" -eq 2 ] || { cat "$summary"; fail "expected 2 rows, got $rows"; }
# Each row: budget, render s, passes, passes per second, relMAE, FLIP, two biases, estimate.
while IFS='|' read -r _ _ _ budget seconds passes rate relmae flip mean indirect estimate _; do
  awk -v b="$budget" -v s="$seconds" 'BEGIN { exit !(s + 0 >= b + 0) }' || fail "rendered $seconds s on a $budget s budget"
  [[ $passes =~ ^\ *[1-9][0-9]*\ *$ ]] || fail "passes '$passes'"
  [[ $relmae =~ ^\ *[0-9.]+\ %\ *$ ]] || fail "relMAE '$relmae'"
  [[ $mean =~ ^\ *[-+][0-9.]+%\ *$ && $indirect =~ ^\ *[-+][0-9.]+%\ *$ ]] || fail "biases '$mean' '$indirect'"
  [[ $estimate =~ ^\ *[0-9.]+%\ *$ ]] || fail "estimate '$estimate'"
  : "$rate" "$flip"
done < <(grep '^| opencl | cornell-box |' "$summary")
grep -q 'cornell-box: --method photon --estimator radius' "$summary" || fail "the reference is not named"

# A comparison that fails makes its row say so and the suite exit non-zero.
cat >"$work/broken-compare" <<WRAP
#!/usr/bin/env bash
if [ "\$1" = compare ]; then echo "pmrender: compare broke" >&2; exit 2; fi
exec "$pmrender" "\$@"
WRAP
chmod +x "$work/broken-compare"
if "$suite" --pmrender "$work/broken-compare" --backend opencl --scenes cornell-box --resolution 16x9 --photons 1024 \
     --reference-photons 16384 --times 0.1 --reference-time 0.2 --out "$work/broken" >"$work/broken.log" 2>&1; then
  fail "a failed comparison left the suite's exit code 0"
fi
grep -q '^| opencl | cornell-box | 0.1 | failed: pmrender: compare broke |' "$work/broken/summary.md" ||
  { cat "$work/broken/summary.md"; fail "the failed row does not say so"; }

for bad in "--times 1,x" "--scenes attic" "--scenes cornell-box --reference-time 1,2" "--photons 0" \
           "--reference-photons 2x" "--frobnicate"; do
  # shellcheck disable=SC2086
  "$suite" --pmrender "$pmrender" $bad --out "$work/bad" >"$work/bad.out" 2>"$work/bad.err"
  rc=$?
  [ "$rc" -eq 2 ] || fail "'$bad': exit $rc, expected 2"
  [ "$(wc -l <"$work/bad.err")" -eq 1 ] || { cat "$work/bad.err"; fail "'$bad': expected one line"; }
  [ ! -e "$work/bad" ] || fail "'$bad': wrote $work/bad"
done
echo "progressive_suite.sh: 2 rows, a failed comparison reported, 6 bad inputs refused"
