"""Content comparison of two stage outputs (HDF5): every dataset's values bit for bit, every
attribute, and the group structure, apart from what records when and where a file was made —
datasets named `provenance` and the root attributes `created_utc` and `inputs` (the input paths
and their SHA-256: the input files embed their own provenance, so their hashes differ too). HDF5 files also embed object timestamps, so raw bytes differ between
two runs even when every value is identical; this is the comparison that matters.

    python3 -m anisodyn_run.compare A.h5 B.h5      (exit 0 when equal, 1 with the differences)"""
import sys

IGNORED_DATASETS = {"provenance"}
IGNORED_ROOT_ATTRS = {"created_utc", "inputs"}


def differences(a_path, b_path):
    import h5py
    import numpy as np
    out = []
    with h5py.File(a_path, "r") as a, h5py.File(b_path, "r") as b:
        def attrs(obj, name, root):
            d = {}
            for k, v in obj.attrs.items():
                if root and k in IGNORED_ROOT_ATTRS:
                    continue
                d[k] = v
            return d

        def same(x, y):
            if isinstance(x, np.ndarray) or isinstance(y, np.ndarray):
                x, y = np.asarray(x), np.asarray(y)
                return x.shape == y.shape and x.dtype == y.dtype and x.tobytes() == y.tobytes() if x.dtype != object else \
                    x.shape == y.shape and all(p == q for p, q in zip(x.ravel(), y.ravel()))
            return x == y

        def walk(ga, gb, path):
            ka, kb = set(ga.keys()), set(gb.keys())
            for k in sorted(ka ^ kb):
                out.append(f"{path}/{k}: only in {'the first' if k in ka else 'the second'}")
            ra, rb = attrs(ga, path, path == ""), attrs(gb, path, path == "")
            for k in sorted(set(ra) | set(rb)):
                if k not in ra or k not in rb or not same(ra[k], rb[k]):
                    out.append(f"{path or '/'}: attribute {k} differs")
            for k in sorted(ka & kb):
                if k in IGNORED_DATASETS:
                    continue
                oa, ob = ga[k], gb[k]
                p = f"{path}/{k}"
                if isinstance(oa, h5py.Group) != isinstance(ob, h5py.Group):
                    out.append(f"{p}: a group in one file, a dataset in the other")
                elif isinstance(oa, h5py.Group):
                    walk(oa, ob, p)
                else:
                    if not same(oa[()], ob[()]):
                        out.append(f"{p}: values differ")
                    for ak in sorted(set(oa.attrs) | set(ob.attrs)):
                        if ak not in oa.attrs or ak not in ob.attrs or not same(oa.attrs[ak], ob.attrs[ak]):
                            out.append(f"{p}: attribute {ak} differs")
        walk(a, b, "")
    return out


if __name__ == "__main__":
    diffs = differences(sys.argv[1], sys.argv[2])
    print("\n".join(diffs) if diffs else "identical (apart from provenance)")
    sys.exit(1 if diffs else 0)
