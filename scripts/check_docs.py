#!/usr/bin/python3
"""Documentation consistency check of README.md, doc/*.md and the comment
lines of prm/*.prm (standard library only; run by the ctest
doc_consistency).

1. Links and file names. Every relative Markdown link [text](path) or
   [text](path#anchor) names a file of the repository, and the anchor a
   heading of it (GitHub's slug). A link that leaves the repository (http,
   or a path outside it such as ../shared/...) is an error in README.md and
   doc/. A mention of doc/..., prm/..., meshes/..., scripts/... (and tests/,
   include/, source/, benchmarks/, fuzz/) in text, backticks, code blocks
   or prm comments names an existing file or folder.
2. Parameters. The parameter tree is read from
   `mpm --print-parameters FILE` for a few prm files that together select
   every plugin any shipped or test prm selects (material models, boundary
   types, basal laws, region types, postprocessors, transfers, ...). The
   per-name sections (Materials/<material>, Material points/<region>,
   Boundary conditions/<boundary>) are compared with the name as a
   wildcard. Checked: 'Section/.../Name' paths in quotes or backticks (full
   path when it starts with a top-level section, else as the tail of one),
   'Name = value' and `set Name = value` in text and code blocks (within
   the code block's subsections when they start at the top), --set "A/B=v"
   anywhere, and quoted or backticked phrases that look like a parameter
   name ('Rest speed'). Backticked C++ names containing :: or ending in ()
   must exist in the code (include/, source/, scripts/, benchmarks/, fuzz/,
   tests/; names outside the repository in deal.II's headers).
3. Commands. Every command in README.md's code blocks that runs
   scripts/run.sh, scripts/test.sh, mpm or scripts/convergence.py names
   existing prm files and options the program takes, and its --set options
   are accepted by `mpm --print-parameters FILES --set ...`.

Each problem is printed as file:line: message; the exit status is 1 if
there is any.

Usage: scripts/check_docs.py [--mpm EXECUTABLE] [--dealii-include DIR] [--all-prm]
                             [--verbose]
"""
import argparse
import concurrent.futures
import fnmatch
import glob
import os
import re
import shlex
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# Sections created once per name from a list ('List of materials', ...): the
# name is compared as a wildcard.
PER_NAME_SECTIONS = {"Materials", "Material points", "Boundary conditions"}
# Subsections of a per-name section that are not user-named: their own
# entries, written as they are.
FIXED_SUBSECTIONS = {("Boundary conditions", "Side walls")}

# Keys whose value selects a plugin or a kind of object: the prm files read
# for the parameter tree together select every value any prm file selects.
SELECTING_KEYS = {"Model", "Type", "Basal law", "List of postprocessors", "Scheme",
                  "Particle-grid weights", "Source", "Dimension"}

# Folders whose mentioned paths (doc/x.md, `scripts/run.sh`) must exist.
PATH_PREFIXES = ("doc", "prm", "meshes", "scripts", "tests", "include", "source",
                 "benchmarks", "fuzz")

# Placeholders in mentioned paths and commands, read as any name.
PATH_PLACEHOLDERS = {"NAME", "CASE", "N", "K", "DIR", "FILE", "NNNNN", "OLD_ROOT"}

# Where a backticked C++ name (Class::member, function()) must occur.
CODE_FOLDERS = ("include", "source", "scripts", "benchmarks", "fuzz", "tests")
CODE_EXTENSIONS = (".h", ".cc", ".py", ".sh", ".cmake", ".txt")

# --- Allow-lists: each entry with the reason it is not a problem. ---------

# Quoted or backticked phrases that look like a parameter name but are not
# one.
NOT_PARAMETERS = {
}

# Prm file names in README commands that stand for any case.
PLACEHOLDER_PRM = {
    "case.prm": "stands for the reader's own parameter file",
    "changes.prm": "stands for a file of overrides (later files override earlier ones)",
}
# The file a placeholder's --set options are checked with (the case
# scripts/run.sh runs by default).
PLACEHOLDER_STAND_IN = "prm/sliding_block.prm"

# Backticked C++ names that need not exist in the code or deal.II headers.
CODE_NAME_ALLOWED = {
}

# Problems found but left to be fixed in a file that is being reworked:
# printed as warnings (standard error) instead of failing the check; an
# entry that no longer matches is a warning too (remove it then).
# (file, message) -> why it is left.
KNOWN_PROBLEMS = {}

# Programs outside the repository whose names may be qualified (checked in
# deal.II's headers when they are installed, else accepted).
EXTERNAL_NAMESPACES = {"std", "dealii", "MPI", "Utilities", "VectorTools", "Particles",
                       "ParticleHandler", "Triangulation", "AffineConstraints",
                       "LinearAlgebra", "Mapping", "MappingQ1", "VectorOperation",
                       "parallel", "TimerOutput", "MultithreadInfo", "GridIn",
                       "GridTools", "GeometryInfo", "Tensor", "SymmetricTensor"}


