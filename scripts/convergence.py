#!/usr/bin/python3
"""Mesh convergence of any scene: run it at h, h/2, h/4 (more with
--levels), collect every quantity the run reports, and give for each the
observed order, the Richardson-extrapolated value and the grid convergence
index (GCI).

The mesh and the material points are refined together through 'Mesh/Global
refinements' (each level splits every cell into 2^dim; regions seeded with
'Points per cell' get 2^dim times the points; the CFL time step follows the
cells). Every other parameter is the scene's own, so the answer is that of
the scene as it is shipped or as the --set arguments change it.

Quantities: every scalar line 'label: value' of the run's report.txt (what
the postprocessors compare with references: runouts, errors, peak speeds,
...), and from its statistics file the last row's kinetic energy, mean
speed and centre of mass, and the largest mean speed over the output times
with its time. The 'Done:' line gives the cost of each level (steps,
points, wall time of the steps).

For the three finest levels f1 (finest), f2, f3 with ratio r = 2 (Celik et
al. 2008, J. Fluids Eng. 130, 078001; Roache 1998):
  e21 = f2 - f1, e32 = f3 - f2, R = e21 / e32
  R in (0, 1): monotone convergence, observed order p = ln(1/R) / ln r,
    Richardson f_ext = f1 + (f1 - f2) / (r^p - 1),
    GCI_fine = 1.25 |e21 / f1| / (r^p - 1)   (an error band on f1)
  R < 0: oscillatory (reported, not extrapolated; the spread of the three
    values is given instead); R >= 1: the differences do not shrink
    (diverging, not extrapolated); e21 = e32 = 0: unchanged.
The change between the two finest levels, |f1 - f2| / |f1|, is printed for
every quantity.

Writes DIR/convergence.csv (one row per quantity), DIR/convergence.txt (the
table as printed) and, where matplotlib is available, DIR/convergence.png;
each level's run is in DIR/level-K (its log in DIR/level-K.log).

Usage:
  scripts/convergence.py CASE.prm [MORE.prm ...] [--levels 3]
      [--set "Section/Name=value" ...] [--threads N] [--mpirun N]
      [--out DIR] [--reuse] [--only REGEX] [--mpm EXECUTABLE]
      [--time-step-check] [--points-per-cell-check]
Examples:
  scripts/convergence.py prm/column_collapse.prm --out output-conv-collapse
  scripts/convergence.py prm/flume_usgs.prm --set "Time stepping/End time=1"
  scripts/convergence.py prm/slope_runout.prm --levels 4 --reuse
  scripts/convergence.py prm/column_collapse.prm --points-per-cell-check
(doc/convergence_command.md)."""
import argparse
import csv
import math
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SAFETY_FACTOR = 1.25
NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"


def parse_arguments(argv):
    parser = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0],
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("prm", nargs="+", help="parameter file(s), read in order")
    parser.add_argument("--levels", type=int, default=3,
                        help="number of meshes, each twice as fine as the last (>= 2; default 3)")
    parser.add_argument("--set", action="append", default=[], metavar="ENTRY=VALUE",
                        help="a parameter override passed to every run")
    parser.add_argument("--threads", type=int, default=None, help="threads per rank")
    parser.add_argument("--mpirun", type=int, default=1, help="MPI ranks per run")
    parser.add_argument("--out", default=None,
                        help="folder of the study (default output-convergence-CASE)")
    parser.add_argument("--reuse", action="store_true",
                        help="keep a level whose report.txt and log already exist (finish or extend a study)")
    parser.add_argument("--only", default=None,
                        help="keep only the quantities whose name matches this regular expression")
    parser.add_argument("--mpm", default=os.path.join(ROOT, "build", "release", "mpm"),
                        help="the mpm executable (default build/release/mpm)")
    parser.add_argument("--no-plot", action="store_true", help="skip the PNG")
    parser.add_argument("--time-step-check", action="store_true",
                        help="run the finest level again at half the time step (half the CFL "
                             "number, or half a fixed 'Time step') and give each quantity's "
                             "value there and its change: the levels halve the time step with "
                             "the cells, and a result may depend on the step as much")
    parser.add_argument("--points-per-cell-check", action="store_true",
                        help="run the finest level again with one more point per cell direction "
                             "in every region ('Points per cell' n -> n + 1) and give each "
                             "quantity's value there and its change: the levels keep the points "
                             "per cell, and a result may depend on them as much (a collapse's "
                             "final height moved by 12 %% from 2 x 2 to 3 x 3, "
                             "doc/column_collapse.md)")
    args = parser.parse_args(argv)
    if args.levels < 2:
        parser.error("--levels must be at least 2")
    return args


