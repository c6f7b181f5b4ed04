#!/usr/bin/env python3
"""Where the public items of the science crates are used: each item's nearest user.

For every `pub` item of a science crate (stiffid-core, -metrology, -identify, -design,
-machining, -view), declared in its `src/` outside its tests (the items docs/ARCHITECTURE.md's
table "Public items" counts: every `pub` function, a method too, type, trait, constant, static,
module and `pub use` line; `pub(crate)` is not public), the users of its name, first of:

    science   another science crate names it (its own crate's dependents below the jobs)
    front     the command, the Python package, the figures, the benches, the facade's
              `lib.rs` or its examples name it, or the facade's API lists it
              (`crates/stiffid/public-api.txt`: its source file and its name; a module by
              its own file), or it is a type the interface of an API item of the jobs crate
              carries (a job's request, report or document: its public fields, a public
              function's signature), which a library user meets there
    jobs      the jobs crate (`crates/stiffid/src/app/`) names it, and no one above: the seam
              between the science and the jobs
    interface no one outside names it, but the signature or a public field of a used item of
              its crate, or a trait implementation's associated type, carries it (a type a used
              function returns)
    tests     only tests outside its crate name it (`crates/*/tests/`, other crates' unit tests)
    crate     nothing outside its crate names it (its own code or unit tests, or nothing)

An item is named where its name appears as a whole word in code: comments, doc comments and
string literals are left out, and so is the item's own declaration line. A `pub use` line is
named where any of the names it brings is. The measure is by name, so an item whose name another
item shares (`new`, `len`) counts as used wherever that name is: the counts of `tests` and
`crate` are lower bounds, and the compiler (the item made `pub(crate)`) has the last word.

Usage:

    python3 crates/stiffid/tools/surface.py             # the table, per crate and user
    python3 crates/stiffid/tools/surface.py tests crate # and the items of those users, listed
"""
import re
import sys
from collections import Counter, defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
SCIENCE = ["stiffid-core", "stiffid-metrology", "stiffid-identify", "stiffid-design",
           "stiffid-machining", "stiffid-view"]
USERS = ["science", "front", "jobs", "interface", "tests", "crate"]
TYPES = {"struct", "enum", "trait", "type", "use"}
DECLARATION = re.compile(
    r"^\s*pub\s+(?:(?:async|unsafe|const|extern\s+\"C\")\s+)*"
    r"(fn|struct|enum|trait|type|const|static|mod|use)\b\s*(?:mut\s+)?(.*)")
WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
ASSOCIATED = re.compile(r"^\s+type\s+\w+\s*=")


def strip(text):
    """`text` without comments and with empty string and character literals."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            i = text.find("\n", i)
            i = n if i < 0 else i
        elif text.startswith("/*", i):
            depth, i = 1, i + 2
            while i < n and depth:
                if text.startswith("/*", i):
                    depth, i = depth + 1, i + 2
                elif text.startswith("*/", i):
                    depth, i = depth - 1, i + 2
                else:
                    i += 1
        elif c == "r" and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")) \
                and re.match(r'r#*"', text[i:i + 40]):
            hashes = len(re.match(r"r(#*)", text[i:]).group(1))
            close = '"' + "#" * hashes
            end = text.find(close, i + 2 + hashes)
            i = n if end < 0 else end + len(close)
            out.append('""')
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            out.append('""')
            i = j + 1
        elif c == "'" and re.match(r"'(\\.[^']*|[^'\\])'", text[i:i + 12]):
            m = re.match(r"'(\\.[^']*|[^'\\])'", text[i:i + 12])
            out.append("' '")
            i += len(m.group(0))
        else:
            out.append(c)
            i += 1
    return "".join(out)


def item_end(code, start):
    """Where the item starting at `start` ends: after its `;` at the top level or its block."""
    depth, i = 0, start
    while i < len(code):
        c = code[i]
        if c == "{":
            depth += 1
        elif c == "}":
            depth -= 1
            if depth == 0:
                return i + 1
        elif c == ";" and depth == 0:
            return i + 1
        i += 1
    return len(code)


def without_tests(code):
    """`code` without its `#[cfg(test)]` items (their lines kept empty) and the tests apart."""
    kept, tests = code, []
    while (at := kept.find("#[cfg(test)]")) >= 0:
        end = item_end(kept, at + len("#[cfg(test)]"))
        tests.append(kept[at:end])
        kept = kept[:at] + "\n" * kept[at:end].count("\n") + kept[end:]
    return kept, "\n".join(tests)


def dependencies(root, crate):
    """The workspace crates `crate`'s manifest depends on, its dev-dependencies too (its unit
    tests may name them)."""
    manifest = (root / "crates" / crate / "Cargo.toml").read_text()
    return set(re.findall(r"^(stiffid[\w-]*)\s*[.=]", manifest, re.M)) - {crate}


def is_test_file(path):
    return path.name == "tests.rs" or path.name.endswith("_tests.rs") or "tests" in path.parts


def rust_files(directory):
    return sorted(p for p in directory.rglob("*.rs") if "target" not in p.parts)


def words(code):
    return Counter(WORD.findall(code))


def use_names(tree):
    """The names a `use` tree brings: each path's last segment or its `as` alias."""
    tree = re.sub(r"\s+", " ", tree.split(";")[0])
    names = []
    for part in re.split(r"[{},]", tree):
        part = part.strip()
        if not part or part.endswith("::"):
            continue
        alias = re.search(r"\bas\s+(\w+)$", part)
        last = alias.group(1) if alias else part.split("::")[-1].strip()
        if last not in ("self", "*", "_"):
            names.append(last)
    return names


