#!/usr/bin/python3
"""Generates doc/parameters.md, the parameter guide, from the program
itself (standard library only; never edit the page by hand).

The entries, their defaults and their documentation are read from
`mpm --print-parameters FILE` for the parameter files check_docs.py builds
to select every plugin any shipped or test prm file selects (material
models, boundary types, basal laws, region types, postprocessors,
transfers, mesh sources, both dimensions), plus one file for each plugin
that a plugin-selecting entry offers but no prm file selects. The per-name
sections (Materials/<name>, Material points/<name>, Boundary
conditions/<name>) are shown once with the placeholder <name>.

`--print-parameters` prints no patterns (deal.II's PRM style gives the
documentation, the value and, where they differ, the default). The
allowed values are therefore asked of mpm entry by entry: the entry is set
to a value no number, flag or choice accepts, and mpm's error message
names its pattern; an entry that takes the value takes any text (names,
file names, expressions, points: the program checks them when it reads
them). An entry is asked in 2D, and in 3D too where it exists only there or
its default differs (points and vectors). One mpm start per entry: about
200 of them, a minute on two cores.

The page ends with the patterns as asked (an HTML comment). --check makes
the page in memory and compares it with doc/parameters.md (exit status 1
and the head of a unified diff if they differ; ctest
parameter_guide_current): everything is read from mpm anew, except that
the patterns of entries that select no plugin are taken from that
comment, so that the check takes a few seconds. The plugin-selecting
entries (check_docs.SELECTING_KEYS) and entries the comment does not know
are asked anew. --check --all-patterns asks for every pattern (a
pattern changed without any documentation or default changing shows
only so).

Usage: scripts/make_parameter_guide.py [--mpm EXECUTABLE] [--check [--all-patterns]]
                                       [--output FILE] [--verbose]
"""
import argparse
import concurrent.futures
import difflib
import glob
import os
import re
import subprocess
import sys
import tempfile
import time

import check_docs
from check_docs import ROOT, PER_NAME_SECTIONS, FIXED_SUBSECTIONS

# The entry that lists the names of each per-name section.
NAME_LISTS = {"Materials": "List of materials", "Material points": "List of regions",
              "Boundary conditions": "List of boundaries"}

# The value each entry is set to when its pattern is asked for: no number,
# flag, choice or list of them.
PROBE_VALUE = "@not-a-value@"

# Units that documentation texts state, as 'in Pa', '(m/s)' or '(m, ...'.
UNITS = ["kg/m^3", "m/s^2", "m/s", "m^2", "m^3", "1/s", "kPa", "MPa", "Pa", "kg", "m", "s",
         "degrees", "rad", "N", "J", "Hz"]
UNIT_WORDS = {"seconds": "s", "minutes": "min"}

OUTPUT = os.path.join(ROOT, "doc", "parameters.md")


def run(command):
    """Run a command from the project's root, with a session directory base
    of its own for Open MPI's singleton (calls run two at a time; under one
    base, one singleton's clean-up can remove the directory the other is
    creating, scripts/check_docs.py:run)."""
    started = time.time()
    with tempfile.TemporaryDirectory(
            dir=os.environ.get("OMPI_MCA_orte_tmpdir_base")) as session:
        environment = dict(os.environ, OMPI_MCA_orte_tmpdir_base=session)
        result = subprocess.run(command, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                universal_newlines=True, timeout=300, env=environment)
    return result.returncode, result.stdout, result.stderr, time.time() - started


# --- Reading a listing ---------------------------------------------------------------------

