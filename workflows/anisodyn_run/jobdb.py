"""The campaign's job database: <campaign>/.anisodyn/jobs.json, rewritten atomically after every
change. It records each job's state (pending, running, done, up-to-date, failed, blocked,
interrupted), timings, exit code and log paths, plus a cache of input file hashes keyed by
(size, mtime) so that unchanged multi-GB inputs are hashed once."""
import hashlib
import json
import os

DIR = ".anisodyn"


def atomic_write_text(path, text):
    tmp = path + ".partial"
    with open(tmp, "w") as f:
        f.write(text)
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)


class JobDb:
    def __init__(self, campaign):
        self.path = os.path.join(campaign, DIR, "jobs.json")
        self.data = {"jobs": {}, "hashes": {}}
        if os.path.exists(self.path):
            try:
                with open(self.path) as f:
                    self.data = json.load(f)
            except (OSError, json.JSONDecodeError):
                pass  # a damaged database is rebuilt from the stamps beside the outputs
        self.data.setdefault("jobs", {})
        self.data.setdefault("hashes", {})

    def job(self, jid):
        return self.data["jobs"].setdefault(jid, {})

    def update(self, jid, **fields):
        self.job(jid).update(fields)

    def save(self):
        os.makedirs(os.path.dirname(self.path), exist_ok=True)
        atomic_write_text(self.path, json.dumps(self.data, indent=1, sort_keys=True))

    def sha256(self, path):
        st = os.stat(path)
        key = os.path.abspath(path)
        cached = self.data["hashes"].get(key)
        if cached and cached[0] == st.st_size and cached[1] == st.st_mtime_ns:
            return cached[2]
        h = hashlib.sha256()
        with open(path, "rb") as f:
            for chunk in iter(lambda: f.read(1 << 22), b""):
                h.update(chunk)
        self.data["hashes"][key] = [st.st_size, st.st_mtime_ns, h.hexdigest()]
        return h.hexdigest()

