#!/usr/bin/env bash
# Bad input to anisodyn-config and anisodyn-mc: each case must exit with code 2, print a message
# naming the cause, and leave no output file (nor a .partial) behind.
set -uo pipefail
bin=$1; tmp=$2
source "$(dirname "${BASH_SOURCE[0]}")/expect_bad.sh"
rm -rf "$tmp"; mkdir -p "$tmp"; cd "$tmp"

good_config='{"seed": 3, "species": [{"name": "hs", "shape": {"type": "sphere", "diameter": 1}}],
  "composition": [{"species": "hs", "count": 64}], "box": {"packing_fraction": 0.1}}'
good_mc='{"seed": 4, "phases": [{"type": "nvt", "cycles": 10}]}'
echo "$good_config" > good_config.json
echo "$good_mc" > good_mc.json
"$bin/anisodyn-config" -q --config good_config.json --output state.h5 || { echo "setup failed"; exit 1; }


echo '{"species": [ {"name": "hs", ' > malformed.json
expect_bad "malformed JSON" "malformed.json.*line" out1.h5 -- "$bin/anisodyn-config" --config malformed.json --output out1.h5

sed 's/"seed": 3/"sead": 3/' good_config.json > unknown_key.json
expect_bad "unknown key" "unknown_key.json.*sead" out2.h5 -- "$bin/anisodyn-config" --config unknown_key.json --output out2.h5

sed 's/"diameter": 1/"diameter": -1/' good_config.json > negative.json
expect_bad "negative dimension" "species\[0\]\.shape\.diameter.*positive" out3.h5 -- "$bin/anisodyn-config" --config negative.json --output out3.h5

sed 's/"diameter": 1/"diameter": 0/' good_config.json > zero.json
expect_bad "zero dimension" "species\[0\]\.shape\.diameter.*positive" out4.h5 -- "$bin/anisodyn-config" --config zero.json --output out4.h5

cat > cuboid_zero.json <<'JSON'
{"species": [{"name": "b", "shape": {"type": "cuboid", "edges": [1, 0, 12]}}],
 "composition": [{"species": "b", "count": 10}], "box": {"packing_fraction": 0.01}}
JSON
expect_bad "zero cuboid edge" "species\[0\]\.shape\.edges" out5.h5 -- "$bin/anisodyn-config" --config cuboid_zero.json --output out5.h5

cat > unreachable.json <<'JSON'
{"species": [{"name": "hs", "shape": {"type": "sphere", "diameter": 1}}],
 "composition": [{"species": "hs", "count": 300}], "box": {"packing_fraction": 0.6},
 "placement": "random", "max_attempts_per_particle": 2000}
JSON
expect_bad "unreachable packing fraction (random)" "packing_fraction.*cannot be reached.*stuck" out6.h5 -- "$bin/anisodyn-config" --config unreachable.json --output out6.h5

# lattice placement has no use for the insertion bound: drop it with the placement
sed 's/"placement": "random", "max_attempts_per_particle": 2000/"placement": "lattice"/' unreachable.json > unreachable_lattice.json
expect_bad "unreachable packing fraction (lattice)" "packing_fraction.*lattice holds" out7.h5 -- "$bin/anisodyn-config" --config unreachable_lattice.json --output out7.h5

expect_bad "missing input file" "no_such_state.h5" out8.h5 -- "$bin/anisodyn-mc" --config good_mc.json --input no_such_state.h5 --output out8.h5

expect_bad "missing config file" "no_such_config.json" out9.h5 -- "$bin/anisodyn-mc" --config no_such_config.json --input state.h5 --output out9.h5

expect_bad "unwritable output" "cannot write|not writable|does not exist" /nonexistent-dir/out.h5 -- "$bin/anisodyn-mc" --config good_mc.json --input state.h5 --output /nonexistent-dir/out.h5

cp state.h5 overlapping.h5
"${PYTHON:-$(command -v /usr/bin/python3 || command -v python3)}" - <<'PY'
import h5py
with h5py.File("overlapping.h5", "r+") as f:
    pos = f["particles/all/position/value"]
    p = pos[...]
    p[-1, 1, :] = p[-1, 0, :] + 0.5   # particles 0 and 1 now half a diameter apart
    pos[...] = p
PY
expect_bad "overlapping input configuration" "overlapping.h5.*overlap" out10.h5 -- "$bin/anisodyn-mc" --config good_mc.json --input overlapping.h5 --output out10.h5

echo '{"seed": 4, "phases": [{"type": "nvt", "cycles": -5}]}' > negative_cycles.json
expect_bad "negative cycle count" "phases\[0\]\.cycles" out11.h5 -- "$bin/anisodyn-mc" --config negative_cycles.json --input state.h5 --output out11.h5

expect_bad "bad --set override" "set" out12.h5 -- "$bin/anisodyn-mc" --config good_mc.json --set "=3" --input state.h5 --output out12.h5

echo "$passed passed, $failures failed"
[[ $failures -eq 0 ]]