def parse_listing(text):
    """Entries and sections of an `mpm --print-parameters` listing: a list of
    ('entry', path, value, default, documentation) and ('section', path)
    in the listing's order. The default is the value unless the line says
    '# default: ...'."""
    items = []
    stack, comment = [], []
    lines = text.splitlines()
    # deal.II's header: '# Listing of Parameters' and a rule.
    if len(lines) >= 2 and lines[0].startswith("# Listing of Parameters") and \
            re.match(r"#\s*-+\s*$", lines[1]):
        lines = lines[2:]
    for line in lines:
        stripped = line.strip()
        if stripped.startswith("#"):
            comment.append(stripped[1:].strip())
            continue
        if not stripped:
            comment = []
            continue
        match = re.match(r"subsection\s+(.*\S)\s*$", stripped)
        if match:
            stack.append(match.group(1))
            items.append(("section", tuple(stack)))
            comment = []
            continue
        if stripped == "end":
            stack.pop()
            comment = []
            continue
        match = re.match(r"set\s+(.*?)\s*=(.*)$", stripped)
        if not match:
            raise ValueError(f"unexpected line in the listing: {line!r}")
        value, _, remark = match.group(2).partition("#")
        value = value.strip()
        default = value
        remark = remark.strip()
        if remark.startswith("default:"):
            default = remark[len("default:"):].strip()
        items.append(("entry", tuple(stack + [match.group(1)]), value, default,
                      " ".join(comment)))
        comment = []
    return items


def normalise(path, section=False):
    """The path of an entry (or of a section) with the name of a per-name
    section as '<name>'."""
    if (path[0] in PER_NAME_SECTIONS and len(path) > (1 if section else 2)
            and tuple(path[:2]) not in FIXED_SUBSECTIONS):
        return (path[0], "<name>") + tuple(path[2:])
    return tuple(path)


def deal_ii_key(name):
    """The order in which deal.II prints the entries (and the subsections)
    of a section: by the mangled name, every character that is not a letter
    or digit written as %XX."""
    return "".join(c if c.isalnum() else "%%%02x" % ord(c) for c in name)


class Tree:
    """The normalised entries and sections over all listings read."""

    def __init__(self):
        self.entries = {}     # path -> {dim: (default, documentation)}
        self.real_path = {}   # (path, dim) -> (a real path, the file whose listing has it,
        #                       the value there)
        self.sections = {}    # path -> set of dims

    def add_listing(self, items, dim, prm):
        for item in items:
            if item[0] == "section":
                path = normalise(item[1], section=True)
                self.sections.setdefault(path, set()).add(dim)
                continue
            _, real, value, default, documentation = item
            path = normalise(real)
            seen = self.entries.setdefault(path, {})
            if dim in seen and seen[dim] != (default, documentation):
                raise ValueError(f"{'/'.join(path)}: two defaults or texts in {dim}D")
            seen[dim] = (default, documentation)
            self.real_path.setdefault((path, dim), (real, prm, value))

    def children(self, section):
        """The entries and subsections directly in a section (a path), in
        deal.II's order."""
        entries = sorted((p for p in self.entries if p[:-1] == section),
                         key=lambda p: deal_ii_key(p[-1]))
        subsections = sorted((p for p in self.sections if p[:-1] == section),
                             key=lambda p: deal_ii_key(p[-1]))
        return entries, subsections


# --- Asking for the patterns ------------------------------------------------------------------

def probe_text(real_path, value):
    lines = []
    for depth, name in enumerate(real_path[:-1]):
        lines.append("  " * depth + f"subsection {name}")
    lines.append("  " * (len(real_path) - 1) + f"set {real_path[-1]} = {value}")
    for depth in reversed(range(len(real_path) - 1)):
        lines.append("  " * depth + "end")
    return "\n".join(lines) + "\n"


def read_pattern(status, error):
    """The pattern description in mpm's answer to a probe; 'text' if the
    probe value was taken; None if mpm failed otherwise."""
    if status == 0:
        return "text"
    match = re.search(r"does not match the given pattern:\s*\n\s*(\S.*?)\s*$", error, re.M)
    return match.group(1) if match else None