class Problems:
    def __init__(self):
        self.items = []

    def add(self, path, line, message):
        self.items.append((os.path.relpath(path, ROOT), line, message))

    def report(self):
        """Prints the problems; returns how many are not known ones."""
        counted = 0
        matched = set()
        for path, line, message in sorted(set(self.items)):
            if (path, message) in KNOWN_PROBLEMS:
                matched.add((path, message))
                print(f"{path}:{line}: {message} (known: {KNOWN_PROBLEMS[path, message]})",
                      file=sys.stderr)
            else:
                print(f"{path}:{line}: {message}")
                counted += 1
        for path, message in set(KNOWN_PROBLEMS) - matched:
            print(f"check_docs.py: the known problem \"{path}: {message}\" is gone: remove it "
                  "from KNOWN_PROBLEMS", file=sys.stderr)
        return counted


# --- The parameter tree ----------------------------------------------------

def parse_parameter_listing(text, sections=None):
    """Paths (tuples) of the entries in a prm listing. The paths of its
    subsections, also of those without entries (a postprocessor or basal
    law without parameters), are added to the set sections if given."""
    entries = set()
    stack = []
    for line in text.splitlines():
        stripped = line.split("#", 1)[0].strip()
        if not stripped:
            continue
        match = re.match(r"subsection\s+(.*\S)\s*$", stripped)
        if match:
            stack.append(match.group(1))
            if sections is not None:
                sections.add(tuple(stack))
            continue
        if stripped == "end":
            if stack:
                stack.pop()
            continue
        match = re.match(r"set\s+(.*?)\s*=", stripped)
        if match:
            entries.add(tuple(stack + [match.group(1)]))
    return entries


def normalise(path):
    """The path with the per-name component as a wildcard."""
    path = tuple(path)
    if len(path) > 2 and path[0] in PER_NAME_SECTIONS and path[:2] not in FIXED_SUBSECTIONS:
        return (path[0], "*") + path[2:]
    return path


def base_chain(prm):
    """The files mpm reads for a test: its '# base:' files first."""
    chain = [prm]
    current = prm
    for _ in range(20):
        base = None
        with open(current, errors="replace") as file:
            for line in file:
                match = re.match(r"# base:\s*(\S+)", line)
                if match:
                    base = os.path.normpath(os.path.join(os.path.dirname(current),
                                                         match.group(1)))
                    break
        if not base or not os.path.isfile(base):
            break
        chain.insert(0, base)
        current = base
    return chain


def selected_values(files):
    """(section path, key, value) of every plugin-selecting entry set in files."""
    features = set()
    for prm in files:
        stack = []
        with open(prm, errors="replace") as file:
            for line in file:
                stripped = line.split("#", 1)[0].strip()
                if not stripped:
                    continue
                match = re.match(r"subsection\s+(.*\S)\s*$", stripped)
                if match:
                    stack.append(match.group(1))
                    continue
                if stripped == "end":
                    if stack:
                        stack.pop()
                    continue
                match = re.match(r"set\s+(.*?)\s*=\s*(.*)$", stripped)
                if match and match.group(1) in SELECTING_KEYS:
                    section = normalise(stack + [""])[:-1]
                    for value in match.group(2).split(","):
                        if value.strip():
                            features.add((section, match.group(1), value.strip()))
    return features


def instance_names(all_prm):
    """The names of the materials, regions and boundaries the prm files use."""
    names = set()
    for prm in all_prm:
        with open(prm, errors="replace") as file:
            for line in file:
                match = re.match(r"\s*set\s+List of (materials|regions|boundaries)\s*=([^#]*)",
                                 line)
                if match:
                    names |= {name.strip() for name in match.group(2).split(",")}
    return names - {""}


def covering_parameter_files(all_prm, directory):
    """Parameter files that together select every plugin value that any of
    all_prm selects: each per-name section gets one name per value (a
    material per model, a boundary per type, ...), the postprocessor list
    names every postprocessor, and a value that can only be one at a time
    (Dimension, Transfer/Scheme, Mesh/Source) takes its values in turn over
    the files. Returns their paths (written into directory)."""
    features = set()
    for prm in all_prm:
        if not os.path.basename(prm).startswith("bad_input_"):
            features |= selected_values(base_chain(prm))
    per_name = sorted(f for f in features if f[0][:1] and f[0][0] in PER_NAME_SECTIONS
                      and len(f[0]) > 1)
    lists, single = {}, {}
    for section, key, value in sorted(set(features) - set(per_name)):
        (lists if key.startswith("List of") else single).setdefault((section, key),
                                                                     []).append(value)
    n_files = max([len(values) for values in single.values()] + [1])
    blocks = []
    for index in range(n_files):
        entries = []           # (section path, key, value)
        names = {}
        for number, (section, key, value) in enumerate(per_name, 1):
            name = f"checked{number}"
            names.setdefault(section[0], []).append(name)
            entries.append(((section[0], name) + section[2:], key, value))
        for top, name_list in names.items():
            list_key = {"Materials": "List of materials", "Material points": "List of regions",
                        "Boundary conditions": "List of boundaries"}[top]
            entries.append(((top,), list_key, ", ".join(name_list)))
        for (section, key), values in lists.items():
            entries.append((section, key, ", ".join(values)))
        for (section, key), values in single.items():
            entries.append((section, key, values[index % len(values)]))
        lines = []
        for section, key, value in sorted(entries):
            for depth, name in enumerate(section):
                lines.append("  " * depth + f"subsection {name}")
            lines.append("  " * len(section) + f"set {key} = {value}")
            for depth in reversed(range(len(section))):
                lines.append("  " * depth + "end")
        path = os.path.join(directory, f"covering_{index + 1}.prm")
        with open(path, "w") as file:
            file.write("\n".join(lines) + "\n")
        blocks.append(path)
    return blocks