def interface(kind, code, start):
    """The text of the item at `start` that others see: a function's signature, a struct's
    public fields, an enum's variants, a trait's items, a type alias' or constant's type."""
    if kind in ("enum", "trait"):
        return code[start:item_end(code, start)]
    if kind == "struct":
        block = code[start:item_end(code, start)]
        head = block.split("{")[0]
        return head + " ".join(l for l in block.split("\n") if l.strip().startswith("pub "))
    if kind in ("fn", "type", "const", "static"):
        ends = [i for i in (code.find("{", start), code.find(";", start)) if i >= 0]
        return code[start:min(ends)] if ends else ""
    return ""


class Item:
    def __init__(self, crate, path, line, kind, names, text, face):
        self.crate, self.path, self.line, self.kind = crate, path, line, kind
        self.names, self.text, self.face = names, text, face
        self.user = None


class Workspace:
    def __init__(self, root):
        self.root = root
        self.items = []  # (crate, file, line, kind, names)
        self.code = defaultdict(Counter)  # group -> word counts
        self.dependencies = {crate: dependencies(root, crate) for crate in SCIENCE}
        self.associated = defaultdict(set)  # crate -> names of trait impls' associated types
        for crate in SCIENCE:
            self.read_science(crate)
        self.read_others()
        self.read_api()

    def group(self, name, code):
        self.code[name].update(words(code))

    def read_science(self, crate):
        src = self.root / "crates" / crate / "src"
        for path in rust_files(src):
            code, tests = without_tests(strip(path.read_text()))
            if is_test_file(path.relative_to(src)):
                self.group(("unit", crate), code + tests)
                continue
            self.group(("crate", crate), code)
            self.group(("unit", crate), tests)
            self.declarations(crate, path, code)

    def declarations(self, crate, path, code):
        lines = code.split("\n")
        # A trait implementation's associated type is as public as the trait and the type.
        self.associated[crate] |= {w for l in lines if ASSOCIATED.match(l)
                                   for w in WORD.findall(l.split("=", 1)[1])}
        starts = [0]
        for line in lines:
            starts.append(starts[-1] + len(line) + 1)
        for number, line in enumerate(lines):
            m = DECLARATION.match(line)
            if not m:
                continue
            kind, rest = m.groups()
            if kind == "use":
                tail = " ".join(lines[number:number + 40])
                names = use_names(tail[tail.index("use") + 3:])
            else:
                name = WORD.match(rest)
                names = [name.group(0)] if name else []
            if names:
                face = interface(kind, code, starts[number])
                self.items.append(Item(crate, path.relative_to(self.root), number + 1, kind,
                                       names, line.strip(), set(WORD.findall(face))))

    def read_others(self):
        crates = self.root / "crates"
        self.jobs_api = []  # (file, kind, names, face) of the jobs crate's pub items
        for path in rust_files(crates / "stiffid" / "src"):
            code, tests = without_tests(strip(path.read_text()))
            self.jobs_declarations(path, code)
            group = "front" if path.name == "lib.rs" and path.parent.name == "src" else "jobs"
            self.group(group, code)
            self.group("tests", tests)
        for name in ["stiffid-cli", "stiffid-py", "stiffid-figures", "stiffid-bench"]:
            for directory in ["src", "benches"]:
                for path in rust_files(crates / name / directory):
                    code, tests = without_tests(strip(path.read_text()))
                    self.group("front", code)
                    self.group("tests", tests)
        for path in rust_files(crates / "stiffid" / "examples"):
            self.group("front", strip(path.read_text()))
        for name in ["stiffid", "stiffid-cli", "stiffid-py"]:
            for path in rust_files(crates / name / "tests"):
                self.group("tests", strip(path.read_text()))

    def jobs_declarations(self, path, code):
        """The jobs crate's `pub` items in `code` with what their interface names."""
        lines = code.split("\n")
        starts = [0]
        for line in lines:
            starts.append(starts[-1] + len(line) + 1)
        for number, line in enumerate(lines):
            m = DECLARATION.match(line)
            if not m or m.group(1) in ("use", "mod"):
                continue
            name = WORD.match(m.group(2))
            if name:
                face = set(WORD.findall(interface(m.group(1), code, starts[number])))
                self.jobs_api.append((str(path.relative_to(self.root)), name.group(0), face))

    def api_faces(self):
        """What the interfaces of the facade's API items in the jobs crate name: the types a
        library user meets in a job's request, report or document."""
        return {w for f, name, face in self.jobs_api
                if f in self.api_files and name in self.api_names for w in face - {name}}

    def read_api(self):
        """The facade's API (`crates/stiffid/public-api.txt`): its source files and the names
        of its items; an item of a science crate the API lists is used by a library user."""
        listing = (self.root / "crates/stiffid/public-api.txt").read_text().splitlines()
        self.api_files = {l.split()[-1] for l in listing if l.startswith("# source ")}
        self.api_names = {l.split()[-1].split("::")[-1] for l in listing if not l.startswith("#")}

    def in_api(self, item):
        """Whether the API lists `item`: by its file and name, a module by its own file
        (rustdoc places a module where its text is, `name.rs` or `name/mod.rs` beside the file
        that declares it)."""
        files = {str(item.path)}
        if item.kind == "mod":
            folder = item.path.parent
            files = {str(folder / f"{n}.rs") for n in item.names} | \
                {str(folder / n / "mod.rs") for n in item.names}
        return files & self.api_files and set(item.names) & self.api_names

    def uses(self, names, own):
        """How many times the code of each group names one of `names`: the groups that can
        reach `own`'s items (a science crate that depends on it, and every crate above)."""
        return {group: sum(counts[n] for n in names) for group, counts in self.code.items()
                if not isinstance(group, tuple) or own in self.dependencies[group[1]]}

    def user(self, crate, kind, names):
        uses = self.uses(names, crate)
        science = sum(v for g, v in uses.items() if isinstance(g, tuple) and g[0] == "crate")
        if science:
            return "science"
        if uses.get("front"):
            return "front"
        if uses.get("jobs"):
            return "jobs"
        units = sum(v for g, v in uses.items() if isinstance(g, tuple) and g[0] == "unit")
        if uses.get("tests") or units:
            return "tests"
        return "crate"