def probes_needed(tree):
    """(path, dim) of the entries whose pattern is asked for: in 2D, and in
    3D where the entry exists only there or its default differs (the
    number of components of a point or vector)."""
    needed = []
    for path, by_dim in sorted(tree.entries.items()):
        dims = sorted(by_dim)
        if len(dims) > 1 and len({by_dim[d][0] for d in dims}) == 1:
            dims = dims[:1]
        needed += [(path, dim) for dim in dims]
    return needed


def ask_patterns(tree, mpm, pool, directory, recorded=None):
    """{(path, dim): pattern description} for every entry and dimension.
    With recorded (the patterns the page states), only the plugin-selecting
    entries and the entries the page does not know are asked for."""
    patterns = {}
    calls = []

    def submit(path, dim, value):
        real, prm, _ = tree.real_path[path, dim]
        probe = os.path.join(directory, f"probe_{len(calls)}.prm")
        with open(probe, "w") as file:
            file.write(probe_text(real, value))
        calls.append((path, dim, value,
                      pool.submit(run, [mpm, "--print-parameters", prm, probe])))

    for path, dim in probes_needed(tree):
        if recorded is not None and path[-1] not in check_docs.SELECTING_KEYS and \
                (path, dim) in recorded:
            patterns[path, dim] = recorded[path, dim]
        else:
            submit(path, dim, PROBE_VALUE)
    index = 0
    while index < len(calls):
        path, dim, value, future = calls[index]
        index += 1
        status, _, error, _ = future.result()
        pattern = read_pattern(status, error)
        current = tree.real_path[path, dim][2]
        if pattern is None and value == PROBE_VALUE and current:
            # A list of names: the probe as one more name (alone, the
            # names' subsections of the file would be undeclared).
            submit(path, dim, f"{current}, {PROBE_VALUE}")
            continue
        if pattern is None:
            raise RuntimeError(f"mpm did not say the pattern of {'/'.join(path)} ({dim}D): "
                               + " ".join(error.split())[:300])
        patterns[path, dim] = pattern
    for path, by_dim in tree.entries.items():
        asked = [d for d in sorted(by_dim) if (path, d) in patterns]
        for dim in by_dim:
            patterns.setdefault((path, dim), patterns[path, asked[0]])
    return patterns


def choices(pattern):
    """The options of a Selection or MultipleSelection pattern, else []."""
    match = re.match(r"\[(Multiple)?Selection (.*?)\s*\]$", pattern)
    return [c.strip() for c in match.group(2).split("|")] if match else []


# --- Rendering ---------------------------------------------------------------------------------

def number(text):
    return {"MAX_DOUBLE": None, "-MAX_DOUBLE": None, "2147483647": None,
            "-2147483648": None, "4294967295": None}.get(text, text)


def describe_range(kind, low, high):
    low, high = number(low), number(high)
    if low is None and high is None:
        return kind
    if high is None:
        return f"{kind} >= {low}"
    if low is None:
        return f"{kind} <= {high}"
    return f"{kind} from {low} to {high}"


def describe_pattern(pattern, plural=False):
    """deal.II's pattern description in words."""
    if pattern == "text":
        return "any text"
    match = re.match(r"\[Double (\S+)\.\.\.(\S+) \(inclusive\)\]$", pattern)
    if match:
        return describe_range("numbers" if plural else "a number", *match.groups())
    if pattern == "[Double]":
        return "numbers" if plural else "a number"
    match = re.match(r"\[Integer range (\S+)\.\.\.(\S+) \(inclusive\)\]$", pattern)
    if match:
        return describe_range("integers" if plural else "an integer", *match.groups())
    if pattern == "[Integer]":
        return "integers" if plural else "an integer"
    if pattern == "[Bool]":
        return "`true` or `false`"
    match = re.match(r"\[Selection (.*?)\s*\]$", pattern)
    if match:
        options = ", ".join(f"`{c}`" for c in choices(pattern))
        return f"one of {options}"
    match = re.match(r"\[MultipleSelection (.*?)\s*\]$", pattern)
    if match:
        options = ", ".join(f"`{c}`" for c in choices(pattern))
        return f"a comma separated list of {options}"
    match = re.match(r"\[List of <(.*)> of length (\S+)\.\.\.(\S+) \(inclusive\)"
                     r"(?: separated by <(.*)>)?\]$", pattern)
    if match:
        inner, low, high, separator = match.groups()
        separator = separator or ","
        low, high = number(low), number(high)
        length = ""
        if low == high and low is not None:
            length = f" {low}"
        elif low not in (None, "0") or high is not None:
            length = f" ({describe_range('length', low, high)[len('length '):]})"
        return (f"a list of{length} {describe_pattern(inner, plural=True)} "
                f"separated by `{separator}`")
    return f"`{pattern}`"