def run(command, timeout=120):
    """Run a command from the project's root. Each call gets a session
    directory base of its own for Open MPI's singleton: two mpm processes
    started at once under one base raced (one removed ompi.HOST.0/jf.0 at
    its end while the other created jf.0/1 in it, and the second stopped in
    MPI_Init with 'A call to mkdir was unable to create the desired
    directory')."""
    started = time.time()
    with tempfile.TemporaryDirectory(
            dir=os.environ.get("OMPI_MCA_orte_tmpdir_base")) as session:
        environment = dict(os.environ, OMPI_MCA_orte_tmpdir_base=session)
        result = subprocess.run(command, cwd=ROOT, stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, universal_newlines=True,
                                timeout=timeout, env=environment)
    return result.returncode, result.stdout, result.stderr, time.time() - started


# --- Markdown ---------------------------------------------------------------

def github_slug(heading):
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading)
    text = text.replace("`", "").strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def headings_of(path, cache={}):
    """Heading texts, GitHub anchors and bold paragraph labels ('**The time
    step.** ...') of a Markdown file."""
    if path in cache:
        return cache[path]
    texts, anchors, labels = [], set(), []
    counts = {}
    in_code = False
    if path.endswith(".md") and os.path.isfile(path):
        with open(path, errors="replace") as file:
            for line in file:
                if re.match(r"\s*(```|~~~)", line):
                    in_code = not in_code
                    continue
                match = None if in_code else re.match(r"#{1,6}\s+(.*?)\s*#*\s*$", line)
                if not in_code:
                    labels += re.findall(r"\*\*([^*]+?)[.:]?\*\*", line)
                if match:
                    texts.append(match.group(1))
                    slug = github_slug(match.group(1))
                    anchors.add(slug if slug not in counts else f"{slug}-{counts[slug]}")
                    counts[slug] = counts.get(slug, 0) + 1
    cache[path] = (texts, anchors, labels)
    return cache[path]


class Document:
    """A documentation file as prose (code blocks and, for prm files, the
    non-comment lines blanked) and code-block lines, with line numbers."""

    def __init__(self, path):
        self.path = path
        self.is_prm = path.endswith(".prm")
        with open(path, errors="replace") as file:
            lines = file.read().split("\n")
        prose, self.code_lines = [], []
        in_code = False
        block = 0
        for number, line in enumerate(lines, 1):
            if self.is_prm:
                stripped = line.lstrip()
                if stripped.startswith("#"):
                    prose.append(" " * (len(line) - len(stripped)) + " " + stripped[1:])
                else:
                    prose.append("")
                continue
            if re.match(r"\s*(```|~~~)", line):
                in_code = not in_code
                block += 1
                prose.append("")
                continue
            if in_code:
                self.code_lines.append((number, block, line))
                prose.append("")
            else:
                # A blockquote's '>' is no part of its text.
                prose.append(re.sub(r"^(\s*>)+", lambda m: " " * len(m.group(0)), line))
        self.prose = "\n".join(prose)
        self.line_starts = [0]
        for line in prose:
            self.line_starts.append(self.line_starts[-1] + len(line) + 1)

    def line_of(self, offset):
        low, high = 0, len(self.line_starts) - 1
        while low < high:
            middle = (low + high + 1) // 2
            if self.line_starts[middle] <= offset:
                low = middle
            else:
                high = middle - 1
        return low + 1

    def code_spans(self):
        """(offset, text) of the inline code spans of the prose."""
        for match in re.finditer(r"(`+)(?!`)((?:(?!\n\s*\n).)+?)(?<!`)\1(?!`)", self.prose,
                                 re.S):
            yield match.start(), match.group(2)

    def prose_without_code(self):
        return re.sub(r"(`+)(?!`)((?:(?!\n\s*\n).)+?)(?<!`)\1(?!`)",
                      lambda m: " " * len(m.group(0)) if "\n" not in m.group(0)
                      else re.sub(r"[^\n]", " ", m.group(0)), self.prose, flags=re.S)


def quoted(text, quote):
    """(offset, content) of the strings in single quotes (an apostrophe inside
    a word, as in Poisson's, does not end them) or double quotes."""
    position = 0
    while True:
        start = text.find(quote, position)
        if start < 0:
            return
        position = start + 1
        before = text[start - 1] if start > 0 else " "
        after = text[start + 1] if start + 1 < len(text) else " "
        if before.isalnum() or after.isspace() or after == quote:
            continue
        end = start + 1
        while True:
            end = text.find(quote, end)
            if end < 0 or "\n\n" in text[start:end]:
                end = -1
                break
            following = text[end + 1] if end + 1 < len(text) else " "
            if not following.isalnum() and not text[end - 1].isspace():
                break
            end += 1
        if end < 0 or end - start > 160:
            continue
        yield start, text[start + 1:end]
        position = end + 1


# --- The check ----------------------------------------------------------------