def classify(workspace):
    """Each item's nearest user; a type only its crate names but a used item's interface
    carries (a function's signature, a public field) is used through it: `interface`."""
    for item in workspace.items:
        item.user = workspace.user(item.crate, item.kind, item.names)
        if item.user not in ("science", "front") and workspace.in_api(item):
            item.user = "front"
    faces = workspace.api_faces()
    for item in workspace.items:
        if item.user == "jobs" and item.kind in TYPES and set(item.names) & faces:
            item.user = "front"
    changed = True
    while changed:
        changed = False
        faces = defaultdict(set, {c: set(n) for c, n in workspace.associated.items()})
        for item in workspace.items:
            if item.user not in ("tests", "crate"):
                faces[item.crate] |= item.face - set(item.names)
        for item in workspace.items:
            if item.user in ("tests", "crate") and item.kind in TYPES \
                    and set(item.names) & faces[item.crate]:
                item.user, changed = "interface", True


def main(listed):
    workspace = Workspace(ROOT)
    classify(workspace)
    table = defaultdict(Counter)
    for item in workspace.items:
        table[item.crate][item.user] += 1
    print("| crate | " + " | ".join(USERS) + " | all |")
    print("|---|" + "---|" * (len(USERS) + 1))
    total = Counter()
    for crate in SCIENCE:
        total.update(table[crate])
        cells = [str(table[crate][u]) for u in USERS]
        print(f"| {crate} | " + " | ".join(cells) + f" | {sum(table[crate].values())} |")
    cells = [str(total[u]) for u in USERS]
    print("| science crates | " + " | ".join(cells) + f" | {sum(total.values())} |")
    for user in listed:
        print(f"\n{user}:")
        for item in sorted(workspace.items, key=lambda i: (str(i.path), i.line)):
            if item.user == user:
                print(f"  {item.path}:{item.line}  {item.kind}  {','.join(item.names)}")


if __name__ == "__main__":
    main(sys.argv[1:])