def unit_of(name, documentation):
    """The unit the documentation states for the entry's value, if one:
    'in Pa', '(m/s)', '(m, ...)' in its first sentence, or a unit word in
    the name or that sentence ('Wall-clock seconds', 'Minutes between
    checkpoints'). None if there is none or several, and for a file (an
    elevation grid's values are in m, the file name is not), and for the
    time variable of a function ('t (s)')."""
    first = re.split(r"(?<=[.;])\s+(?=[A-Z0-9'(])", documentation, maxsplit=1)[0]
    if re.search(r"\b(file|grid|raster) (\(|(of|whose|with)\b)", first) and \
            not re.search(r"\bin (%s)\b" % "|".join(re.escape(u) for u in UNITS), first):
        return None
    alternatives = "|".join(re.escape(u) for u in UNITS)
    found = []
    for match in re.finditer(r"(?:\bin |\(|, )(%s)(?=[\s),;:.]|$)" % alternatives, first):
        if not re.search(r"\bt \($", first[:match.start(1)]):
            found.append(match.group(1))
    for word, unit in UNIT_WORDS.items():
        if re.search(r"\b%s\b" % word, name + " " + first, re.I):
            found.append(unit)
    found = list(dict.fromkeys(found))
    return found[0] if len(found) == 1 else None


def markdown_text(text):
    """Documentation text as Markdown: deal.II's `quoted' style as 'quoted',
    addresses as code (not links: the pages link only inside the
    repository), and the characters Markdown would take as markup escaped."""
    text = re.sub(r"`([^`']*)'", r"'\1'", text)
    pieces = re.split(r"(https?://[^\s)]*[^\s).,;:])", text)
    out = []
    for index, piece in enumerate(pieces):
        if index % 2:
            out.append(f"`{piece}`")
            continue
        piece = piece.replace("\\", "\\\\").replace("`", "\\`").replace("*", "\\*")
        piece = re.sub(r"([\[\]])", r"\\\1", piece)
        piece = re.sub(r"<(?=[A-Za-z/!?])", r"\\<", piece)
        piece = re.sub(r"(?<![A-Za-z0-9])_|_(?![A-Za-z0-9])", r"\\_", piece)
        out.append(piece)
    return "".join(out)


def code(text):
    """text as an inline code span (empty: 'empty')."""
    if text == "":
        return "empty"
    return f"`` {text} ``" if "`" in text else f"`{text}`"


def wrap(text, width=90, indent="  "):
    """Lines of at most width characters (longer words kept whole), the
    continuation lines indented. A word Markdown would read at the start of
    a line as a list item, quote, heading or rule ('-', '>', '1.') stays
    with the word before it."""
    words = []
    for word in text.split(" "):
        if words and re.match(r"([-+*>#=|]+|\d+[.)])$", word):
            words[-1] += " " + word
        elif word:
            words.append(word)
    lines, current = [], ""
    for word in words:
        if current and len(current) + 1 + len(word) > width - len(indent):
            lines.append(current)
            current = word
        else:
            current = f"{current} {word}" if current else word
    lines.append(current)
    return ("\n" + indent).join(lines)


def section_title(path):
    return "/".join(path)