def mpm_command(args, extra):
    command = [args.mpm] + args.prm
    for entry in args.set:
        command += ["--set", entry]
    command += extra
    if args.threads is not None:
        command += ["--threads", str(args.threads)]
    if args.mpirun > 1:
        command = ["mpirun", "--oversubscribe", "--allow-run-as-root", "-np", str(args.mpirun)] + command
    return command


def scene_parameters(args):
    """The scene's parameters as it runs them, from --print-parameters:
    {'Section/Name': value}."""
    command = [args.mpm, "--print-parameters"] + args.prm
    for entry in args.set:
        command += ["--set", entry]
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"convergence.py: '{' '.join(command)}' failed:\n{result.stderr}")
    path, values = [], {}
    for line in result.stdout.splitlines():
        words = line.split()
        if not words:
            continue
        if words[0] == "subsection":
            path.append(" ".join(words[1:]))
        elif words[0] == "end":
            path.pop()
        elif words[0] == "set":
            name, _, value = line.partition("=")
            values["/".join(path + [name.split(None, 1)[1].strip()])] = value.split("#")[0].strip()
    return values


def base_refinements(parameters):
    """The scene's own 'Mesh/Global refinements'."""
    if "Mesh/Global refinements" not in parameters:
        sys.exit("convergence.py: no 'Mesh/Global refinements' in the parameters")
    return int(parameters["Mesh/Global refinements"])


def half_time_step(parameters):
    """The setting that halves the scene's time step: the CFL number, or the
    fixed 'Time step'."""
    if parameters.get("Time stepping/Time step selection", "cfl") == "cfl":
        name = "Time stepping/CFL number"
    else:
        name = "Time stepping/Time step"
    if name not in parameters:
        sys.exit(f"convergence.py: no '{name}' in the parameters (--time-step-check)")
    return f"{name}={float(parameters[name]) / 2!r}"


def more_points_per_cell(parameters):
    """The settings that seed one more point per cell direction in every
    region of 'Material points' ('Points per cell' n -> n + 1)."""
    settings = []
    for name, value in parameters.items():
        if re.fullmatch(r"Material points/[^/]+/Points per cell", name):
            settings.append(f"{name}={int(value) + 1}")
    if not settings:
        sys.exit("convergence.py: no 'Material points/<region>/Points per cell' in the "
                 "parameters (--points-per-cell-check)")
    return settings


def run_level(args, out, refinements, extra=(), suffix=""):
    directory = os.path.join(out, f"level-{refinements}{suffix}")
    log = directory + ".log"
    report = os.path.join(directory, "report.txt")
    if args.reuse and os.path.exists(report) and os.path.exists(log) and \
            any(line.startswith("Done:") for line in open(log)):
        print(f"  level {refinements}: reusing {directory}", flush=True)
        return directory
    command = mpm_command(args, ["--set", f"Mesh/Global refinements={refinements}",
                                 "--set", f"Output/Directory={directory}",
                                 "--set", "Output/Write particles=false"] + list(extra))
    print(f"  level {refinements}: {' '.join(command)}", flush=True)
    with open(log, "w") as stream:
        result = subprocess.run(command, stdout=stream, stderr=subprocess.STDOUT)
    if result.returncode != 0:
        tail = "".join(open(log).readlines()[-15:])
        sys.exit(f"convergence.py: the run at 'Global refinements = {refinements}' failed "
                 f"(exit code {result.returncode}); its log {log} ends with:\n{tail}")
    return directory


