#!/usr/bin/python3
"""Runs SUMO (reference) and LPSim (candidate) on the same SUMO scenarios, with each car-following model asked
for, and compares loaded/inserted/arrived counts, trip durations, edge speeds and teleports against five
targets. Standard library only: run with /usr/bin/python3.

  tools/validate.py [SCENARIO.sumocfg...] [--all [--shared DIR]] [--extra DIR]... [--model IDM|Krauss|both]
                    [--out DIR] [--sumo-cache DIR] [--refresh-sumo] [--lpsim build/lpsim] [--end T]
                    [--threads 2] [--markdown FILE] [--seed S] [--candidate sumo --candidate-model Krauss]

  tools/validate.py --all --extra /tmp/wiz --model both --out /tmp/validation_all

--all takes every scenario folder of ../shared/scenarios (beside the repository): its run.sumocfg where there
is one (other cfgs there are kept for reference only), else its .sumocfg. --extra DIR (repeatable) adds every
DIR/*/osm.sumocfg (osmWebWizard-style, tools/make_wizard_scenarios.py). --model both runs Krauss (SUMO's
default) and IDM, each as --default.carfollowmodel of both simulators.

Targets per (scenario, model), LPSim against SUMO: inserted within 1 %, arrivals within 3 %, mean duration of
the arrived trips within 10 %, per-edge mean speed Pearson r >= 0.85, teleports <= max(2 x SUMO's, 5). Both
sides are counted alike: loaded/inserted/teleports are each simulator's own totals, arrived the tripinfo
elements with an arrival. A scenario LPSim refuses (exit status 2) is a row 'refused: <its error line>' and
misses every target.

SUMO's runs are cached (default OUT/sumo_cache) under a key hashing the scenario folder's file contents, the
cfg's name, model, seed, end, step length and the first line of `sumo --version`; a cached run is reused
unless --refresh-sumo is given. Each simulator runs in its own mirror of the cfg's folder (copies, never
links, through which an output named like a shipped file would overwrite it; cwd = the mirrored cfg folder),
under OUT/<scenario>/<model>/, so outputs the cfg or its add-files name relatively land under --out and the
scenario folder stays untouched. Prints one markdown table (a row per scenario and model) and a line totalling
the targets, and writes OUT/report.md and OUT/results.json with all numbers. A run that is missing or fails is
reported in its row; the other scenarios still run.
"""
import argparse
import os
import shutil
import sys

TOOLS_DIR = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, TOOLS_DIR)

from validation import cache, metrics, parsers, report, runner, scenarios  # noqa: E402

SHARED_SCENARIOS = os.path.join(os.path.dirname(os.path.dirname(TOOLS_DIR)), "shared", "scenarios")


def parse_args(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog="\n\n".join(__doc__.split("\n\n")[2:]))
    parser.add_argument("configs", nargs="*", metavar="SCENARIO_CFG", help=".sumocfg files")
    parser.add_argument("--all", action="store_true",
                        help="every scenario of --shared (run.sumocfg, else the folder's .sumocfg)")
    parser.add_argument("--shared", default=SHARED_SCENARIOS,
                        help="scenario folders for --all (default ../shared/scenarios beside the repository)")
    parser.add_argument("--extra", action="append", default=[], metavar="DIR",
                        help="also every DIR/*/osm.sumocfg (osmWebWizard-style); repeatable")
    parser.add_argument("--lpsim", default="build/lpsim", help="LPSim executable (default build/lpsim)")
    parser.add_argument("--sumo", default="sumo", help="SUMO executable (default sumo)")
    parser.add_argument("--sumo-home", default=None, help="SUMO_HOME (default $SUMO_HOME or /usr/share/sumo)")
    parser.add_argument("--out", default="build/validation", help="output folder (default build/validation)")
    parser.add_argument("--sumo-cache", default=None, help="cache of SUMO's runs (default OUT/sumo_cache)")
    parser.add_argument("--refresh-sumo", action="store_true", help="rerun SUMO even where a cached run matches")
    parser.add_argument("--end", type=float, default=None, help="simulation end for all runs (default: the cfg's)")
    parser.add_argument("--step-length", type=float, default=None, help="step length (default: the cfg's, else 1)")
    parser.add_argument("--seed", type=int, default=23423, help="random seed for both (default 23423, SUMO's)")
    parser.add_argument("--threads", type=int, default=2, help="LPSim threads (default 2)")
    parser.add_argument("--model", default="IDM",
                        help="default car-following model of SUMO and LPSim (--default.carfollowmodel): IDM "
                             "(default), Krauss, or both (Krauss, then IDM)")
    parser.add_argument("--markdown", default=None, help="also write the markdown table here")
    parser.add_argument("--timeout", type=float, default=3600, help="seconds per simulator run (default 3600)")
    parser.add_argument("--weighted-speed", action="store_true",
                        help="weight the edge-speed correlation by time sampled on each edge")
    parser.add_argument("--candidate", choices=("lpsim", "sumo"), default="lpsim",
                        help="what to compare against SUMO; 'sumo' checks the metrics with a second SUMO run")
    parser.add_argument("--candidate-model", default=None, help="with --candidate sumo: its car-following model")
    parser.add_argument("--candidate-seed", type=int, default=None, help="with --candidate sumo: its seed")
    return parser.parse_args(argv)