class Checker:
    def __init__(self, entries, instance_names=(), dealii_include=(), sections=()):
        self.problems = Problems()
        self.entries = entries                      # normalised entry paths
        self.instance_names = set(instance_names)   # materials, regions, boundaries
        self.dealii_include = dealii_include
        self.sections = {path[:k] for path in entries for k in range(1, len(path))} | \
            set(sections)                           # normalised section paths
        self.top_sections = {path[0] for path in self.sections}
        self.entry_names = {path[-1] for path in entries}
        self.section_names = {name for path in self.sections for name in path} - {"*"}
        self.heading_texts = set()
        for doc in [os.path.join(ROOT, "README.md")] + glob.glob(os.path.join(ROOT, "doc", "*.md")):
            self.heading_texts |= {re.sub(r"[`*]", "", text).lower()
                                   for text in headings_of(doc)[0]}
        self._code_words = None
        self._code_texts = None
        self._dealii_words = None
        self._file_stems = None

    # -- parameters --

    def path_known(self, components, full):
        """components: a parameter or section path (list); '<...>' and the name
        of a per-name section are wildcards. full: it starts at the top."""
        pattern = list(components)

        def placeholder(p):
            return p.startswith("<") and p.endswith(">") or p in PATH_PLACEHOLDERS

        def a_name(p):
            """p can be the name of a material, region or boundary: one that
            a prm file uses, a placeholder, or a name not capitalised like
            the entries ('Materials/sand', not 'Material points/Point
            locator')."""
            return placeholder(p) or p in self.instance_names or not p[:1].isupper()

        def match(known):
            if len(known) != len(pattern):
                return False
            return all(p == k or placeholder(p) or k == "*" and a_name(p)
                       for p, k in zip(pattern, known))
        candidates = self.entries | self.sections
        if full:
            return any(match(known) for known in candidates)
        return any(match(known[len(known) - len(pattern):]) for known in candidates
                   if len(known) >= len(pattern))

    def check_parameter_text(self, doc, line, text, kind):
        """text: the content of quotes or backticks; kind: 'single', 'double',
        'code' or 'set' (a `set Name = value` line)."""
        text = re.sub(r"\s+", " ", text).strip()
        required = kind == "set"
        if text.startswith("set ") and kind != "double":
            text, required = text[4:], True
        if text.startswith("subsection ") and kind != "double":
            name = text[len("subsection "):].strip()
            if name not in self.section_names:
                self.problems.add(doc.path, line, f"unknown subsection '{name}'")
            return
        name = text
        if kind == "double" and "/" not in text:
            return     # "..." quotes headings and sentences; only paths are checked
        if "=" in text:
            name = text.split("=", 1)[0].strip()
            # Parameter-like: capitalised words (not an environment variable
            # such as MPM_CELL_SIZE, nor a file name).
            if re.match(r"^(\.\.\./|<|[A-Z])[\w\s'()<>/\-]*$", name) and \
                    not re.match(r"^[A-Z0-9_]+$", name):
                required = True
            else:
                return
        if not name:
            return
        if "/" in name:
            components = [part.strip() for part in name.split("/")]
            if components[0] == "...":
                components, full = components[1:], False
            elif components[0] in self.top_sections:
                full = True
            elif components[0] in self.section_names:
                full = False
            elif len(components) >= 2 and re.match(r"^[A-Z][a-z]+( [a-z]+)*$", components[0]) \
                    and all(re.match(r"^[A-Za-z<>'()\- ]+$", part) for part in components):
                full = True
            else:
                return
            if not all(components):
                return
            if not self.path_known(components, full):
                self.problems.add(doc.path, line, f"no parameter or section '{name}'")
            return
        if name in self.entry_names or name in self.section_names or name in NOT_PARAMETERS:
            return
        if required:
            self.problems.add(doc.path, line, f"no parameter '{name}'")
            return
        if kind in ("single", "code") and self.looks_like_parameter(name) and \
                not any(heading.startswith(name.lower()) for heading in self.heading_texts):
            self.problems.add(doc.path, line, f"no parameter '{name}' (quoted as one)")

    @staticmethod
    def looks_like_parameter(name):
        """'Rest speed', 'CFL number': a capitalised phrase of 2-6 words whose
        other words are lower case (or acronyms)."""
        words = name.split(" ")
        if not 2 <= len(words) <= 6 or not re.match(r"^[A-Z][a-z]+$|^[A-Z]{2,}$", words[0]):
            return False
        return all(re.match(r"^([a-z][a-z\-]*|[A-Z]{2,}|[A-Z]?[a-z]*'s|\d+)$", word)
                   for word in words[1:])

    # -- C++ names --

    def code_corpus(self):
        """The words of the code, and (text, words) of each file."""
        if self._code_words is None:
            self._code_words, self._code_texts = set(), []
            for folder in CODE_FOLDERS:
                for directory, _, files in os.walk(os.path.join(ROOT, folder)):
                    for name in files:
                        if name.endswith(CODE_EXTENSIONS):
                            with open(os.path.join(directory, name), errors="replace") as file:
                                text = file.read()
                            words = set(re.findall(r"\w+", text))
                            self._code_texts.append((text, words))
                            self._code_words |= words
        return self._code_words, self._code_texts

    def files_defining(self, owner, cache={}):
        """Word sets of the files that define class or namespace owner (or
        define its members, owner::...)."""
        if owner not in cache:
            pattern = re.compile(r"\b(class|struct|namespace)\s+%s\b|\b%s(<[^<>;]*>)?::"
                                 % (owner, owner))
            cache[owner] = [words for text, words in self.code_corpus()[1]
                            if owner in words and pattern.search(text)]
        return cache[owner]

    def dealii_words(self):
        if self._dealii_words is None:
            self._dealii_words = set()
            for include in self.dealii_include:
                for directory, _, files in os.walk(include):
                    for name in files:
                        with open(os.path.join(directory, name), errors="replace") as file:
                            self._dealii_words.update(re.findall(r"\w+", file.read()))
        return self._dealii_words

    def check_code_name(self, doc, line, text):
        text = re.sub(r"\s+", " ", text).strip()
        if "::" not in text and not text.endswith("()"):
            return
        if text in CODE_NAME_ALLOWED:
            return
        name = text.split("=", 1)[0].strip() if " = " in text else text
        previous = None
        while previous != name:
            previous = name
            name = re.sub(r"<[^<>]*>", "", name)
            name = re.sub(r"\([^()]*\)", "", name)
        name = name.strip()
        if not re.match(r"^[A-Za-z_~]\w*(::[A-Za-z_~]\w*)*$", name):
            return
        components = name.split("::")
        words, texts = self.code_corpus()
        if components[0] in EXTERNAL_NAMESPACES or not all(c in words for c in components):
            dealii = self.dealii_words()
            if dealii and not all(c in words or c in dealii for c in components):
                missing = [c for c in components if c not in words and c not in dealii]
                self.problems.add(doc.path, line,
                                  f"`{text}`: no '{missing[0]}' in the code or deal.II")
            elif not dealii and components[0] not in EXTERNAL_NAMESPACES:
                missing = [c for c in components if c not in words]
                self.problems.add(doc.path, line, f"`{text}`: no '{missing[0]}' in the code")
            return
        # Class::member: the member occurs where the class is defined.
        for owner, member in zip(components, components[1:]):
            defining = self.files_defining(owner)
            if defining and not any(member in words for words in defining):
                self.problems.add(doc.path, line,
                                  f"`{text}`: '{member}' is not a member of '{owner}' "
                                  "in the code")
                return

    def repository_names(self):
        """Stems of the repository's files, and unit_<stem> (the ctest names
        of tests/unit)."""
        if self._file_stems is None:
            self._file_stems = set()
            for directory, folders, files in os.walk(ROOT):
                folders[:] = [f for f in folders if not f.startswith((".", "build", "output"))]
                for name in files:
                    self._file_stems.add(name.split(".")[0])
                    if os.path.basename(directory) == "unit":
                        self._file_stems.add("unit_" + name.split(".")[0])
        return self._file_stems

    def check_snake_case_name(self, doc, line, text):
        """A backticked snake_case name (`round_trip`, `spinning_body_*`) is a
        name of the code, a file stem (a test, a figure's data) or a ctest."""
        text = text.strip()
        if not re.match(r"^[a-z][a-z0-9]*(_[a-z0-9*]+)+$", text):
            return
        words = self.code_corpus()[0] | self.repository_names()
        if "*" in text:
            if not fnmatch.filter(words, text):
                self.problems.add(doc.path, line, f"`{text}` matches no name in the repository")
        elif text not in words and text not in self.dealii_words():
            self.problems.add(doc.path, line,
                              f"`{text}`: no such name in the code, the tests or the files")

    # -- files and links --

    def check_link(self, doc, line, target):
        target = target.strip().strip("<>")
        if re.match(r"^[a-z][a-z0-9+.-]*:", target):
            if not doc.is_prm:
                self.problems.add(doc.path, line,
                                  f"link '{target}' leaves the repository (name it in words)")
            return
        path, _, anchor = target.partition("#")
        path = re.sub(r"%20", " ", path)
        resolved = os.path.normpath(os.path.join(os.path.dirname(doc.path), path)) \
            if path else doc.path
        if not (resolved + os.sep).startswith(ROOT + os.sep):
            self.problems.add(doc.path, line,
                              f"link '{target}' leaves the repository (name it in words)")
            return
        if not os.path.exists(resolved):
            self.problems.add(doc.path, line, f"link to a missing file '{path}'")
            return
        if anchor and anchor not in headings_of(resolved)[1]:
            self.problems.add(doc.path, line,
                              f"link '{target}': no heading '#{anchor}' in "
                              f"{os.path.relpath(resolved, ROOT)}")

    def check_mentions(self, doc, line, text):
        """File names in text: doc/x.md, `prm/y.prm`, ../shared/..."""
        for match in re.finditer(r"(?<![\w./\-])\.\./[\w.\-/]*", text):
            relative = match.group(0)
            resolved = os.path.normpath(os.path.join(os.path.dirname(doc.path), relative))
            # A file parameter in a command line ('--set "Mesh/Terrain/
            # Elevation model=../meshes/x.tif"') is read relative to the
            # prm file, and the shipped ones live in prm/.
            from_prm = os.path.normpath(os.path.join(ROOT, "prm", relative))
            if "shared" not in relative.split("/") and \
                    (from_prm + os.sep).startswith(ROOT + os.sep) and \
                    os.path.exists(from_prm):
                continue
            if "shared" in relative.split("/") or \
                    not (resolved + os.sep).startswith(ROOT + os.sep):
                self.problems.add(doc.path, line + text.count("\n", 0, match.start()),
                                  f"'{relative}' is outside the repository (name it in words)")
        pattern = r"(?<![\w./\-$])((?:%s)/[\w.*{},/+=\-$]*)" % "|".join(PATH_PREFIXES)
        for match in re.finditer(pattern, text):
            mention = match.group(1).rstrip(".,;:=")
            if not self.path_exists(mention):
                self.problems.add(doc.path, line + text.count("\n", 0, match.start()),
                                  f"'{mention}' does not exist")

    @staticmethod
    def path_exists(mention):
        alternatives = [mention]
        while any("{" in item for item in alternatives):
            expanded = []
            for item in alternatives:
                match = re.search(r"\{([^{}]*)\}", item)
                if not match:
                    expanded.append(item)
                    continue
                for choice in match.group(1).split(","):
                    expanded.append(item[:match.start()] + choice + item[match.end():])
            if expanded == alternatives:
                break
            alternatives = expanded
        for item in alternatives:
            item = re.sub(r"\$\{?\w+\}?", "*", item)      # a shell variable
            item = "/".join("*" if part in PATH_PLACEHOLDERS else
                            re.sub(r"\b(%s)\b" % "|".join(PATH_PLACEHOLDERS), "*", part)
                            for part in item.split("/"))
            if any(c in item for c in "*?["):
                if not glob.glob(os.path.join(ROOT, item)):
                    return False
            elif not os.path.exists(os.path.join(ROOT, item)) and \
                    not glob.glob(os.path.join(ROOT, item) + ".*"):
                # (a program, e.g. tests/unit/point_location, named without
                # the extension of its source)
                return False
        return True

    # -- one document --

    def check_document(self, doc):
        prose = doc.prose_without_code()
        # Links.
        for match in re.finditer(r"\[([^\]]*)\]\(([^()\s]*(?:\([^()\s]*\)[^()\s]*)*)"
                                 r"(?:\s+\"[^\"]*\")?\)", prose):
            self.check_link(doc, doc.line_of(match.start()), match.group(2))
        for match in re.finditer(r"<(https?://[^>\s]+)>", prose):
            self.check_link(doc, doc.line_of(match.start()), match.group(1))
        # File names: prose, code spans, code blocks.
        self.check_mentions(doc, 1, doc.prose)
        for number, _, line in doc.code_lines:
            self.check_mentions(doc, number, line)
        # Parameters and code names in code spans and quotes.
        for offset, text in doc.code_spans():
            line = doc.line_of(offset)
            self.check_parameter_text(doc, line, text, "code")
            self.check_code_name(doc, line, text)
            if not doc.path.endswith("_references.md"):   # (these quote other projects)
                self.check_snake_case_name(doc, line, text)
        # Sections named after a page: doc/x.md, 'Heading' (or a bold label).
        for match in re.finditer(r"(?<![\w/])((?:doc/)?[\w-]+\.md),\s+(['\"])([^'\"\n]+?)\2",
                                 prose):
            target = match.group(1)
            target = os.path.join(ROOT, target if "/" in target or target == "README.md"
                                  else os.path.join("doc", target))
            if os.path.isfile(target):
                texts, _, labels = headings_of(target)
                wanted = re.sub(r"\s+", " ", match.group(3)).lower()
                if not any(re.sub(r"[`*]", "", text).lower().startswith(wanted)
                           for text in texts + labels):
                    self.problems.add(doc.path, doc.line_of(match.start()),
                                      f"no section '{match.group(3)}' in "
                                      f"{os.path.relpath(target, ROOT)}")
        for quote, kind in (("'", "single"), ('"', "double")):
            for offset, text in quoted(prose, quote):
                self.check_parameter_text(doc, doc.line_of(offset), text, kind)
        for match in re.finditer(r"--set\s+\"([^\"]+)\"", doc.prose, re.S):
            self.check_set_option(doc, doc.line_of(match.start()), match.group(1))
        if doc.is_prm:
            for match in re.finditer(r"(?m)^\s*set\s+([^=\n]+?)\s*=", doc.prose):
                self.check_parameter_text(doc, doc.line_of(match.start()),
                                          match.group(1) + " = x", "set")
        # Code blocks: prm snippets (within their subsections) and --set.
        stack, current_block = [], None
        for number, block, line in doc.code_lines:
            if block != current_block:
                stack, current_block = [], block
            stripped = line.split("#", 1)[0].strip()
            match = re.match(r"subsection\s+(.*\S)\s*$", stripped)
            if match:
                stack.append(match.group(1))
                if stack[0] in self.top_sections:
                    if not self.path_known(stack, True):
                        self.problems.add(doc.path, number,
                                          f"no section '{'/'.join(stack)}'")
                elif match.group(1) not in self.section_names:
                    self.problems.add(doc.path, number,
                                      f"unknown subsection '{match.group(1)}'")
                continue
            if stripped == "end":
                if stack:
                    stack.pop()
                continue
            match = re.match(r"set\s+([^=]+?)\s*=", stripped)
            if match:
                if stack and stack[0] in self.top_sections:
                    if not self.path_known(stack + [match.group(1)], True):
                        self.problems.add(doc.path, number, "no parameter '%s'"
                                          % "/".join(stack + [match.group(1)]))
                elif stack:
                    if not self.path_known(stack + [match.group(1)], False):
                        self.problems.add(doc.path, number, "no parameter '%s'"
                                          % "/".join(stack + [match.group(1)]))
                else:
                    self.check_parameter_text(doc, number, match.group(1) + " = x", "set")
            for set_match in re.finditer(r"--set[ =]\"([^\"]+)\"", line):
                self.check_set_option(doc, number, set_match.group(1))

    def check_set_option(self, doc, line, option):
        option = re.sub(r"\s+", " ", option)
        if "=" not in option:
            self.problems.add(doc.path, line, f"--set \"{option}\": no '='")
            return
        self.check_parameter_text(doc, line, option.split("=", 1)[0] + " = x", "set")


