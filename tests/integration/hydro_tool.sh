#!/usr/bin/env bash
# anisodyn-hydro end to end: a species file (JSON and HDF5) from a small configuration, read back by
# anisodyn-config through "diffusion_from"; then bad input: each case exits with code 2, names the
# file and JSON path, and leaves no output behind.
set -uo pipefail
bin=$1; tmp=$2
source "$(dirname "${BASH_SOURCE[0]}")/expect_bad.sh"
rm -rf "$tmp"; mkdir -p "$tmp"; cd "$tmp"

cat > good.json <<'JSON'
{"species": [{"name": "cube", "shape": {"type": "cube", "edge": 1}},
             {"name": "rod", "shape": {"type": "spherocylinder", "length": 2, "diameter": 1}}],
 "shells": {"count": 4, "max_beads": 1500}}
JSON
"$bin/anisodyn-hydro" -q --config good.json --output species.json || { echo "FAIL: the good configuration does not run"; exit 1; }
"$bin/anisodyn-hydro" -q --config good.json --output species.h5 || { echo "FAIL: HDF5 output"; exit 1; }
for f in species.json species.h5; do
  cat > config.json <<JSON
{"seed": 1, "species": [{"name": "cube", "diffusion_from": {"file": "$f", "species": "cube"}}],
 "composition": [{"species": "cube", "count": 8}], "box": {"edges": [6, 6, 6]}}
JSON
  "$bin/anisodyn-config" -q --config config.json --output "state_${f%.*}.h5" || { echo "FAIL: config reading $f"; exit 1; }
done
"$PYTHON" - <<'PY' || { echo "FAIL: species file contents"; exit 1; }
import json, h5py
doc = json.load(open("species.json"))
cube = next(s for s in doc["species"] if s["name"] == "cube")
dt, dr = cube["D_trans"], cube["D_rot"]
assert all(d > 0 for d in dt + dr), (dt, dr)
assert max(dt) / min(dt) - 1 < 1e-9 and max(dr) / min(dr) - 1 < 1e-9, "a cube is isotropic"
assert len(cube["hydro"]["shells"]) == 4
with h5py.File("species.h5") as f:
    assert abs(f["/species/cube/D_trans"][0] - dt[0]) < 1e-15
print("species file ok: cube D_trans", dt[0], "D_rot", dr[0])
PY

run_bad() { local name=$1 pattern=$2 cfg=$3 out=$4; echo "$cfg" > "$out.json"
  expect_bad "$name" "$pattern" "$out" -- "$bin/anisodyn-hydro" -q --config "$out.json" --output "$out"; }

run_bad "unknown shape" "o1.json.json.*species\[0\]\.shape\.type.*(one of|expected)" \
  '{"species": [{"name": "x", "shape": {"type": "torus", "radius": 1}}]}' o1.json
run_bad "non-positive dimension" "o2.json.json.*species\[0\]\.shape\.edges.*positive" \
  '{"species": [{"name": "x", "shape": {"type": "cuboid", "edges": [1, 0, 12]}}]}' o2.json
run_bad "too few beads" "o3.json.json.*shells.*too few beads" \
  '{"species": [{"name": "x", "shape": {"type": "cuboid", "edges": [1, 8, 12]}}], "shells": {"max_beads": 100}}' o3.json
run_bad "too few resolutions" "o4.json.json.*shells\.count.*at least 3" \
  '{"species": [{"name": "x", "shape": {"type": "sphere", "diameter": 1}}], "shells": {"count": 2}}' o4.json
run_bad "too few bead radii" "o5.json.json.*bead_radii.*at least 3" \
  '{"species": [{"name": "x", "shape": {"type": "sphere", "diameter": 1}, "bead_radii": [0.1, 0.05]}]}' o5.json
run_bad "misspelt key" "o6.json.json.*unknown key 'shels'" \
  '{"species": [{"name": "x", "shape": {"type": "sphere", "diameter": 1}}], "shels": {"count": 4}}' o6.json
run_bad "repeated name" "o7.json.json.*species\[1\]\.name.*unique" \
  '{"species": [{"name": "x", "shape": {"type": "sphere", "diameter": 1}}, {"name": "x", "shape": {"type": "sphere", "diameter": 2}}]}' o7.json
run_bad "unknown shell construction" "o8.json.json.*construction.*(one of|expected)" \
  '{"species": [{"name": "x", "shape": {"type": "sphere", "diameter": 1}}], "construction": "voronoi"}' o8.json