def collect_configs(args):
    """The cfgs named, then those of --all and of each --extra folder; each once, in that order."""
    configs = list(args.configs)
    if args.all:
        configs += scenarios.shared_configs(args.shared)
    for folder in args.extra:
        configs += scenarios.wizard_configs(folder)
    unique, seen = [], set()
    for cfg in configs:
        if os.path.abspath(cfg) not in seen:
            seen.add(os.path.abspath(cfg))
            unique.append(cfg)
    return unique


def resolve_executable(path):
    """Absolute path for a path with a folder part (runs use other working folders); PATH lookup otherwise."""
    if os.sep in path:
        return os.path.abspath(path)
    return shutil.which(path) or path


def scenario_names(configs):
    """Scenario name = the cfg's folder name; cfgs sharing a folder name get their file stem appended."""
    folders = [os.path.basename(os.path.dirname(os.path.abspath(c))) for c in configs]
    names = []
    for cfg, folder in zip(configs, folders):
        stem = os.path.basename(cfg).rsplit(".sumocfg", 1)[0]
        names.append(folder if folders.count(folder) == 1 else "%s-%s" % (folder, stem))
    return names


def _summary_of(outputs):
    """The per-run figures reported even without a comparison."""
    trips = outputs["trips"]
    return {
        "loaded": outputs["stats"].get("loaded"),
        "inserted": outputs["stats"].get("inserted"),
        "arrived": trips.arrived,
        "teleports": outputs["stats"].get("teleports"),
        "duration": metrics.duration_summary(trips.durations),
        "mean_route_length": metrics.mean(trips.route_lengths),
        "mean_time_loss": metrics.mean(trips.time_losses),
        "edges_in_edgedata": len(outputs["edges"]),
    }


def _prepare(scenario_dir, role, cfg):
    """Run folder for one simulator and the path of the cfg inside its mirror of the scenario folder."""
    run_dir = os.path.join(scenario_dir, role)
    work_dir = os.path.join(run_dir, "work")
    os.makedirs(run_dir, exist_ok=True)
    runner.mirror_folder(os.path.dirname(os.path.abspath(cfg)), work_dir)
    return run_dir, work_dir, os.path.join(work_dir, os.path.basename(cfg))


def _execute(name, role, command_for, cfg, scenario_dir, env, timeout, is_sumo, off_road=frozenset()):
    run_dir, work_dir, mirrored_cfg = _prepare(scenario_dir, role, cfg)
    files = runner.output_files(run_dir, with_statistics=is_sumo)
    for path in files.values():  # stale outputs of an earlier run must not pass for this one's
        if os.path.lexists(path):
            os.remove(path)
    result = runner.RunResult(role, command_for(mirrored_cfg, files), work_dir, files)
    print("[%s] %s: %s" % (name, role, runner.describe(result.command)), file=sys.stderr, flush=True)
    runner.run_timed(result, env=env, timeout=timeout)
    timing = "" if result.cpu_s is None else ", %.1f CPU s, %.1f wall s" % (result.cpu_s, result.wall_s)
    print("[%s] %s: %s%s" % (name, role, result.error or "ok", timing), file=sys.stderr, flush=True)
    outputs, error = None, result.error
    if error is None:
        try:
            outputs = runner.load_outputs(result, is_sumo, off_road)
        except ValueError as bad:
            error = str(bad)
    entry = {"run": result.to_json()}
    if outputs is not None:
        entry["summary"] = _summary_of(outputs)
    return entry, outputs, error