# --- README commands -------------------------------------------------------------

PROGRAMS = {"scripts/run.sh": "run.sh", "scripts/test.sh": "test.sh",
            "build/release/mpm": "mpm", "build/debug/mpm": "mpm", "mpm": "mpm",
            "scripts/convergence.py": "convergence.py"}


def convergence_options():
    """Options of scripts/convergence.py (flags, options with a value)."""
    flags, valued = set(), set()
    with open(os.path.join(ROOT, "scripts", "convergence.py")) as file:
        text = file.read()
    for match in re.finditer(r"add_argument\(\s*\"(--[\w-]+)\"([^)]*)", text):
        (flags if "store_true" in match.group(2) else valued).add(match.group(1))
    return flags, valued


def readme_commands(readme):
    """(line, program, arguments) of the commands in README.md's code blocks."""
    doc = Document(readme)
    commands = []
    pending, pending_line = "", None
    for number, _, line in doc.code_lines:
        if pending_line is None:
            pending_line = number
        pending += line
        if pending.rstrip().endswith("\\"):
            pending = pending.rstrip()[:-1] + " "
            continue
        text, line_number = pending, pending_line
        pending, pending_line = "", None
        try:
            tokens = shlex.split(text, comments=True)
        except ValueError as error:
            commands.append((line_number, None, [str(error)]))
            continue
        while tokens and (re.match(r"^\w+=", tokens[0]) or tokens[0] in ("/usr/bin/python3",
                                                                           "python3")):
            tokens.pop(0)
        if tokens[:1] in (["mpirun"], ["mpiexec"]):
            tokens = tokens[1:]
            while tokens and tokens[0].startswith("-"):
                tokens = tokens[2:] if tokens[0] in ("-np", "-n") else tokens[1:]
        if tokens and tokens[0] in PROGRAMS:
            commands.append((line_number, PROGRAMS[tokens[0]], tokens[1:]))
    return commands