run_bad "unknown extrapolation" "o10.json.json.*species\[0\]\.extrapolation.*(one of|expected)" \
  '{"species": [{"name": "x", "shape": {"type": "sphere", "diameter": 1}, "extrapolation": "cubic"}]}' o10.json
run_bad "construction that does not cover the shape" "o9.json.json.*species\[0\]\.construction.*cell_centres shell construction covers" \
  '{"species": [{"name": "x", "shape": {"type": "spherocylinder", "length": 2, "diameter": 1}, "construction": "cell_centres"}]}' o9.json

# The second shell construction runs and says so in the method; the default construction is not named.
# The extrapolation: auto by default (the fit with the smaller error estimate), linear or quadratic
# on request (per species); each species names its fit, and its error estimate names the fit it is
# compared with (the next higher one).
cat > cells.json <<'JSON'
{"species": [{"name": "cube", "shape": {"type": "cube", "edge": 1}, "construction": "cell_centres"},
             {"name": "cube_quadratic", "shape": {"type": "cube", "edge": 1}, "extrapolation": "quadratic"},
             {"name": "cube_linear", "shape": {"type": "cube", "edge": 1}, "extrapolation": "linear"}],
 "shells": {"count": 4, "max_beads": 1500}}
JSON
"$bin/anisodyn-hydro" -q --config cells.json --output cells.json.out.json || { echo "FAIL: cell_centres or quadratic does not run"; exit 1; }
"$PYTHON" - <<'PY' || { echo "FAIL: construction or extrapolation in the species file"; exit 1; }
import json
cells, quad, lin = json.load(open("cells.json.out.json"))["species"]
auto = next(s for s in json.load(open("species.json"))["species"] if s["name"] == "cube")
assert cells["hydro"]["method"].endswith("; shell construction cell_centres"), cells["hydro"]["method"]
assert "construction" not in auto["hydro"]["method"], auto["hydro"]["method"]
# The default: auto, which outputs one of the two fits, the one with the smaller error estimate.
assert auto["hydro"]["extrapolation_rule"] == "auto", auto["hydro"]
fit = auto["hydro"]["extrapolation"]
assert fit in ("linear", "quadratic"), fit
assert "(extrapolation auto: the fit with the smaller error estimate" in auto["hydro"]["method"], auto["hydro"]["method"]
assert ("extrapolated linearly" if fit == "linear" else "extrapolated quadratically") in auto["hydro"]["method"]
same = lin if fit == "linear" else quad
assert all(abs(a / b - 1) < 1e-12 for a, b in zip(auto["D_rot"] + auto["D_trans"], same["D_rot"] + same["D_trans"]))
err = lambda s: max(s["hydro"]["extrapolation_error"]["D_trans"] + s["hydro"]["extrapolation_error"]["D_rot"])
assert abs(err(auto) - min(err(lin), err(quad))) <= 1e-9 * err(auto), (err(auto), err(lin), err(quad))
assert lin["hydro"]["extrapolation"] == "linear", lin["hydro"]["extrapolation"]
assert lin["hydro"]["extrapolation_rule"] == "linear", lin["hydro"]
assert lin["hydro"]["method"].endswith("extrapolated linearly to zero bead radius"), lin["hydro"]["method"]
assert lin["hydro"]["extrapolation_error"]["compared_with"] == "quadratic"
assert quad["hydro"]["extrapolation"] == "quadratic"
assert quad["hydro"]["method"].endswith("extrapolated quadratically to zero bead radius"), quad["hydro"]["method"]
assert quad["hydro"]["extrapolation_error"]["compared_with"] == "cubic"
# Same shells, another fit: the shell table agrees, the extrapolated D do not.
assert all(a["sigma_b"] == b["sigma_b"] and abs(a["D_rot"][0] / b["D_rot"][0] - 1) < 1e-12
           for a, b in zip(quad["hydro"]["shells"], lin["hydro"]["shells"]))
assert abs(quad["D_rot"][0] / lin["D_rot"][0] - 1) > 1e-6, (quad["D_rot"], lin["D_rot"])
PY

cat > bad_from.json <<'JSON'
{"seed": 1, "species": [{"name": "cube", "diffusion_from": {"file": "species.json", "species": "sphere"}}],
 "composition": [{"species": "cube", "count": 8}], "box": {"edges": [6, 6, 6]}}
JSON
expect_bad "species missing from the species file" "bad_from.json.*species\[0\]\.diffusion_from\.species.*no species named 'sphere'" state_bad.h5 -- \
  "$bin/anisodyn-config" -q --config bad_from.json --output state_bad.h5

echo "$passed passed, $failures failed"
[[ $failures -eq 0 ]]
