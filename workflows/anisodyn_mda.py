"""An MDAnalysis Universe from an anisodyn H5MD file (docs/file-format.md, "Reading with MDAnalysis").

    import sys; sys.path.insert(0, "<anisodyn>/workflows")
    from anisodyn_mda import universe
    u = universe("trajectory.h5")                 # or universe(path, unwrap=True)
    for ts in u.trajectory:
        ts.positions                # (N, 3) centres, wrapped into the box (unwrapped with unwrap=True)
        ts.data["orientation"]      # (N, 4) float64 unit quaternions (w, x, y, z), body -> lab
        ts.data["image"]            # (N, 3) int32 box crossings: unwrapped = position + image * L
    u.atoms.types                   # species names; u.atoms.masses, u.atoms.ids from the file

`mda.Universe(path)` does not work on these files (MDAnalysis 2.4): the `.h5` extension is not one
it knows, its minimal topology for H5MD only looks at a particle group named `trajectory`, and
without `unit` attributes (anisodyn uses reduced units) it refuses to read with its default
`convert_units=True`. This module builds the topology itself: one atom and one residue per
particle, the species names as atom types, and a transformation that attaches the per-frame data
MDAnalysis does not read. Needs MDAnalysis, h5py and numpy (Debian: python3-mdanalysis).
"""
import warnings

import h5py
import numpy as np

GROUP = "particles/all"


class AnisodynFrameData:
    """MDAnalysis transformation: puts the frame's orientations and images into `ts.data` and, with
    `unwrap`, replaces the wrapped positions by position + image * L (L of that frame's box). Opens
    the file lazily and drops the handle when pickled, so a Universe using it can be pickled too."""

    def __init__(self, path, unwrap=False):
        self.path, self.unwrap = path, unwrap
        self._file = None

    def __getstate__(self):
        return {"path": self.path, "unwrap": self.unwrap, "_file": None}

    def _group(self):
        if self._file is None:
            self._file = h5py.File(self.path, "r")
        return self._file[GROUP]

    def __call__(self, ts):
        group = self._group()
        image = group["image/value"][ts.frame]
        ts.data["orientation"] = group["orientation/value"][ts.frame]
        ts.data["image"] = image
        if self.unwrap:
            lengths = np.diagonal(group["box/edges/value"][ts.frame])
            wrapped = group["position/value"][ts.frame]  # float64: MDAnalysis keeps float32 positions
            ts.positions = wrapped + image * lengths
        return ts


def species_per_particle(path):
    """(species name of each particle, mass of each particle or None, particle ids) from the file;
    the species of a particle must not change over the frames (MDAnalysis types are static)."""
    with h5py.File(path, "r") as f:
        species = f[f"{GROUP}/species/value"][()]
        if np.any(species != species[0]):
            raise ValueError(f"{path}: the species of some particles change between frames; "
                             "MDAnalysis atom types cannot follow that")
        table = f["parameters/species"]
        names = np.array(table["name"].asstr()[()], dtype=object)
        masses = table["mass"][()] if "mass" in table else None
        ids = f[f"{GROUP}/id/value"][0] if "id" in f[GROUP] else np.arange(species.shape[1])
    return names[species[0]], (None if masses is None else masses[species[0]]), ids


def import_mdanalysis():
    """The MDAnalysis module (ImportError when it is not installed), imported without the
    deprecation warnings MDAnalysis 2.4 prints on import."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        import MDAnalysis
    return MDAnalysis


def universe(path, unwrap=False, transformations=()):
    """The trajectory as an MDAnalysis Universe (see the module documentation). `transformations`
    are further MDAnalysis transformations, applied after the one that attaches the anisodyn data
    (MDAnalysis accepts transformations only once per trajectory)."""
    mda = import_mdanalysis()
    types, masses, ids = species_per_particle(path)
    n = len(types)
    u = mda.Universe.empty(n, n_residues=n, atom_resindex=np.arange(n), trajectory=True)
    u.add_TopologyAttr("types", types)
    u.add_TopologyAttr("ids", ids)
    if masses is not None:
        u.add_TopologyAttr("masses", masses)
    # reduced units without `unit` attributes: MDAnalysis must not try to convert them
    u.load_new(path, format="H5MD", convert_units=False)
    u.trajectory.add_transformations(AnisodynFrameData(path, unwrap), *transformations)
    return u