def mpm_options(help_text):
    """Options of mpm from its --help: (flags, options taking a value)."""
    flags, valued = set(), set()
    for match in re.finditer(r"^\s*\[?(--[\w-]+)( [A-Z][\w.=]*)?", help_text, re.M):
        (valued if match.group(2) else flags).add(match.group(1))
    for match in re.finditer(r"\[(--[\w-]+)( [A-Z][\w.=\"/]*)?\]", help_text):
        (valued if match.group(2) else flags).add(match.group(1))
    return flags, valued


class ReadmeCommands:
    """README.md's commands: their prm files and options, and their --set
    options through mpm --print-parameters FILES --set ... (one call per set
    of files; where it fails, one per command to say which)."""

    def __init__(self, readme, mpm):
        self.readme, self.mpm = readme, mpm
        self.commands = []     # (line, program, [(option, value)], [positional])
        for line, program, arguments in readme_commands(readme):
            options, positional = [], []
            index = 0
            while index < len(arguments):
                argument = arguments[index]
                if argument.startswith("--"):
                    option, equals, value = argument.partition("=")
                    if not equals and index + 1 < len(arguments) and \
                            not arguments[index + 1].startswith("-") and \
                            not arguments[index + 1].endswith(".prm"):
                        value = arguments[index + 1]     # taken only if the option takes one
                    options.append((option, value if equals else None, value))
                else:
                    positional.append((index, argument))
                index += 1
            self.commands.append((line, program, options, positional))

    def files_of(self, command):
        line, program, options, positional = command
        prm_files = [argument for _, argument in positional if argument.endswith(".prm")]
        files = []
        for prm in prm_files:
            if prm in PLACEHOLDER_PRM:
                files.append(PLACEHOLDER_STAND_IN)
            elif os.path.isfile(os.path.join(ROOT, prm)):
                files.extend(os.path.relpath(path, ROOT)
                             for path in base_chain(os.path.join(ROOT, prm)))
            else:
                return None
        if not files and program == "run.sh":
            files = [PLACEHOLDER_STAND_IN]
        return tuple(files)

    @staticmethod
    def sets_of(command):
        return [given if given is not None else following
                for option, given, following in command[2] if option == "--set"]

    def submit(self, pool):
        """Starts one mpm call per set of files (all its commands' --set)."""
        groups = {}
        for command in self.commands:
            files, sets = self.files_of(command), self.sets_of(command)
            if command[1] in ("run.sh", "mpm", "convergence.py") and files and sets:
                groups.setdefault(files, []).append(command)
        self.calls = []
        for files, commands in groups.items():
            arguments = [self.mpm, "--print-parameters"] + list(files)
            for command in commands:
                for option in self.sets_of(command):
                    arguments += ["--set", option]
            self.calls.append((files, commands, pool.submit(run, arguments)))

    def check(self, problems, mpm_help):
        mpm_flags, mpm_valued = mpm_options(mpm_help)
        conv_flags, conv_valued = convergence_options()
        readme = self.readme
        for line, program, options, positional in self.commands:
            if program is None:
                problems.add(readme, line, f"cannot split the command: {positional}")
                continue
            if program == "test.sh":
                continue     # its arguments go to ctest
            flags, valued = (conv_flags, conv_valued) if program == "convergence.py" \
                else (mpm_flags, mpm_valued)
            taken = set()
            for option, given, following in options:
                if option in valued:
                    if given is None:
                        taken.add(following)
                elif option not in flags:
                    problems.add(readme, line, f"{program} takes no option '{option}'")
            for index, argument in positional:
                if argument.endswith(".prm"):
                    if argument not in PLACEHOLDER_PRM and \
                            not os.path.isfile(os.path.join(ROOT, argument)):
                        problems.add(readme, line, f"'{argument}' does not exist")
                elif argument not in taken:
                    problems.add(readme, line, f"{program}: unexpected argument '{argument}'")
        for files, commands, future in self.calls:
            status, _, error, _ = future.result()
            if status == 0:
                continue
            for command in commands:
                arguments = [self.mpm, "--print-parameters"] + list(files)
                for option in self.sets_of(command):
                    arguments += ["--set", option]
                status, _, error, _ = run(arguments)
                if status != 0:
                    problems.add(readme, command[0], "mpm --print-parameters %s rejects "
                                 "its --set: %s" % (" ".join(files),
                                                    " ".join(error.split())[:300]))