def selected_by(tree, patterns, section):
    """'Model = mohr coulomb' when the section is named after an option of
    an entry of its parent section (its plugin), else None."""
    parent = section[:-1]
    for entry in sorted(tree.entries):
        if entry[:-1] != parent or entry[-1] not in check_docs.SELECTING_KEYS:
            continue
        for dim in sorted(tree.entries[entry]):
            pattern = patterns[entry, dim]
            if section[-1] in choices(pattern):
                if pattern.startswith("[MultipleSelection"):
                    return f"its name is in `{entry[-1]}`"
                return f"`{entry[-1]} = {section[-1]}`"
    return None


def render_entry(tree, patterns, path, dims_all):
    by_dim = tree.entries[path]
    dims = sorted(by_dim)
    facts = [code("/".join(path))]
    defaults = {d: by_dim[d][0] for d in dims}
    if len(set(defaults.values())) == 1:
        facts.append("default " + code(defaults[dims[0]]))
    else:
        facts.append("default " + ", ".join(f"{code(defaults[d])} in {d}D" for d in dims))
    described = {d: describe_pattern(patterns[path, d]) for d in dims}
    if len(set(described.values())) == 1:
        facts.append(described[dims[0]])
    else:
        facts.append("; ".join(f"{described[d]} in {d}D" for d in dims))
    texts = {d: by_dim[d][1] for d in dims}
    unit = unit_of(path[-1], texts[dims[0]])
    if unit:
        facts.append(f"unit {unit}")
    if dims != dims_all:
        facts.append(" and ".join(f"{d}D" for d in dims) + " only")
    if len(set(texts.values())) == 1:
        text = markdown_text(texts[dims[0]]) or "(no documentation)"
    else:
        text = " ".join(f"In {d}D: {markdown_text(texts[d]) or '(no documentation)'}"
                        for d in dims)
    return "- " + wrap(f"**{path[-1]}** ({'; '.join(facts)}) - {text}")


