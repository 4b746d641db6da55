"""Runs SUMO and LPSim on one .sumocfg with the same step length, seed and end, each in its own mirror of
the scenario folder, and times them (CPU of the child process via getrusage, and wall clock)."""
import os
import resource
import shlex
import shutil
import subprocess
import time

from . import parsers

SUMO_HOME_DEFAULT = "/usr/share/sumo"


class RunResult:
    """One simulator run: its command, exit status, timings and the files it was asked to write."""

    def __init__(self, name, command, cwd, files):
        self.name = name
        self.command = command
        self.cwd = cwd
        self.files = files  # role -> absolute path: tripinfo, edgedata, statistics, summary, stdout, stderr
        self.returncode = None
        self.cpu_s = None
        self.wall_s = None
        self.error = None  # one line when the run could not start, failed or timed out
        self.message = None  # a failed run's most telling output line (its error message)

    def to_json(self):
        return {"command": self.command, "cwd": self.cwd, "files": self.files, "returncode": self.returncode,
                "cpu_s": self.cpu_s, "wall_s": self.wall_s, "error": self.error, "message": self.message}


def mirror_folder(source_dir, target_dir):
    """Recreates source_dir as target_dir with a copy of every file. A simulator run from the mirror reads
    copies of the inputs and writes the outputs that the cfg or add-files name relatively (detector and
    edgeData files, logs) into the mirror: the scenario folders may be read-only and must stay clean.
    Copies, not links: an output whose name is also a file the scenario ships (a detector file, say) would
    be written through a link into the scenario folder, replacing that file."""
    source_dir = os.path.abspath(source_dir)
    for folder, subfolders, files in os.walk(source_dir):
        relative = os.path.relpath(folder, source_dir)
        destination = os.path.normpath(os.path.join(target_dir, relative))
        os.makedirs(destination, exist_ok=True)
        for name in files:
            copy = os.path.join(destination, name)
            if os.path.lexists(copy):
                os.remove(copy)  # a link left by an older mirror must not be written through
            shutil.copyfile(os.path.join(folder, name), copy)
        subfolders[:] = [s for s in subfolders if not s.startswith(".")]
    return target_dir


def output_files(run_dir, with_statistics):
    files = {
        "tripinfo": os.path.join(run_dir, "tripinfo.xml"),
        "edgedata": os.path.join(run_dir, "edgedata.xml"),
        "summary": os.path.join(run_dir, "summary.xml"),
        "stdout": os.path.join(run_dir, "stdout.txt"),
        "stderr": os.path.join(run_dir, "stderr.txt"),
    }
    if with_statistics:
        files["statistics"] = os.path.join(run_dir, "statistics.xml")
        files["log"] = os.path.join(run_dir, "sumo.log")
        files["edgedata_add"] = os.path.join(run_dir, "edgedata.add.xml")
    return files


def _time_options(end, step_length, seed):
    options = ["--step-length", _number(step_length), "--seed", str(seed)]
    if end is not None:
        options += ["--end", _number(end)]
    return options


def _number(value):
    """3600.0 -> '3600', 0.5 -> '0.5' (both simulators accept either; this keeps commands readable)."""
    return str(int(value)) if float(value).is_integer() else repr(float(value))


def write_edgedata_additional(path, edgedata_file):
    """An additional file declaring one whole-run edgeData output. SUMO 1.15's --edgedata-output writes an
    empty file when the simulation begins after 0 (its interval starts at 0), so SUMO gets this instead;
    an additional edgeData spans begin..end of the run, the same one interval."""
    from xml.sax.saxutils import quoteattr
    with open(path, "w") as handle:
        handle.write('<additional>\n    <edgeData id="validate_edgedata" file=%s excludeEmpty="false"/>\n'
                     '</additional>\n' % quoteattr(edgedata_file))
    return path


def cfg_additional_files(config, cfg_path):
    """The cfg's additional files as absolute paths next to cfg_path (the mirrored cfg), in their order."""
    value = config["options"].get("additional-files") or config["options"].get("additional") or ""
    folder = os.path.dirname(os.path.abspath(cfg_path))
    names = [name.strip() for name in value.replace(";", ",").split(",") if name.strip()]
    return [name if os.path.isabs(name) else os.path.join(folder, name) for name in names]