# --- main -------------------------------------------------------------------------

def default_mpm():
    """The Release build's mpm if there is one, else the Debug build's."""
    release = os.path.join(ROOT, "build", "release", "mpm")
    return release if os.path.exists(release) else os.path.join(ROOT, "build", "debug", "mpm")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--mpm", default=default_mpm(), help="the mpm executable")
    parser.add_argument("--all-prm", action="store_true",
                        help="read the parameter tree of every prm file, not a covering few")
    parser.add_argument("--dealii-include", action="append", default=None, metavar="DIR",
                        help="deal.II's headers, where the C++ names the docs use from "
                             "deal.II are looked up (default /usr/include/deal.II and "
                             "/usr/local/include/deal.II; if none exists, names in a "
                             "deal.II or std namespace are accepted)")
    parser.add_argument("--verbose", action="store_true", help="say what is read and its time")
    args = parser.parse_args()
    if args.dealii_include is None:
        args.dealii_include = [d for d in ("/usr/include/deal.II", "/usr/local/include/deal.II")
                               if os.path.isdir(d)]
    started = time.time()
    mpm = os.path.abspath(args.mpm)
    if not os.access(mpm, os.X_OK):
        print(f"check_docs.py: no mpm executable at {args.mpm}", file=sys.stderr)
        return 2

    all_prm = sorted(glob.glob(os.path.join(ROOT, "prm", "*.prm")) +
                     glob.glob(os.path.join(ROOT, "tests", "*.prm")))
    temporary = tempfile.TemporaryDirectory()
    chosen = [p for p in all_prm if not os.path.basename(p).startswith("bad_input_")] \
        if args.all_prm else covering_parameter_files(all_prm, temporary.name)
    readme = os.path.join(ROOT, "README.md")
    problems_before = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        tree_calls = [(prm, pool.submit(run, [mpm, "--print-parameters"] +
                                        [os.path.relpath(p, ROOT) for p in base_chain(prm)]))
                      for prm in chosen]
        help_call = pool.submit(run, [mpm, "--help"])
        commands = ReadmeCommands(readme, mpm)
        commands.submit(pool)
        entries, sections = set(), set()
        for prm, future in tree_calls:
            status, output, error, seconds = future.result()
            if args.verbose:
                print(f"  --print-parameters {os.path.basename(prm)}: {seconds:.2f} s",
                      file=sys.stderr)
            if status != 0:
                if args.all_prm:
                    where, what = prm, ""
                else:
                    where = os.path.join(ROOT, "scripts", "check_docs.py")
                    with open(prm) as file:
                        what = " (of a file setting %s)" % "; ".join(
                            line.strip() for line in file if "set " in line)
                problems_before.append((where, 1, f"mpm --print-parameters fails{what}: "
                                        + " ".join(error.split())[:300]))
                continue
            listed_sections = set()
            entries |= {normalise(path) for path in parse_parameter_listing(output,
                                                                            listed_sections)}
            sections |= {normalise(path + ("",))[:-1] for path in listed_sections}
        if not entries:
            print("check_docs.py: no parameter tree read", file=sys.stderr)
            return 2
        checker = Checker(entries, instance_names(all_prm), args.dealii_include, sections)
        for item in problems_before:
            checker.problems.add(*item)
        documents = [readme] + sorted(glob.glob(os.path.join(ROOT, "doc", "*.md"))) + \
            sorted(glob.glob(os.path.join(ROOT, "prm", "*.prm")))
        for path in documents:
            checker.check_document(Document(path))
        _, help_text, help_error, _ = help_call.result()
        commands.check(checker.problems, help_text + help_error)
    failures = checker.problems.report()
    if args.verbose:
        print(f"check_docs.py: {len(chosen)} prm files for the parameter tree "
              f"({len(entries)} entries), {len(documents)} documents, "
              f"{time.time() - started:.1f} s", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