INTRO = """\
# Parameters

<!-- Generated by scripts/make_parameter_guide.py from `mpm --print-parameters`: do not
edit; run the script after changing a parameter (ctest parameter_guide_current fails while
this page is out of date). -->

Every parameter of `mpm`, with its default, the values it accepts and its
documentation, as the program itself prints them (`mpm --print-parameters`).

## The parameter file

A parameter file (`.prm`) is read by deal.II's ParameterHandler. Entries are
grouped in subsections (`subsection Time stepping` ... `end`), which nest; a
line `set End time = 2` sets an entry; `#` starts a comment, and a line ending
in `\\` continues on the next:

```
set Dimension = 2

subsection Time stepping
  set End time = 2          # s
  set Gravity  = 0, -9.81
end

subsection Materials
  set List of materials = sand
  subsection sand
    set Density = 1500
    set Model   = mohr coulomb
    subsection mohr coulomb
      set Friction angle = 30
    end
  end
end
```

An entry that is not set keeps its default. The file is read strictly: an
unknown subsection or entry, or a value the entry's pattern does not accept
(a number, `true` or `false`, one of a list of choices), stops the program
with the file, line and entry; values the pattern takes as text (names, file
names, expressions, points) are checked when the program reads them.
`mpm --print-parameters case.prm` prints every parameter with the value the
case would run with, and its default where that differs.

**Names.** `Materials/List of materials`, `Material points/List of regions`
and `Boundary conditions/List of boundaries` are comma separated lists of
names chosen by the user; each name has a subsection of its own with the
entries shown below under `<name>`. The model of a material, the basal law
of a boundary and each postprocessor read their parameters from a
subsection named after them (`Materials/<name>/mohr coulomb`): every such
subsection exists, whichever is chosen, and the chosen one is used.

**Lists, points and vectors.** Lists are comma separated
(`List of postprocessors = flume, energy balance`). Points and vectors are
comma separated components, as many as `Dimension` unless the entry says
otherwise (`Gravity = 0, -9.81` in 2D, `0, 0, -9.81` in 3D; a polygon's
vertices are x, y in 3D too); the entries that take several points say their
separator (`Box = 0, 0 : 1, 1`, `Polygon = 0, 0 ; 1, 0 ; 1, 1`).

**Functions.** The subsections `Material points/<name>/Initial velocity` and
`Initial stress function` are deal.II's parsed functions: `Function
expression` holds one expression per component separated by `;`, in the
variables of `Variable names` (`x,y,t` in 2D, `x,y,z,t` in 3D), with
constants from `Function constants` (`rho=1800, g=9.81`). The syntax is that
of deal.II's FunctionParser (the muparser library): `+ - * / ^`, functions
such as `sin`, `cos`, `exp`, `sqrt`, `tan`, `atan2`, comparisons and
`&&`, `||`, which give 1 or 0, `c ? a : b` and `if(c, a, b)`; `pi` and `Pi`
are defined. `Material points/<name>/Inside function` (variables x, y (, z)
and h), `Time stepping/Local damping` and `Materials/Strength reduction
factor` (variable t) are expressions of the same syntax without the
predefined `pi` (write `_pi`, muparser's constant).

**File names.** A relative file name in a parameter file (`Mesh/Gmsh file`,
`Mesh/Terrain/Elevation model`, `Material points/<name>/Point file`,
`Polygon file`, `Release depth`, `Release top surface`) is read relative to
the folder of the first parameter file on the command line, whichever file
sets it. `Output/Directory` is relative to the folder `mpm` is started in.

**Several files and `--set`.** `mpm base.prm changes.prm` reads the files in
turn into the same parameters: a later file overrides the entries it sets and
leaves the others as the earlier files set them. `--set` (repeatable; the
entry's path with `/` between the subsections, then `=` and the value, as in
`--set "Time stepping/End time=0.4"`) is applied after all files, in the order
given, and read as a one-line parameter file with the same checks; the last
setting of an entry wins:

```
mpm prm/sliding_block.prm changes.prm --set "Time stepping/End time=0.4"
```

The lists of names are read from all files and `--set` options before the
rest, so a later file or a `--set` may add a name
(`--set "Materials/List of materials=sand, rock" --set "Materials/rock/Density=2600"`);
a subsection of a name that the final list no longer contains is an error.

**Dimension.** `Dimension` (2 or 3) is read first. A 3D scene has entries a
2D one has not (marked *3D only* below), and most of its points and vectors
have three components (entries whose default differs give both).

Each entry below: its name, full path, default, the values it accepts, its
unit where its documentation states one, and its documentation.
"""


def render(tree, patterns, dims_all):
    out = [INTRO]
    tops = sorted({p[0] for p in tree.sections} | {p[0] for p in tree.entries if len(p) > 1},
                  key=deal_ii_key)
    top_entries = [p for p in tree.entries if len(p) == 1]
    out.append("## Contents\n")
    if top_entries:
        out.append("- [Top level](#top-level)")
    for top in tops:
        out.append(f"- [{top}](#{check_docs.github_slug(top)})")
    out.append("")
    if top_entries:
        out.append("## Top level\n")
        for path in sorted(top_entries, key=lambda p: deal_ii_key(p[0])):
            out.append(render_entry(tree, patterns, path, dims_all))
        out.append("")

    def section(path, level):
        entries, subsections = tree.children(path)
        heading = path[0] if len(path) == 1 else f"`{section_title(path)}`"
        out.append("#" * min(level, 6) + f" {heading}\n")
        notes = []
        if len(path) == 2 and path[1] == "<name>":
            notes.append(f"One subsection per name in `{path[0]}/{NAME_LISTS[path[0]]}`.")
        plugin = selected_by(tree, patterns, path) if len(path) > 1 else None
        if plugin:
            notes.append(f"Used when {plugin}.")
        dims = sorted(tree.sections.get(path, set(dims_all)))
        if dims != dims_all:
            notes.append(" and ".join(f"{d}D" for d in dims) + " only.")
        if not entries and not subsections:
            notes.append("No parameters.")
        if notes:
            out.append(" ".join(notes) + "\n")
        for entry in entries:
            out.append(render_entry(tree, patterns, entry, dims_all))
        if entries:
            out.append("")
        for subsection in subsections:
            section(subsection, level + 1)

    for top in tops:
        section((top,), 2)
    while out and out[-1] == "":
        out.pop()
    return "\n".join(out) + "\n"


