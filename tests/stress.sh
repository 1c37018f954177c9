#!/usr/bin/env bash
# Run the whole test suite N times in a row (default 5) with demos running
# beside it the whole time, the load a busy CI machine puts on the tests.
# A test that waits on wall time instead of on what it waits for fails here.
#
#   tests/stress.sh [N] [pytest args...]      (after `make build sanitize`)
#
# Results: build/stress/run-K.log per run, build/stress/summary.txt.
set -uo pipefail
cd "$(dirname "$0")/.."
runs=${1:-5}; shift || true
out=build/stress
mkdir -p "$out"
: > "$out/summary.txt"

# Demos one after another until killed (constant load), in a process group of
# their own so that one signal stops the loop, the demo and its children.
demo_loop='k=0; while true; do k=$((k + 1));
    tests/isolated_net.sh .venv/bin/auv-demo --out "$0/demo" > "$0/demo-$k.log" 2>&1; done'

failed=0
loader=
# Stopping this script stops the demos too (they run in their own group).
trap '[[ -n $loader ]] && kill -TERM -- "-$loader" 2>/dev/null' EXIT
trap 'exit 130' INT TERM
for i in $(seq 1 "$runs"); do
    setsid bash -c "$demo_loop" "$out" & loader=$!
    start=$(date +%s)
    # -v: a test that fails is named as it fails, even in a run stopped before its summary
    tests/isolated_net.sh .venv/bin/python -m pytest -v "$@" > "$out/run-$i.log" 2>&1
    rc=$?
    kill -TERM -- "-$loader" 2>/dev/null; wait "$loader" 2>/dev/null; loader=
    line="run $i: exit $rc, $(( $(date +%s) - start )) s: $(tail -1 "$out/run-$i.log")"
    echo "$line" | tee -a "$out/summary.txt"
    [[ $rc -eq 0 ]] || failed=$((failed + 1))
done
echo "$((runs - failed)) of $runs runs passed with demos beside them" | tee -a "$out/summary.txt"
(( failed == 0 ))
