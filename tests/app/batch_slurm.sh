#!/usr/bin/env bash
# `serosa batch --slurm` through a real single-node Slurm cluster (tools/slurm_cluster.sh): a
# small manifest runs as one job array and merges; every run passes and the JUnit XML exists.
# Then a task loses its result (as one killed before it finished, then requeued): the array
# submitted again with --resume runs that one alone, and the others keep theirs.
# usage: batch_slurm.sh SEROSA SOURCE_DIR WORK_DIR
set -euo pipefail
serosa=$1
src=$2
work=$3
rm -rf "$work"
mkdir -p "$work"
cluster="$work/cluster"
trap '"$src/tools/slurm_cluster.sh" stop "$cluster" || true' EXIT
eval "$("$src/tools/slurm_cluster.sh" start "$cluster")"
export SLURM_CONF

cat >"$work/m.toml" <<TOML
title = "slurm"
timeout = 120
throttle = 2
[[run]]
name = "drill"
scene = "$src/config/transfer.toml"
steps = 200
seeds = [1, 2]
[[run]]
name = "plain"
scene = "$src/config/transfer.toml"
steps = 200
golden = "$work/transfer.json"
TOML
# The golden this run is compared with, written by the same binary.
"$serosa" headless "$src/config/transfer.toml" --steps 200 --golden "$work/transfer.json" \
  --update-golden >/dev/null

"$serosa" batch "$work/m.toml" --out "$work/out" --slurm
python3 - "$work/out" <<'PY'
import json, os, sys
out = sys.argv[1]
s = json.load(open(os.path.join(out, "summary.json")))
assert len(s["runs"]) == 3, s
for r in s["runs"]:
    assert r["status"] == "passed", r
assert [r for r in s["runs"] if r["id"] == "plain"][0]["golden"] == "match", s
assert os.path.isfile(os.path.join(out, "junit.xml"))
for i in range(3):  # each array task wrote its log
    assert os.path.isfile(os.path.join(out, "slurm", "task_%d.log" % i)), i
PY

kept="$work/out/runs/plain/result.json"
before=$(stat -c %y "$kept")
sleep 1
rm "$work/out/runs/drill.seed-2/result.json"
"$serosa" batch "$work/m.toml" --out "$work/out" --slurm --resume
[[ $(stat -c %y "$kept") == "$before" ]] || { echo "a finished run ran again" >&2; exit 1; }
[[ -f "$work/out/runs/drill.seed-2/result.json" ]] || { echo "the lost run did not run" >&2; exit 1; }
python3 -c "import json,sys; s=json.load(open(sys.argv[1])); assert s['passed'] == 3, s" \
  "$work/out/summary.json"
echo "slurm batch: passed"