# --- The parameter files read ----------------------------------------------------------------

def covering_files(directory):
    """check_docs.py's covering parameter files (every plugin any prm file
    selects), each with its dimension."""
    all_prm = sorted(glob.glob(os.path.join(ROOT, "prm", "*.prm")) +
                     glob.glob(os.path.join(ROOT, "tests", "*.prm")))
    files = check_docs.covering_parameter_files(all_prm, directory)
    return [(prm, dimension_of(prm)) for prm in files]


def dimension_of(prm):
    with open(prm) as file:
        match = re.search(r"^\s*set\s+Dimension\s*=\s*(\d)", file.read(), re.M)
    return int(match.group(1)) if match else 2


def unselected_plugins(tree, patterns, listings):
    """(real path, option) of the options of plugin-selecting entries
    (check_docs.SELECTING_KEYS) that no listing read selects."""
    selected = set()
    for items in listings:
        for item in items:
            if item[0] == "entry" and item[1][-1] in check_docs.SELECTING_KEYS:
                selected |= {(normalise(item[1]), v.strip()) for v in item[2].split(",")}
    missing = []
    for path, by_dim in sorted(tree.entries.items()):
        if path[-1] not in check_docs.SELECTING_KEYS:
            continue
        for dim in sorted(by_dim):
            for option in choices(patterns[path, dim]):
                if (path, option) not in selected:
                    missing.append((path, dim, option))
                    selected.add((path, option))
    return missing


PATTERNS_HEAD = "<!-- The patterns as mpm states them"


def recorded_patterns(page):
    """{(path, dim): pattern} from the block at the end of a page."""
    recorded = {}
    head = page.find(PATTERNS_HEAD)
    if head < 0:
        return recorded
    for line in page[head:].splitlines()[1:]:
        if line.startswith("-->"):
            break
        parts = line.split("\t")
        if len(parts) == 3 and re.match(r"\dD$", parts[0]):
            recorded[tuple(parts[1].split("/")), int(parts[0][0])] = parts[2]
    return recorded


def patterns_block(tree, patterns):
    """The patterns of the entries as asked for, for --check to read back."""
    lines = [PATTERNS_HEAD + " (dimension, entry, pattern; 'text': any value is taken),",
             "read back by scripts/make_parameter_guide.py --check:"]
    for path, dim in probes_needed(tree):
        lines.append(f"{dim}D\t{'/'.join(path)}\t{patterns[path, dim]}")
    lines.append("-->")
    return "\n".join(lines) + "\n"