def sumo_command(sumo, cfg, files, model, end, step_length, seed, additional_files, extra=()):
    """SUMO with the given default car-following model; all outputs forced to absolute paths in the run
    folder, and the cfg's own <log> redirected there too. additional_files replaces the cfg's list on the
    command line, so it must hold the cfg's own files plus the edgeData one (files["edgedata_add"]). SUMO
    writes no summary: it would slow SUMO down, and --statistic-output already holds the totals."""
    additional = list(additional_files) + [files["edgedata_add"]]
    return ([sumo, "-c", cfg, "--default.carfollowmodel", model,
             "--additional-files", ",".join(additional), "--tripinfo-output", files["tripinfo"],
             "--statistic-output", files["statistics"], "--log", files["log"],
             "--no-step-log", "--duration-log.statistics"]
            + _time_options(end, step_length, seed) + list(extra))


def lpsim_command(lpsim, cfg, files, end, step_length, seed, threads, model=None, extra=()):
    """LPSim's CLI mirrors SUMO's option names; it has no statistic-output, so the totals come from its
    summary-output (cumulative counts in the last step) or its printed statistics. model: the default
    car-following model, given to LPSim as to SUMO (None: LPSim's default, Krauss as SUMO's)."""
    model_options = ["--default.carfollowmodel", model] if model else []
    return ([lpsim, "run", "-c", cfg, "--tripinfo-output", files["tripinfo"],
             "--edgedata-output", files["edgedata"], "--summary-output", files["summary"],
             "--threads", str(threads)] + model_options
            + _time_options(end, step_length, seed) + list(extra))


def run_timed(result, env=None, timeout=None):
    """Runs result.command in result.cwd, stdout/stderr to files; fills returncode, cpu_s (user + system time
    of the finished child, from RUSAGE_CHILDREN before/after: runs are sequential, so the difference is this
    child alone), wall_s and error."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    try:
        with open(result.files["stdout"], "w") as out, open(result.files["stderr"], "w") as err:
            completed = subprocess.run(result.command, cwd=result.cwd, env=env, stdout=out, stderr=err,
                                       timeout=timeout)
        result.returncode = completed.returncode
    except FileNotFoundError as missing:
        result.error = "cannot start: %s" % missing
    except PermissionError as denied:
        result.error = "cannot start: %s" % denied
    except subprocess.TimeoutExpired:
        result.error = "timed out after %s s" % timeout
    if result.error is not None and result.returncode is None and not result.error.startswith("timed out"):
        return result  # never started: no times to report
    result.wall_s = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    result.cpu_s = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if result.error is None and result.returncode != 0:
        result.message = _last_error_line(result.files)
        result.error = "exit status %d: %s" % (result.returncode, result.message)
    return result


def _last_error_line(files):
    """The most telling line of a failed run: the last 'error' line of stderr, else of stdout, else the last
    non-empty line of either."""
    outputs = []
    for role in ("stderr", "stdout"):
        try:
            with open(files[role], errors="replace") as handle:
                outputs.append([line.strip() for line in handle if line.strip()])
        except OSError:
            outputs.append([])
    for lines in outputs:
        for line in reversed(lines):
            if "error" in line.lower():
                return line[:300]
    lines = outputs[0] + outputs[1]
    return lines[-1][:300] if lines else "no output"


def sumo_env(sumo_home):
    env = dict(os.environ)
    env["SUMO_HOME"] = sumo_home or env.get("SUMO_HOME") or SUMO_HOME_DEFAULT
    return env


def describe(command):
    return " ".join(shlex.quote(part) for part in command)


def load_outputs(result, is_sumo, off_road_vtypes=frozenset()):
    """Parses a finished run's files into {'trips', 'edges', 'stats', 'cpu_s'}; raises ValueError with the
    reason when the tripinfo or edgeData file is missing or unreadable. Trips of off_road_vtypes are counted
    apart (parsers.parse_tripinfo)."""
    files = result.files
    for role in ("tripinfo", "edgedata"):
        if not parsers.file_exists(files[role]):
            raise ValueError("no %s output (%s)" % (role, files[role]))
    try:
        trips = parsers.parse_tripinfo(files["tripinfo"], off_road_vtypes)
        edges = parsers.parse_edgedata(files["edgedata"])
    except Exception as bad:  # ParseError, bad numbers: report, do not abort the other scenarios
        raise ValueError("unreadable output: %s" % bad)
    stats = {}
    # Sources from least to most authoritative; later ones overwrite.
    if parsers.file_exists(files.get("summary")):
        try:
            stats.update(parsers.parse_summary_last(files["summary"]))
        except Exception:
            pass
    with open(files["stdout"], errors="replace") as handle:
        stats.update(parsers.parse_statistics_text(handle.read()))
    if is_sumo and parsers.file_exists(files.get("statistics")):
        stats.update(parsers.parse_statistic_output(files["statistics"]))
    return {"trips": trips, "edges": edges, "stats": stats, "cpu_s": result.cpu_s}
