#!/usr/bin/env bash
# Bad input to anisodyn-dmc: each case must exit with code 2, name the file and JSON path (or the
# cause), and leave no output (nor a .partial or checkpoint) behind.
set -uo pipefail
bin=$1; tmp=$2
source "$(dirname "${BASH_SOURCE[0]}")/expect_bad.sh"
rm -rf "$tmp"; mkdir -p "$tmp"; cd "$tmp"

cat > config.json <<'JSON'
{"seed": 3,
 "species": [{"name": "hs", "shape": {"type": "sphere", "diameter": 1}, "D_trans": [0.106, 0.106, 0.106]},
             {"name": "probe", "shape": {"type": "sphere", "diameter": 1}, "D_trans": [0.106, 0.106, 0.106]}],
 "composition": [{"species": "hs", "count": 30}, {"species": "probe", "count": 1}], "box": {"edges": [12, 12, 12]}}
JSON
"$bin/anisodyn-config" -q --config config.json --output state.h5 || { echo "setup failed"; exit 1; }
good='{"seed": 1, "cycles": 10, "time_step": {"hs": 0.01}, "balance": {"reference": "hs", "preliminary_cycles": 5}}'
echo "$good" > good.json
"$bin/anisodyn-dmc" -q --config good.json --input state.h5 --output good.h5 >/dev/null || { echo "FAIL: the good configuration does not run"; exit 1; }

dmc() { local cfg=$1 out=$2; shift 2; echo "$cfg" > "$out.json"; "$bin/anisodyn-dmc" -q --config "$out.json" --input state.h5 --output "$out" "$@"; }
run_bad() { local name=$1 pattern=$2 cfg=$3 out=$4; echo "$cfg" > "$out.json"
  expect_bad "$name" "$pattern" "$out" -- "$bin/anisodyn-dmc" -q --config "$out.json" --input state.h5 --output "$out"; }

run_bad "unknown species" "o1.h5.json.*time_step\.rod.*unknown species 'rod'" \
  '{"cycles": 10, "time_step": {"rod": 0.01}}' o1.h5
run_bad "negative Peclet number" "o2.h5.json.*tracer\.pe.*≥ 0" \
  '{"cycles": 10, "time_step": {"probe": 0.01}, "tracer": {"species": "probe", "pe": -1}}' o2.h5
run_bad "schedule out of order" "o3.h5.json.*schedule\.switches\[1\]\.cycle.*increasing order" \
  '{"cycles": 100, "time_step": {"hs": 0.01}, "balance": {"reference": "hs"}, "field": {"dipoles": {"gamma": 1, "species": ["hs"]}},
    "schedule": {"switches": [{"cycle": 50, "field": "on"}, {"cycle": 20, "field": "off"}]}}' o3.h5
run_bad "tracer missing (no such species)" "o4.h5.json.*tracer\.species.*unknown species 'tracer'" \
  '{"cycles": 10, "time_step": {"hs": 0.01}, "tracer": {"species": "tracer", "pe": 1}}' o4.h5
run_bad "tracer missing (species has 30 particles)" "o5.h5.json.*tracer\.species.*exactly one particle.*30" \
  '{"cycles": 10, "time_step": {"hs": 0.01}, "tracer": {"species": "hs", "pe": 1}}' o5.h5
run_bad "no run length" "o6.h5.json.*cycles.*run length" '{"time_step": {"hs": 0.01}}' o6.h5
run_bad "field switched on but none defined" "o7.h5.json.*field.*switches the field on" \
  '{"cycles": 100, "time_step": {"hs": 0.01}, "balance": {"reference": "hs"}, "schedule": {"switches": [{"cycle": 50, "field": "on"}]}}' o7.h5
run_bad "negative time step" "o8.h5.json.*time_step\.hs.*positive" '{"cycles": 10, "time_step": {"hs": -0.01}}' o8.h5
run_bad "unknown key" "o9.h5.json.*unknown key 'cycels'" '{"cycels": 10, "cycles": 10, "time_step": {"hs": 0.01}}' o9.h5
run_bad "several time steps, no reference" "o10.h5.json.*balance\.reference" '{"cycles": 10, "time_step": {"hs": 0.01, "probe": 0.02}}' o10.h5
run_bad "switch after the end" "o11.h5.json.*schedule\.switches.*before the end" \
  '{"cycles": 100, "time_step": {"hs": 0.01}, "balance": {"reference": "hs"}, "field": {"dipoles": {"gamma": 1, "species": ["hs"]}},
    "schedule": {"switches": [{"cycle": 500, "field": "on"}]}}' o11.h5
expect_bad "missing input state" "no_such.h5" o12.h5 -- "$bin/anisodyn-dmc" -q --config good.json --input no_such.h5 --output o12.h5

# A species without diffusion coefficients.
cat > nod.json <<'JSON'
{"species": [{"name": "hs", "shape": {"type": "sphere", "diameter": 1}}], "composition": [{"species": "hs", "count": 8}],
 "box": {"edges": [10, 10, 10]}}
JSON
"$bin/anisodyn-config" -q --config nod.json --output nod.h5 || exit 1
echo '{"cycles": 10, "time_step": {"hs": 0.01}}' > o13.json
expect_bad "no diffusion coefficients" "species\.hs\.D_trans.*diffusion" o13.h5 -- "$bin/anisodyn-dmc" -q --config o13.json --input nod.h5 --output o13.h5

echo "$passed passed, $failures failed"
[[ $failures -eq 0 ]]