def generate(mpm, recorded=None, verbose=False):
    """The page. recorded: the patterns a page states, to take for the
    entries that select no plugin instead of asking mpm (see --check)."""
    started = time.time()
    workers = max(2, 3 * (os.cpu_count() or 1))
    with tempfile.TemporaryDirectory() as directory, \
            concurrent.futures.ThreadPoolExecutor(max_workers=workers) as pool:
        files = covering_files(directory)
        if 3 not in {dim for _, dim in files}:
            three = os.path.join(directory, "covering_3d.prm")
            with open(files[0][0]) as base, open(three, "w") as file:
                file.write(re.sub(r"(?m)^\s*set\s+Dimension\s*=.*$", "", base.read())
                           + "set Dimension = 3\n")
            files.append((three, 3))
        tree = Tree()
        listings = []

        def read(prm_files):
            calls = [(prm, dim, pool.submit(run, [mpm, "--print-parameters", prm]))
                     for prm, dim in prm_files]
            for prm, dim, future in calls:
                status, output, error, _ = future.result()
                if status != 0:
                    raise RuntimeError(f"mpm --print-parameters {os.path.basename(prm)} failed: "
                                       + " ".join(error.split())[:300])
                items = parse_listing(output)
                listings.append(items)
                tree.add_listing(items, dim, prm)

        read(files)
        patterns = ask_patterns(tree, mpm, pool, directory, recorded)
        # A plugin that an entry offers but no prm file selects: a file that
        # selects it (its parameters could be declared only then).
        extra_files = []
        for number, (path, dim, option) in enumerate(unselected_plugins(tree, patterns,
                                                                        listings)):
            real, prm, _ = tree.real_path[path, dim]
            extra = os.path.join(directory, f"plugin_{number}.prm")
            with open(prm) as base, open(extra, "w") as file:
                file.write(base.read() + probe_text(real, option))
            extra_files.append((extra, dim))
        if extra_files:
            known = set(tree.entries)
            read(extra_files)
            if set(tree.entries) - known:
                patterns = ask_patterns(tree, mpm, pool, directory, recorded)
        dims_all = sorted({dim for by_dim in tree.entries.values() for dim in by_dim})
        page = render(tree, patterns, dims_all) + "\n" + patterns_block(tree, patterns)
    if verbose:
        asked = len(probes_needed(tree)) if recorded is None else sum(
            1 for key in probes_needed(tree)
            if key[0][-1] in check_docs.SELECTING_KEYS or key not in recorded)
        print(f"make_parameter_guide.py: {len(files) + len(extra_files)} parameter files "
              f"({len(extra_files)} for plugins no prm file selects), {len(tree.entries)} "
              f"entries, {asked} patterns asked for, {time.time() - started:.1f} s",
              file=sys.stderr)
        for path, by_dim in sorted(tree.entries.items()):
            if any(not text for _, text in by_dim.values()):
                print(f"  no documentation: {'/'.join(path)}", file=sys.stderr)
    return page


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--mpm", default=check_docs.default_mpm(), help="the mpm executable")
    parser.add_argument("--check", action="store_true",
                        help="compare with the page instead of writing it; exit status 1 "
                             "if it differs")
    parser.add_argument("--all-patterns", action="store_true",
                        help="with --check: ask mpm for every entry's pattern, not only "
                             "for those of the plugin-selecting entries (a minute)")
    parser.add_argument("--output", default=OUTPUT, help="the page (default doc/parameters.md)")
    parser.add_argument("--verbose", action="store_true", help="say what is read and its time")
    args = parser.parse_args()
    mpm = os.path.abspath(args.mpm)
    if not os.access(mpm, os.X_OK):
        print(f"make_parameter_guide.py: no mpm executable at {args.mpm}", file=sys.stderr)
        return 2
    relative = os.path.relpath(os.path.abspath(args.output), ROOT)
    if not args.check:
        page = generate(mpm, verbose=args.verbose)
        with open(args.output, "w") as file:
            file.write(page)
        return 0
    current = ""
    if os.path.exists(args.output):
        with open(args.output) as file:
            current = file.read()
    recorded = None if args.all_patterns else recorded_patterns(current)
    page = generate(mpm, recorded, args.verbose)
    if current == page:
        return 0
    diff = list(difflib.unified_diff(current.splitlines(), page.splitlines(),
                                     f"{relative} (in the repository)",
                                     f"{relative} (from {os.path.basename(mpm)})",
                                     lineterm=""))
    print(f"{relative} is not what scripts/make_parameter_guide.py makes of this mpm: "
          "run it to regenerate the page. The difference"
          + (f" (first 60 of {len(diff)} lines)" if len(diff) > 60 else "") + ":")
    print("\n".join(diff[:60]))
    return 1


if __name__ == "__main__":
    sys.exit(main())
