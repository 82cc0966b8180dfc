#!/usr/bin/env bash
# Build (once) HOOMD-blue 4.8.2 with only the HPMC sphere and convex-polyhedron
# shape modules, -march=native, CPU only, outside the repository, and print the
# folder to put on PYTHONPATH (it holds the `hoomd` package).
#
#   bench/peers/hoomd.sh                      # builds on first call (about 20 min on 2 cores)
#   PYTHONPATH=$(bench/peers/hoomd.sh) python3 -c 'import hoomd.hpmc'
#
# Sources. HOOMD-blue is not a Debian package. The script takes its public
# source, its submodules and pybind11 (Debian's 2.10 is older than the 2.12
# HOOMD 4.8 requires) from git directories under $ANISODYN_PEER_MIRRORS
# (default: ../.mirror beside the checkout), named <owner>+<name>/repo, as the
# `fetch` tool of a development session leaves them. Where a mirror is missing it
# clones from GitHub instead. A submodule whose pinned commit is absent from its
# mirror is taken at the mirror's newest commit (any branch), and the log says so.
#
# Cache folder: $ANISODYN_PEER_CACHE (default $HOME/.cache/anisodyn-peers).
#   $CACHE/hoomd/hoomd/        installed python package (PYTHONPATH=$CACHE/hoomd)
#   $CACHE/hoomd-src/          exported source tree, build tree and logs
#   $CACHE/pybind11/           pybind11 headers and CMake config
# Nothing is written to the repository.
#
# What is trimmed, in the cache copy only: the HPMC shape modules other than
# sphere and convex polyhedron (their sources are left out of the build and their
# export calls out of module.cc); MD, MPCD, metal, tests, MPI, GPU and LLVM off.
#
# Exit codes: 0 = package available (PYTHONPATH entry on stdout); 77 = cannot
# build (skip); anything else = unexpected failure.
set -euo pipefail

root=$(cd "$(dirname "$0")/../.." && pwd)
CACHE=${ANISODYN_PEER_CACHE:-${HOME}/.cache/anisodyn-peers}
MIRRORS=${ANISODYN_PEER_MIRRORS:-$root/../.mirror}
JOBS=${ANISODYN_PEER_JOBS:-2}
TAG=v4.8.2
PYBIND11_TAG=v2.13.6
PREFIX=$CACHE/hoomd
SRCDIR=$CACHE/hoomd-src
TREE=$SRCDIR/hoomd-blue-${TAG#v}
KEEP_SHAPES="sphere convex_polyhedron"

log() { printf 'hoomd.sh: %s\n' "$*" >&2; }
skip() {
    log "SKIP: cannot build HOOMD-blue: $*"
    exit 77
}

python_can_import_hpmc() {
    PYTHONPATH=$PREFIX /usr/bin/python3 -c 'import hoomd, hoomd.hpmc' >/dev/null 2>&1
}

if [[ -d $PREFIX/hoomd ]] && python_can_import_hpmc; then
    printf '%s\n' "$PREFIX"
    exit 0
fi

NICE=()
command -v nice >/dev/null 2>&1 && NICE=(nice -n 15)

# --- Debian packages ----------------------------------------------------------
need=(cmake g++ make git python3-dev python3-numpy libeigen3-dev)
missing=()
for pkg in "${need[@]}"; do
    status=$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null || true)
    [[ $status == "install ok installed" ]] || missing+=("$pkg")
