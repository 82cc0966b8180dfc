#!/usr/bin/env bash
# Build (once) a minimal LAMMPS with the DPD-BASIC package (and OPENMP when it
# builds) from Debian's *source* package, outside the repository, and print the
# path of the resulting `lmp` binary.
#
#   bench/peers/lammps.sh            # builds on first call, then only prints the path
#   LMP=$(bench/peers/lammps.sh)     # typical use from a benchmark script
#
# Cache folder: $ANISODYN_PEER_CACHE (default $HOME/.cache/anisodyn-peers).
#   $CACHE/lammps/bin/lmp    installed binary
#   $CACHE/lammps-src/       Debian source package, build tree and logs
#   $CACHE/apt/              private apt configuration (deb-src list, indices)
# Nothing is written to the repository and /etc/apt is not modified.
#
# Environment knobs:
#   ANISODYN_PEER_CACHE      cache folder (see above)
#   ANISODYN_PEER_JOBS       make jobs (default 2, never more than 2 is advised here)
#   ANISODYN_DEBIAN_MIRROR   Debian mirror for the deb-src line (default deb.debian.org)
#   ANISODYN_DEBIAN_SUITE    suite for the deb-src line (default: this system's codename)
#
# Exit codes: 0 = binary available (path on stdout); 77 = cannot build (skip);
# anything else = unexpected failure.
set -euo pipefail