def report_quantities(report):
    """Every 'label: value ...' of the report's lines outside the tables
    (the first number after the label; what follows it, a unit or a time,
    is not read); a line 'a: 1  b: 2' gives 'a' and 'a / b'."""
    quantities = {}
    section = ""
    for line in open(report):
        line = line.rstrip("\n")
        if line.startswith("## "):
            section = line[3:].split(":")[0].strip()
            continue
        if not line or line.startswith("#") or line.startswith(" "):
            continue
        pairs = []
        for segment in re.split(r"\s{2,}", line.strip()):
            m = re.match(r"(.+?):\s+(" + NUMBER + r")(?=\s|,|$)", segment)
            if m:
                pairs.append((m.group(1), m.group(2)))
        first = None
        for label, value in pairs:
            name = label.strip() if first is None else f"{first} / {label.strip()}"
            first = first or label.strip()
            if name in quantities:
                name = f"{name} [{section}]"
            quantities[name] = float(value)
    return quantities


def statistics_quantities(directory):
    name = os.path.join(directory, "statistics")
    if not os.path.exists(name):
        return {}
    header = open(name).readline()
    columns = {}
    for item in re.findall(r"(\d+)(?:-(\d+))? ([^,.]+?)(?: \([^)]*\))?(?=,|\.)", header):
        first, last, label = int(item[0]), int(item[1] or item[0]), item[2].strip()
        columns[label] = list(range(first - 1, last))
    rows = [[float(x) for x in line.split()] for line in open(name)
            if line.strip() and not line.startswith("#")]
    if not rows:
        return {}
    quantities = {}
    last = rows[-1]
    for label in ("kinetic energy", "mean speed", "centre of mass"):
        for i, c in enumerate(columns.get(label, [])):
            suffix = f" {'xyz'[i]}" if len(columns[label]) > 1 else ""
            quantities[f"statistics: {label}{suffix} at the end"] = last[c]
    if "mean speed" in columns and "time" in columns:
        s, t = columns["mean speed"][0], columns["time"][0]
        peak = max(rows, key=lambda r: r[s])
        quantities["statistics: largest mean speed"] = peak[s]
        quantities["statistics: time of the largest mean speed"] = peak[t]
    return quantities


def cost(log):
    for line in open(log):
        if line.startswith("Done:"):
            m = re.search(r"Done: (\d+) steps, (\d+) points, wall time (" + NUMBER +
                          r") s \(steps (" + NUMBER + r") s\)", line)
            if m:
                return {"steps": int(m.group(1)), "points": int(m.group(2)),
                        "wall": float(m.group(3)), "steps_wall": float(m.group(4))}
    return {}


def classify(values, ratio=2.0):
    """Celik et al.'s three-grid procedure on the finest three of values
    (coarse to fine). Returns a dict of the figures (None where they do not
    apply)."""
    f3, f2, f1 = values[-3:] if len(values) >= 3 else (None,) + tuple(values[-2:])
    result = {"status": "", "order": None, "extrapolated": None, "gci": None,
              "change": None, "spread": None}
    scale = max(abs(v) for v in values if v is not None) or 1.0
    tiny = 1e-12 * scale
    e21 = f2 - f1
    result["change"] = abs(e21) / abs(f1) if f1 != 0 else (0.0 if e21 == 0 else math.inf)
    if f3 is None:
        result["status"] = "two levels only"
        return result
    e32 = f3 - f2
    result["spread"] = (max(f1, f2, f3) - min(f1, f2, f3)) / 2
    if abs(e21) <= tiny and abs(e32) <= tiny:
        result.update(status="unchanged", extrapolated=f1, gci=0.0)
    elif abs(e21) <= tiny:
        result.update(status="unchanged on the two finest", extrapolated=f1, gci=0.0)
    elif abs(e32) <= tiny or e21 / e32 >= 1:
        result["status"] = "diverging"
        if abs(e32) > tiny:
            result["order"] = math.log(abs(e32 / e21)) / math.log(ratio)
    elif e21 / e32 < 0:
        result["status"] = "oscillatory"
    else:
        p = math.log(e32 / e21) / math.log(ratio)
        extrapolated = f1 + (f1 - f2) / (ratio ** p - 1)
        gci = SAFETY_FACTOR * abs(e21 / f1) / (ratio ** p - 1) if f1 != 0 else None
        result.update(status="monotone", order=p, extrapolated=extrapolated, gci=gci)
    return result