def _cached_reference(name, record, entry_folder, off_road):
    """A cached SUMO run as _execute would have given it; None when its files no longer parse."""
    result = runner.RunResult("sumo", record.get("command"), record.get("cwd"), record["files"])
    result.returncode, result.cpu_s, result.wall_s = record.get("returncode"), record.get("cpu_s"), record.get("wall_s")
    try:
        outputs = runner.load_outputs(result, True, off_road)
    except ValueError:
        return None
    print("[%s] sumo: cached (%s)" % (name, entry_folder), file=sys.stderr, flush=True)
    run = result.to_json()
    run["cached"] = entry_folder
    return {"run": run, "summary": _summary_of(outputs)}, outputs, None


def _reference(name, cfg, model, end, step_length, command, scenario_dir, env, args, sumo_cache, off_road):
    """SUMO's run: from the cache where an entry matches (and --refresh-sumo is not given), else run and, when it
    succeeded, stored. sumo_cache: {'dir', 'version', 'folder_hash'}, or None to run without the cache.
    off_road: vTypes whose trips are counted apart (parsers.off_road_vtypes)."""
    key = None
    if sumo_cache:
        key = cache.cache_key(sumo_cache["folder_hash"], os.path.basename(cfg), model, args.seed, end,
                              step_length, sumo_cache["version"])
        record = None if args.refresh_sumo else cache.load(sumo_cache["dir"], key)
        found = record and _cached_reference(name, record, cache.entry_dir(sumo_cache["dir"], key), off_road)
        if found:
            return found
    entry, outputs, error = _execute(name, "sumo", command, cfg, scenario_dir, env, args.timeout, True, off_road)
    if key and error is None:
        about = {"scenario": name, "cfg": os.path.abspath(cfg), "model": model, "seed": args.seed, "end": end,
                 "step_length": step_length, "sumo": sumo_cache["version"],
                 "folder_hash": sumo_cache["folder_hash"]}
        cache.store(sumo_cache["dir"], key, entry["run"], about)
    return entry, outputs, error


def run_scenario(cfg, name, model, args, env, sumo_cache=None):
    """One (scenario, model) pair: SUMO (perhaps cached) and the candidate, and their comparison."""
    config = parsers.read_sumocfg(cfg)
    end = args.end if args.end is not None else config["end"]
    step_length = args.step_length or config["step_length"] or 1.0
    scenario_dir = os.path.join(os.path.abspath(args.out), name, model)
    sumo = resolve_executable(args.sumo)

    def sumo_with(sumo_model, seed):
        def command(mirrored_cfg, files):
            runner.write_edgedata_additional(files["edgedata_add"], files["edgedata"])
            return runner.sumo_command(sumo, mirrored_cfg, files, sumo_model, end, step_length, seed,
                                       runner.cfg_additional_files(config, mirrored_cfg))
        return command

    if args.candidate == "sumo":
        candidate_label = "sumo-candidate"
        candidate_command = sumo_with(args.candidate_model or model,
                                      args.seed if args.candidate_seed is None else args.candidate_seed)
    else:
        candidate_label = "lpsim"
        lpsim = resolve_executable(args.lpsim)
        candidate_command = (lambda mirrored_cfg, files: runner.lpsim_command(
            lpsim, mirrored_cfg, files, end, step_length, args.seed, args.threads, model))

    entry = {"scenario": name, "model": model, "cfg": os.path.abspath(cfg), "end": end, "cfg_end": config["end"],
             "step_length": step_length, "seed": args.seed, "cfg_outputs": config["outputs"]}
    # Trains and ships, which LPSim leaves out by design, are left out of SUMO's figures (counted apart).
    off_road = frozenset(parsers.off_road_vtypes(cfg, config))
    reference, ref_outputs, ref_error = _reference(name, cfg, model, end, step_length, sumo_with(model, args.seed),
                                                   scenario_dir, env, args, sumo_cache, off_road)
    candidate, cand_outputs, cand_error = _execute(name, candidate_label, candidate_command, cfg, scenario_dir,
                                                   env, args.timeout, args.candidate == "sumo")
    entry["reference"], entry["candidate"] = reference, candidate
    entry["reference_error"] = "SUMO: %s" % ref_error if ref_error else None
    entry["candidate_error"] = "%s: %s" % (candidate_label, cand_error) if cand_error else None
    if args.candidate == "lpsim" and candidate["run"]["returncode"] == 2:
        # LPSim's exit status for input it does not take; the line without the mirror's folder
        entry["refused"] = (candidate["run"]["message"] or "").replace(candidate["run"]["cwd"] + os.sep, "")
    entry["comparison"] = None
    if ref_outputs is not None and cand_outputs is not None:
        entry["comparison"] = metrics.compare_runs(ref_outputs, cand_outputs, args.weighted_speed)
    return entry


