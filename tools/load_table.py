#!/usr/bin/python3
"""Which scenarios SUMO and LPSim load: for every .sumocfg given (or found under the folders given), sumo
loads it and runs its first second, and `lpsim info` loads it; one markdown row each with both outcomes, LPSim's
refusal (its error line) or its warnings (what it skips, accepts or ignores). Standard library only.

  tools/load_table.py [--lpsim build/lpsim] [--out DIR] CFG_OR_FOLDER...

Each scenario is copied to a scratch folder under --out first (add-files may name outputs beside them).
Typical use (docs/VALIDATION.md, "Everything SUMO runs"):

  tools/load_table.py ../shared/scenarios $SUMO_HOME/tools/game build/wizard_scenarios
"""
import argparse
import os
import re
import shutil
import subprocess
import sys


def find_configs(paths):
    configs = []
    for p in paths:
        if os.path.isfile(p):
            configs.append(os.path.abspath(p))
            continue
        for root, _dirs, files in os.walk(p):
            configs += [os.path.join(root, f) for f in sorted(files) if f.endswith(".sumocfg")]
    return sorted(set(configs))


def one_line(text, limit=400):
    text = " ".join(text.split())
    return text if len(text) <= limit else text[:limit] + " ..."


def check(config, lpsim, out):
    folder = os.path.dirname(config)
    name = os.path.relpath(config, os.path.dirname(folder))
    work = os.path.join(out, name.replace(os.sep, "__"))
    shutil.rmtree(work, ignore_errors=True)
    # The configuration's folder with its subfolders (SUMO's game configurations reach into theirs).
    shutil.copytree(folder, work, symlinks=False, ignore=shutil.ignore_patterns("*.pyc", "__pycache__"))
    cfg = os.path.join(work, os.path.basename(config))
    cwd = work
    env = dict(os.environ, SUMO_HOME=os.environ.get("SUMO_HOME", "/usr/share/sumo"))
    begin = re.search(r'<begin\s+value="([^"]+)"', open(cfg, encoding="utf-8", errors="replace").read())
    end = (float(begin.group(1)) if begin else 0.0) + 1
    sumo = subprocess.run(["sumo", "-c", cfg, "--end", str(end), "--no-step-log", "--duration-log.disable",
                           "--no-warnings", "--tripinfo-output", os.devnull, "--output-prefix", "loadcheck."],
                          cwd=cwd, env=env, capture_output=True, text=True, timeout=1800)
    sumo_errors = [l for l in sumo.stderr.splitlines() if l.startswith("Error")]
    lp = subprocess.run([lpsim, "info", "-c", cfg], cwd=cwd, env=env, capture_output=True, text=True,
                        timeout=1800)
    lp_errors = [l for l in lp.stderr.splitlines() if "error:" in l]
    lp_warnings = [l.replace("lpsim: warning: ", "") for l in lp.stderr.splitlines() if "warning:" in l]
    shutil.rmtree(work, ignore_errors=True)
    return {
        "name": name,
        "sumo": "loads" if sumo.returncode == 0 and not sumo_errors else "refuses: " + one_line(
            " ".join(sumo_errors) or sumo.stderr[-300:]),
        "lpsim": "loads" if lp.returncode == 0 else "refuses: " + one_line(
            " ".join(lp_errors).replace(work + os.sep, "").replace(work, "")),
        "warnings": one_line("; ".join(lp_warnings), 600) if lp.returncode == 0 else "",
    }


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("paths", nargs="+", help=".sumocfg files or folders to search")
    parser.add_argument("--lpsim", default="build/lpsim")
    parser.add_argument("--out", default="build/load_table")
    args = parser.parse_args(argv)
    lpsim = os.path.abspath(args.lpsim)
    os.makedirs(args.out, exist_ok=True)
    out = os.path.abspath(args.out)
    print("| scenario | SUMO 1.15 | LPSim | LPSim's warnings |")
    print("|---|---|---|---|")
    for config in find_configs(args.paths):
        r = check(config, lpsim, out)
        print("| {name} | {sumo} | {lpsim} | {warnings} |".format(**r), flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