def fmt(value, spec="{:.6g}"):
    if value is None:
        return "-"
    if isinstance(value, float) and math.isinf(value):
        return "inf"
    return spec.format(value)


def main(argv):
    args = parse_arguments(argv)
    if not (os.path.isfile(args.mpm) and os.access(args.mpm, os.X_OK)):
        sys.exit(f"convergence.py: no mpm executable at {args.mpm} (build it with scripts/run.sh, "
                 "or name one with --mpm)")
    for prm in args.prm:
        if not os.path.isfile(prm):
            sys.exit(f"convergence.py: parameter file {prm} not found")
    case = os.path.splitext(os.path.basename(args.prm[-1]))[0]
    out = args.out or f"output-convergence-{case}"
    os.makedirs(out, exist_ok=True)
    parameters = scene_parameters(args)
    first = base_refinements(parameters)
    levels = list(range(first, first + args.levels))
    print(f"Mesh convergence of {' '.join(args.prm)}: 'Global refinements' {levels[0]}..{levels[-1]} "
          f"(cell size h / 2^k, k = 0..{args.levels - 1}), study in {out}", flush=True)
    directories = [run_level(args, out, k) for k in levels]
    # The finest mesh again with half the time step, or with more points
    # per cell: the levels halve the time step with the cells and keep the
    # points per cell, and a quantity may depend on either as much as on
    # the mesh (doc/convergence_command.md, "The time step" and "The points
    # per cell"). Each check: its settings, the columns of the table and of
    # the CSV, and the quantities of its run.
    checks = []
    if args.time_step_check:
        checks.append({"settings": [half_time_step(parameters)], "suffix": "-half-time-step",
                       "what": "at half the time step", "column": "dt/2",
                       "csv": ["finest_half_time_step", "change_half_time_step"]})
    if args.points_per_cell_check:
        checks.append({"settings": more_points_per_cell(parameters),
                       "suffix": "-more-points-per-cell",
                       "what": "with one more point per cell direction", "column": "n+1",
                       "csv": ["finest_more_points_per_cell", "change_more_points_per_cell"]})
    for check in checks:
        extra = [word for setting in check["settings"] for word in ("--set", setting)]
        directory = run_level(args, out, levels[-1], extra, check["suffix"])
        check["quantities"] = report_quantities(os.path.join(directory, "report.txt"))
        check["quantities"].update(statistics_quantities(directory))
        check["cost"] = cost(directory + ".log")

    per_level = []
    costs = []
    for directory in directories:
        q = report_quantities(os.path.join(directory, "report.txt"))
        q.update(statistics_quantities(directory))
        per_level.append(q)
        costs.append(cost(directory + ".log"))
    names = [n for n in per_level[-1] if all(n in q for q in per_level)
             and all(n in check["quantities"] for check in checks)]
    if args.only:
        names = [n for n in names if re.search(args.only, n)]
    if not names:
        sys.exit("convergence.py: the runs report no quantity in common")

    rows = []
    for name in names:
        values = [q[name] for q in per_level]
        r = classify(values)
        # Each check's value on the finest level, and its change from it.
        r["checks"] = []
        for check in checks:
            value = check["quantities"][name]
            change = abs(value - values[-1]) / abs(values[-1]) \
                if values[-1] != 0 else (0.0 if value == 0 else None)
            r["checks"].append((value, change))
        rows.append((name, values, r))

    lines = []
    lines.append(f"# Mesh convergence: {' '.join(args.prm)}"
                 + "".join(f' --set "{s}"' for s in args.set))
    lines.append("# level k: cell size h/2^k; r = 2; order, extrapolation and GCI (Celik et al. 2008) "
                 "from the three finest levels")
    for k, c in zip(levels, costs):
        if c:
            lines.append(f"# level {k}: {c['points']} points, {c['steps']} steps, "
                         f"{c['steps_wall']:.4g} s of steps")
    header = [f"h/{2 ** (k - first)}" for k in levels] + \
        ["status", "order p", "extrapolated", "GCI fine", "change fine"]
    for check in checks:
        c = check["cost"]
        parts = []
        if c:
            # The points only where the check changes them.
            if c["points"] != costs[-1].get("points"):
                parts.append(f"{c['points']} points")
            parts += [f"{c['steps']} steps", f"{c['steps_wall']:.4g} s of steps"]
        spent = "; " + ", ".join(parts) if parts else ""
        lines.append(f"# finest level again {check['what']} ({', '.join(check['settings'])}): "
                     "its value and the change from the finest level" + spent)
        header += [f"finest, {check['column']}", f"change {check['column']}"]
    width = max(len(n) for n in names)
    lines.append(f"{'quantity':<{width}}  " + "  ".join(f"{h:>12}" for h in header))
    for name, values, r in rows:
        cells = [fmt(v) for v in values] + [
            r["status"], fmt(r["order"], "{:.3g}"), fmt(r["extrapolated"]),
            fmt(None if r["gci"] is None else 100 * r["gci"], "{:.3g} %"),
            fmt(None if r["change"] is None else 100 * r["change"], "{:.3g} %")]
        for value, change in r["checks"]:
            cells += [fmt(value), fmt(None if change is None else 100 * change, "{:.3g} %")]
        lines.append(f"{name:<{width}}  " + "  ".join(f"{c:>12}" for c in cells))
    table = "\n".join(lines)
    print(table)
    with open(os.path.join(out, "convergence.txt"), "w") as stream:
        stream.write(table + "\n")

    with open(os.path.join(out, "convergence.csv"), "w", newline="") as stream:
        writer = csv.writer(stream)
        extra = [column for check in checks for column in check["csv"]]
        writer.writerow(["quantity"] + [f"level_{k}" for k in levels] +
                        ["status", "order", "extrapolated", "gci_fine", "change_fine", "spread"] + extra)
        keys = ("order", "extrapolated", "gci", "change", "spread")
        for name, values, r in rows:
            writer.writerow([name] + [repr(v) for v in values] +
                            [r["status"]] + [("" if r[k] is None else repr(r[k])) for k in keys] +
                            [("" if x is None else repr(x)) for pair in r["checks"] for x in pair])
        writer.writerow(["cost: points"] + [c.get("points", "") for c in costs])
        writer.writerow(["cost: steps"] + [c.get("steps", "") for c in costs])
        writer.writerow(["cost: wall time of the steps (s)"] + [c.get("steps_wall", "") for c in costs])

    if not args.no_plot:
        plot(rows, levels, first, case, os.path.join(out, "convergence.png"))