CACHE=${ANISODYN_PEER_CACHE:-${HOME}/.cache/anisodyn-peers}
PREFIX=$CACHE/lammps
LMP=$PREFIX/bin/lmp
JOBS=${ANISODYN_PEER_JOBS:-2}
MIRROR=${ANISODYN_DEBIAN_MIRROR:-http://deb.debian.org/debian}

log() { printf 'lammps.sh: %s\n' "$*" >&2; }
skip() {
    log "SKIP: cannot build LAMMPS: $*"
    exit 77
}

# Idempotent fast path.
if [[ -x $LMP ]]; then
    printf '%s\n' "$LMP"
    exit 0
fi

command -v apt-get >/dev/null 2>&1 || skip "apt-get not found (Debian/Ubuntu required)"

NICE=()
command -v nice >/dev/null 2>&1 && NICE=(nice -n 15)

SUDO=()
if [[ $(id -u) -ne 0 ]]; then
    if command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
        SUDO=(sudo -n)
    else
        SUDO=(__no_root__)
    fi
fi

# --- build prerequisites (Debian packages only) -----------------------------
# The minimal build (core + DPD-BASIC + OPENMP, no MPI/FFT/JPEG/PNG/Python)
# needs only a C++ compiler with OpenMP (libgomp ships with g++), cmake, make,
# and dpkg-source/xz to unpack the Debian source package.
missing=()
command -v cmake >/dev/null 2>&1 || missing+=(cmake)
command -v g++ >/dev/null 2>&1 || missing+=(g++)
command -v make >/dev/null 2>&1 || missing+=(make)
command -v dpkg-source >/dev/null 2>&1 || missing+=(dpkg-dev)
command -v xz >/dev/null 2>&1 || missing+=(xz-utils)
if ((${#missing[@]})); then
    [[ ${SUDO[0]:-} == __no_root__ ]] && skip "missing build tools (${missing[*]}) and no root/sudo to install them"
    log "installing build prerequisites: ${missing[*]}"
    "${SUDO[@]}" apt-get update >&2 || skip "apt-get update failed (no network?)"
    "${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}" >&2 ||
        skip "apt-get install ${missing[*]} failed"
fi

# --- private apt configuration with a deb-src entry --------------------------
SUITE=${ANISODYN_DEBIAN_SUITE:-}
if [[ -z $SUITE && -r /etc/os-release ]]; then
    SUITE=$(. /etc/os-release && printf '%s' "${VERSION_CODENAME:-}")
fi
SUITE=${SUITE:-bookworm}

APTDIR=$CACHE/apt
mkdir -p "$APTDIR/lists/partial" "$APTDIR/cache/archives/partial" "$APTDIR/sources.list.d"
KEYRING=/usr/share/keyrings/debian-archive-keyring.gpg
if [[ -r $KEYRING ]]; then
    printf 'deb-src [signed-by=%s] %s %s main\n' "$KEYRING" "$MIRROR" "$SUITE" >"$APTDIR/sources.list"
else
    printf 'deb-src %s %s main\n' "$MIRROR" "$SUITE" >"$APTDIR/sources.list"
fi
APT_OPTS=(
    -o "Dir::Etc::SourceList=$APTDIR/sources.list"
    -o "Dir::Etc::SourceParts=$APTDIR/sources.list.d"
    -o "Dir::State::Lists=$APTDIR/lists"
    -o "Dir::Cache=$APTDIR/cache"
)
# Root's download sandbox user (_apt) usually cannot enter $HOME/.cache.
[[ $(id -u) -eq 0 ]] && APT_OPTS+=(-o "APT::Sandbox::User=root")

SRCDIR=$CACHE/lammps-src
mkdir -p "$SRCDIR"
top=$(find "$SRCDIR" -mindepth 2 -maxdepth 2 -name cmake -type d -path "$SRCDIR/lammps-*" | head -n1 || true)
if [[ -z $top ]]; then
    log "fetching the Debian source package index ($SUITE, $MIRROR)"
    # apt-get update exits 0 even when the mirror is unreachable: check for the
    # index itself.
    rm -f "$APTDIR"/lists/*Sources*
    apt-get "${APT_OPTS[@]}" -q update >&2 || true
    compgen -G "$APTDIR/lists/*_Sources*" >/dev/null ||
        skip "could not download the deb-src index from $MIRROR $SUITE (no network?)"
    log "downloading and unpacking the LAMMPS source package into $SRCDIR"
    (cd "$SRCDIR" && apt-get "${APT_OPTS[@]}" -q source lammps) >&2 ||
        skip "apt-get source lammps failed"
    top=$(find "$SRCDIR" -mindepth 2 -maxdepth 2 -name cmake -type d -path "$SRCDIR/lammps-*" | head -n1 || true)
    [[ -n $top ]] || skip "unpacked source package has no cmake/ directory"
fi
LSRC=$(dirname "$top")
log "source tree: $LSRC"

# --- configure and build ----------------------------------------------------
BUILD=$SRCDIR/build
common=(
    -S "$LSRC/cmake" -B "$BUILD"
    -DCMAKE_BUILD_TYPE=Release
    "-DCMAKE_CXX_FLAGS=-march=native"
    "-DCMAKE_INSTALL_PREFIX=$PREFIX"
    -DBUILD_MPI=off
    -DBUILD_SHARED_LIBS=off
    -DBUILD_TOOLS=off
    -DBUILD_DOC=off
    -DBUILD_LAMMPS_SHELL=off
    -DLAMMPS_EXCEPTIONS=off
    -DWITH_JPEG=off -DWITH_PNG=off -DWITH_GZIP=off -DWITH_FFMPEG=off
    -DPKG_KSPACE=off -DPKG_GPU=off -DPKG_KOKKOS=off -DPKG_PYTHON=off
    -DPKG_DPD-BASIC=on
)

build() { # $1 = on/off for OPENMP
    rm -rf "$BUILD"
    "${NICE[@]}" cmake "${common[@]}" -DBUILD_OMP="$1" -DPKG_OPENMP="$1" >"$SRCDIR/cmake-omp-$1.log" 2>&1 || return 1
    "${NICE[@]}" cmake --build "$BUILD" -j "$JOBS" >"$SRCDIR/build-omp-$1.log" 2>&1 || return 1
}

log "configuring and building with DPD-BASIC + OPENMP ($JOBS jobs, niced); logs in $SRCDIR"
if ! build on; then
    log "OpenMP build failed (see $SRCDIR/*-omp-on.log); retrying serial without OPENMP"
    build off || {
        tail -n 30 "$SRCDIR"/build-omp-off.log "$SRCDIR"/cmake-omp-off.log >&2 2>/dev/null || true
        skip "CMake build failed (see $SRCDIR/cmake-omp-off.log and build-omp-off.log)"
    }
fi
cmake --install "$BUILD" >"$SRCDIR/install.log" 2>&1 || skip "cmake --install failed (see $SRCDIR/install.log)"
[[ -x $LMP ]] || skip "build finished but $LMP is missing"

if ! "$LMP" -h 2>/dev/null | grep -w dpd >/dev/null; then  # not -q: an early exit would kill lmp with SIGPIPE (pipefail)
    log "WARNING: $LMP does not list pair style dpd"
fi
printf '%s\n' "$LMP"