done
if ((${#missing[@]})); then
    SUDO=()
    if [[ $(id -u) -ne 0 ]]; then
        sudo -n true 2>/dev/null || skip "missing ${missing[*]} and no root/sudo to install them"
        SUDO=(sudo -n)
    fi
    log "installing ${missing[*]}"
    "${SUDO[@]}" apt-get update -qq >&2 || skip "apt-get update failed (no network?)"
    "${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
        "${missing[@]}" >&2 || skip "apt-get install ${missing[*]} failed"
fi

# --- sources --------------------------------------------------------------------
# export_repo OWNER/NAME COMMIT-ISH DEST: writes the tree of COMMIT-ISH into DEST,
# from the mirror when there is one, else from a GitHub clone.
export_repo() {
    local slug=$1 rev=$2 dest=$3
    local git_dir=$MIRRORS/${slug/\//+}/repo
    if [[ ! -d $git_dir ]]; then
        git_dir=$SRCDIR/clones/${slug/\//+}.git
        if [[ ! -d $git_dir ]]; then
            log "no mirror of $slug under $MIRRORS; cloning from GitHub"
            git clone -q --bare "https://github.com/$slug.git" "$git_dir" >&2 ||
                { rm -rf "$git_dir"; return 1; }
        fi
    fi
    if ! git --git-dir="$git_dir" cat-file -e "$rev^{commit}" 2>/dev/null; then
        local newest
        newest=$(git --git-dir="$git_dir" rev-list -n 1 --all)
        log "WARNING: $slug has no commit $rev; using its newest commit $newest"
        rev=$newest
    fi
    mkdir -p "$dest"
    git --git-dir="$git_dir" archive "$rev" | tar -x -C "$dest"
}

# submodule_pins: "path owner/name commit" for each submodule HOOMD pins at $TAG.
submodule_pins() {
    local git_dir=$1
    git --git-dir="$git_dir" show "$TAG:.gitmodules" |
        awk '$1 == "path" {path = $3} $1 == "url" {print path, $3}' |
        while read -r path url; do
            [[ $path == hoomd/extern/* ]] || continue # the tutorial is not needed
            local slug=${url#https://github.com/}
            slug=${slug%.git}
            local commit
            commit=$(git --git-dir="$git_dir" ls-tree "$TAG" "$path" | awk '{print $3}')
            printf '%s %s %s\n' "$path" "$slug" "$commit"
        done
}

if [[ ! -f $TREE/CMakeLists.txt ]]; then
    rm -rf "$TREE"
    export_repo glotzerlab/hoomd-blue "$TAG" "$TREE" || skip "no HOOMD-blue source ($TAG)"
    hoomd_git=$MIRRORS/glotzerlab+hoomd-blue/repo
    [[ -d $hoomd_git ]] || hoomd_git=$SRCDIR/clones/glotzerlab+hoomd-blue.git
    while read -r path slug commit; do
        rm -rf "${TREE:?}/$path"
        export_repo "$slug" "$commit" "$TREE/$path" || skip "no source for submodule $path ($slug)"
    done < <(submodule_pins "$hoomd_git")
    printf '%s\n' "$TAG" >"$TREE/.anisodyn-exported"
fi

if [[ ! -f $CACHE/pybind11/share/cmake/pybind11/pybind11Config.cmake ]]; then
    rm -rf "$SRCDIR/pybind11"
    export_repo pybind/pybind11 "$PYBIND11_TAG" "$SRCDIR/pybind11" || skip "no pybind11 source"
    cmake -S "$SRCDIR/pybind11" -B "$SRCDIR/pybind11-build" -DPYBIND11_TEST=OFF \
        -DCMAKE_INSTALL_PREFIX="$CACHE/pybind11" >"$SRCDIR/pybind11.log" 2>&1 &&
        cmake --install "$SRCDIR/pybind11-build" >>"$SRCDIR/pybind11.log" 2>&1 ||
        skip "pybind11 install failed (see $SRCDIR/pybind11.log)"
fi

# --- trim HPMC to the shapes the benchmarks use (cache copy only) -------------------
trim_hpmc() {
    local hpmc=$TREE/hoomd/hpmc
    local all=(convex_polygon simple_polygon spheropolygon polyhedron ellipsoid faceted_ellipsoid
        sphinx union_convex_polyhedron union_faceted_ellipsoid union_sphere convex_polyhedron
        convex_spheropolyhedron sphere)
    local shape
    for shape in "${all[@]}"; do
        [[ " $KEEP_SHAPES " == *" $shape "* ]] && continue
        sed -i -E "/^\s*module_${shape}\.cc\s*$/d" "$hpmc/CMakeLists.txt"
        sed -i -E "/^\s*export_${shape}\(m\);\s*$/d" "$hpmc/module.cc"
    done
    for shape in $KEEP_SHAPES; do
        grep -q "export_${shape}(m);" "$hpmc/module.cc" || return 1
    done
}
trim_hpmc || skip "HPMC trimming did not find the expected module.cc lines"

# --- configure and build ------------------------------------------------------------
BUILD=$SRCDIR/build
log "configuring and building HOOMD-blue $TAG (HPMC: $KEEP_SHAPES; $JOBS jobs, niced); logs in $SRCDIR"
"${NICE[@]}" cmake -S "$TREE" -B "$BUILD" \
    -DCMAKE_BUILD_TYPE=Release \
    "-DCMAKE_CXX_FLAGS=-march=native" "-DCMAKE_C_FLAGS=-march=native" \
    "-DCMAKE_INSTALL_PREFIX=$PREFIX" \
    "-Dpybind11_DIR=$CACHE/pybind11/share/cmake/pybind11" \
    -DPython_EXECUTABLE=/usr/bin/python3 \
    -DENABLE_GPU=off -DENABLE_MPI=off -DENABLE_TBB=off -DENABLE_LLVM=off \
    -DBUILD_HPMC=on -DBUILD_MD=off -DBUILD_MPCD=off -DBUILD_METAL=off -DBUILD_TESTING=off \
    >"$SRCDIR/cmake.log" 2>&1 || {
    tail -n 30 "$SRCDIR/cmake.log" >&2
    skip "CMake configuration failed (see $SRCDIR/cmake.log)"
}
"${NICE[@]}" cmake --build "$BUILD" -j "$JOBS" >"$SRCDIR/build.log" 2>&1 || {
    grep -E "error" "$SRCDIR/build.log" | head -n 20 >&2
    skip "build failed (see $SRCDIR/build.log)"
}
cmake --install "$BUILD" >"$SRCDIR/install.log" 2>&1 || skip "install failed (see $SRCDIR/install.log)"
python_can_import_hpmc || skip "the installed package does not import (PYTHONPATH=$PREFIX python3 -c 'import hoomd.hpmc')"
printf '%s\n' "$PREFIX"