def plot(rows, levels, first, case, png):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("(no matplotlib: no plot)")
        return
    shown = rows[:16]
    n = len(shown)
    columns = min(4, n)
    lines = (n + columns - 1) // columns
    fig, axes = plt.subplots(lines, columns, figsize=(4 * columns, 3.0 * lines), squeeze=False)
    h = [1.0 / 2 ** (k - first) for k in levels]
    for ax, (name, values, r) in zip(axes.flat, shown):
        ax.plot(h, values, "o-", color="C0")
        if r["extrapolated"] is not None:
            ax.axhline(r["extrapolated"], color="C3", linestyle="--", linewidth=1,
                       label=f"extrapolated, p = {fmt(r['order'], '{:.2g}')}")
            if r["gci"]:
                band = r["gci"] * abs(values[-1])
                ax.axhspan(values[-1] - band, values[-1] + band, color="C3", alpha=0.12,
                           label="finest +- GCI")
            ax.legend(fontsize=6)
        else:
            ax.set_title(r["status"], fontsize=7, loc="right", color="C1")
        ax.set_xscale("log", base=2)
        ax.set_xlabel("cell size / coarsest", fontsize=7)
        ax.set_title(name if len(name) < 48 else name[:45] + "...", fontsize=7, loc="left")
        ax.tick_params(labelsize=6)
        ax.grid(True, alpha=0.3)
    for ax in list(axes.flat)[n:]:
        ax.axis("off")
    fig.suptitle(f"{case}: mesh convergence", fontsize=9)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    print(f"plot: {png}")


if __name__ == "__main__":
    main(sys.argv[1:])
