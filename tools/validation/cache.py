"""Cache of SUMO's reference runs. An entry holds the output files of one finished SUMO run and its run record;
it is found by a key hashing everything that decides SUMO's result: the contents of the scenario folder, the
cfg's name, the car-following model, seed, end, step length and the first line of `sumo --version`."""
import hashlib
import json
import os
import shutil
import subprocess

# Bump when the way validate.py runs SUMO or what it keeps of a run changes: older entries then stop matching.
CACHE_FORMAT = 1
CACHED_ROLES = ("tripinfo", "edgedata", "statistics", "stdout", "stderr", "log")
RECORD = "run.json"


def folder_digest(folder):
    """Hash of the names and contents of every file that runner.mirror_folder copies (hidden folders are left
    out as there). Contents, not sizes and times: a scenario rewritten in place must not match its old entry.
    BLAKE2 in 1 MiB reads keeps this to a fraction of a second for a few MB of scenario."""
    digest = hashlib.blake2b(digest_size=20)
    folder = os.path.abspath(folder)
    for current, subfolders, files in os.walk(folder):
        subfolders[:] = sorted(s for s in subfolders if not s.startswith("."))
        for name in sorted(files):
            path = os.path.join(current, name)
            digest.update(os.path.relpath(path, folder).encode() + b"\0")
            with open(path, "rb") as handle:
                for block in iter(lambda: handle.read(1 << 20), b""):
                    digest.update(block)
            digest.update(b"\0")
    return digest.hexdigest()


def sumo_version(sumo, env=None):
    """First line of `sumo --version` ('Eclipse SUMO sumo Version 1.15.0'); None when it cannot be had."""
    try:
        completed = subprocess.run([sumo, "--version"], env=env, stdout=subprocess.PIPE,
                                   stderr=subprocess.DEVNULL, timeout=60)
    except (OSError, subprocess.SubprocessError):
        return None
    lines = completed.stdout.decode(errors="replace").strip().splitlines()
    return lines[0].strip() if completed.returncode == 0 and lines else None


def cache_key(folder_hash, cfg_name, model, seed, end, step_length, version):
    """Hex key of one reference run. end None = the cfg runs until the network is empty."""
    fields = {"format": CACHE_FORMAT, "folder": folder_hash, "cfg": cfg_name, "model": model, "seed": seed,
              "end": None if end is None else float(end), "step_length": float(step_length),
              "sumo": version}
    return hashlib.sha256(json.dumps(fields, sort_keys=True).encode()).hexdigest()[:24]


def entry_dir(cache_dir, key):
    return os.path.join(cache_dir, key)


def load(cache_dir, key):
    """The cached run record (with 'files' pointing into the entry) or None when there is no complete entry."""
    folder = entry_dir(cache_dir, key)
    try:
        with open(os.path.join(folder, RECORD)) as handle:
            record = json.load(handle)
    except (OSError, ValueError):
        return None
    record["files"] = {role: os.path.join(folder, name) for role, name in record.get("files", {}).items()}
    if not all(os.path.isfile(path) for path in record["files"].values()):
        return None
    return record


def store(cache_dir, key, run, about):
    """Copies the files of a finished SUMO run (run: RunResult.to_json()) into a new entry; about: what the
    key was made of, kept in the record for people reading the cache. Written beside, then renamed, so an
    interrupted store leaves no half entry. Returns the entry folder."""
    folder = entry_dir(cache_dir, key)
    partial = folder + ".partial"
    shutil.rmtree(partial, ignore_errors=True)
    os.makedirs(partial)
    files = {}
    for role in CACHED_ROLES:
        source = run["files"].get(role)
        if source and os.path.isfile(source):
            files[role] = os.path.basename(source)
            shutil.copyfile(source, os.path.join(partial, files[role]))
    record = dict(run, files=files, about=about)
    with open(os.path.join(partial, RECORD), "w") as handle:
        json.dump(record, handle, indent=2, sort_keys=True)
    shutil.rmtree(folder, ignore_errors=True)
    os.rename(partial, folder)
    return folder