def reference_cache(args, cfg):
    """The cache context for cfg's scenario, or None when SUMO's version cannot be read (runs are then not
    cached: the key would not tell SUMO versions apart)."""
    if args.sumo_version is None:
        return None
    return {"dir": os.path.abspath(args.sumo_cache or os.path.join(args.out, "sumo_cache")),
            "version": args.sumo_version, "folder_hash": cache.folder_digest(os.path.dirname(os.path.abspath(cfg)))}


def run_all(configs, models, args, env):
    """Entries for every (scenario, model) pair, scenario by scenario."""
    entries = []
    for cfg, name in zip(configs, scenario_names(configs)):
        try:
            sumo_cache = reference_cache(args, cfg)
        except OSError as unreadable:
            print("validate: %s: not cached: %s" % (name, unreadable), file=sys.stderr)
            sumo_cache = None
        for model in models:
            try:
                entries.append(run_scenario(cfg, name, model, args, env, sumo_cache))
            except Exception as failure:  # a broken cfg must not stop the other scenarios
                entries.append({"scenario": name, "model": model, "cfg": os.path.abspath(cfg), "comparison": None,
                                "reference_error": "validate: %s: %s" % (type(failure).__name__, failure)})
    return entries


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    configs = collect_configs(args)
    if not configs:
        print("validate: no scenario: name .sumocfg files, --all or --extra DIR", file=sys.stderr)
        return 2
    for cfg in configs:
        if not os.path.isfile(cfg):
            print("validate: no such scenario config: %s" % cfg, file=sys.stderr)
            return 2
    os.makedirs(args.out, exist_ok=True)
    env = runner.sumo_env(args.sumo_home)
    args.sumo_version = cache.sumo_version(resolve_executable(args.sumo), env)
    if args.sumo_version is None:
        print("validate: cannot read `%s --version`: SUMO's runs are not cached" % args.sumo, file=sys.stderr)
    models = scenarios.model_list(args.model)
    entries = run_all(configs, models, args, env)
    if args.candidate == "sumo":
        candidate_label = "SUMO %s seed %s" % (args.candidate_model or "(same model)",
                                               args.seed if args.candidate_seed is None else args.candidate_seed)
    else:
        candidate_label = "LPSim"
    table = report.markdown_table(entries, "%s, seed %d" % (args.sumo_version or "SUMO", args.seed),
                                  candidate_label)
    sys.stdout.write(table)
    for path in filter(None, (args.markdown, os.path.join(args.out, "report.md"))):
        with open(path, "w") as handle:
            handle.write(table)
    report.write_json(os.path.join(args.out, "results.json"), {
        "targets": {"inserted_tolerance": metrics.INSERTED_TOLERANCE,
                    "arrived_tolerance": metrics.ARRIVED_TOLERANCE,
                    "duration_tolerance": metrics.DURATION_TOLERANCE, "speed_r_min": metrics.SPEED_R_MIN,
                    "teleports_max": "max(%d x reference, %d)" % (metrics.TELEPORTS_FACTOR, metrics.TELEPORTS_FLOOR)},
        "totals": metrics.tally([(e.get("comparison") or {}).get("targets") for e in entries]),
        "reference": {"simulator": "sumo", "version": args.sumo_version, "models": models, "seed": args.seed},
        "candidate": {"simulator": args.candidate, "label": candidate_label},
        "scenarios": entries,
    })
    return 0


if __name__ == "__main__":
    sys.exit(main())
