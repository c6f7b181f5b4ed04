#!/usr/bin/env python3
"""The documented public API of the facade `stiffid`, from rustdoc's JSON, following re-exports.

Writes one line per item a library user can name: its path from `stiffid`, its kind
(module, struct, enum, union, trait, type, function, method, constant, static, macro), sorted.
Counted as the API: modules, types, functions, inherent methods, constants and statics reached
from the crate root through public modules and re-exports (into the crates below, too), once
per item (an item reached by two paths is listed under its shortest); not fields, variants,
trait-implementation methods or `#[doc(hidden)]` items (rustdoc leaves those out).

Usage (rustdoc's JSON output is unstable: RUSTC_BOOTSTRAP turns it on with the stable toolchain):

    for c in stiffid stiffid-core stiffid-metrology stiffid-identify stiffid-design \
             stiffid-machining stiffid-view; do
        RUSTC_BOOTSTRAP=1 cargo rustdoc -p $c --lib -- -Zunstable-options --output-format json
    done
    python3 crates/stiffid/tools/public_api.py target/doc . > crates/stiffid/public-api.txt

`crates/stiffid/public-api.txt` is that listing, committed. Its header names every source file an
item of the API is declared in and a fingerprint of those files' `pub` declarations (FNV-1a, 64
bits, over their lines that declare a `pub` item: `pub fn`, `pub struct`, ... `pub use`, trimmed,
sorted, joined by line breaks; fields are not API items and left out); the test
`the_public_api_is_the_listed_one` (crates/stiffid/tests/it/api.rs) computes the same fingerprint
and fails when a declaration changed without the listing being generated again and reviewed.
"""
import json
import sys
from pathlib import Path

KINDS = {"module", "struct", "enum", "union", "trait", "type_alias", "function", "constant",
         "static", "macro", "trait_alias"}
NAMES = {"type_alias": "type", "trait_alias": "trait"}


def load(doc_dir):
    crates = {}
    for path in Path(doc_dir).glob("stiffid*.json"):
        data = json.loads(path.read_text())
        root = data["index"][str(data["root"])]
        crates[root["name"]] = data
    return crates


class Walker:
    def __init__(self, crates):
        self.crates = crates
        self.by_path = {}  # (crate name, tuple path) -> (crate name, id)
        for name, data in crates.items():
            for item_id, summary in data["paths"].items():
                if summary["crate_id"] == 0:
                    self.by_path[(name, tuple(summary["path"]))] = (name, item_id)
        self.seen = {}  # (crate, id) -> (path, kind)
        self.files = set()

    def item(self, crate, item_id):
        return self.crates[crate]["index"].get(str(item_id))

    def resolve(self, crate, item_id):
        """A re-export's target: (crate, id) in a crate we have the JSON of, or None."""
        if item_id is None:
            return None
        data = self.crates[crate]
        if str(item_id) in data["index"]:
            return crate, str(item_id)
        summary = data["paths"].get(str(item_id))
        if summary is None:
            return None
        ext = data["external_crates"].get(str(summary["crate_id"]))
        if ext is None or ext["name"] not in self.crates:
            return None
        return self.by_path.get((ext["name"], tuple(summary["path"])))

    def visit(self, crate, item_id, path):
        item = self.item(crate, item_id)
        if item is None:
            return
        kind, inner = next(iter(item["inner"].items()))
        if kind == "use":
            target = self.resolve(crate, inner["id"])
            if target is None:
                return
            if inner["is_glob"]:
                self.children(*target, path)
            else:
                self.visit(*target, path[:-1] + [inner["name"]])
            return
        if kind not in KINDS:
            return
        key = (crate, item_id)
        name = "::".join(path)
        old = self.seen.get(key)
        if old is not None and (len(old[0]), old[0]) <= (len(name), name):
            return
        self.seen[key] = (name, NAMES.get(kind, kind))
        self.file(item)
        if kind == "module":
            self.children(crate, item_id, path)
        elif kind in ("struct", "enum", "union"):
            self.methods(crate, inner.get("impls", []), path)

    def children(self, crate, module_id, path):
        module = self.item(crate, module_id)
        for child in module["inner"]["module"]["items"]:
            child_item = self.item(crate, child)
            if child_item is None or child_item.get("visibility") != "public":
                continue
            kind = next(iter(child_item["inner"]))
            name = child_item["name"] if kind != "use" else child_item["inner"]["use"]["name"]
            self.visit(crate, str(child), path + [name])

    def methods(self, crate, impls, path):
        for impl_id in impls:
            impl = self.item(crate, impl_id)
            if impl is None or impl["inner"]["impl"]["trait"] is not None:
                continue
            for method_id in impl["inner"]["impl"]["items"]:
                method = self.item(crate, method_id)
                if method is None or method.get("visibility") != "public":
                    continue
                kind = next(iter(method["inner"]))
                label = {"function": "method", "assoc_const": "constant", "assoc_type": "type"}
                key = (crate, str(method_id))
                name = "::".join(path + [method["name"]])
                old = self.seen.get(key)
                if old is None or (len(name), name) < (len(old[0]), old[0]):
                    self.seen[key] = (name, label.get(kind, kind))
                    self.file(method)

    def file(self, item):
        span = item.get("span")
        if span and span["filename"].startswith("crates/"):
            self.files.add(span["filename"])


ITEMS = ("fn ", "struct ", "enum ", "trait ", "type ", "const ", "static ", "mod ", "use ",
         "unsafe fn ", "async fn ", "const fn ")


def declares(line):
    """Whether a trimmed source line declares a `pub` item (not a field, not `pub(crate)`)."""
    return line.startswith("pub ") and line[4:].startswith(ITEMS)


def fingerprint(root, files):
    """FNV-1a (64 bits) of the files' `pub` item lines, trimmed, sorted, joined by line breaks."""
    lines = []
    for name in files:
        text = (Path(root) / name).read_text()
        lines += [line.strip() for line in text.splitlines() if declares(line.strip())]
    h = 0xCBF29CE484222325
    for byte in "\n".join(sorted(lines)).encode():
        h = ((h ^ byte) * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    return f"{h:016x}"


def main():
    crates = load(sys.argv[1] if len(sys.argv) > 1 else "target/doc")
    root = sys.argv[2] if len(sys.argv) > 2 else "."
    walker = Walker(crates)
    data = crates["stiffid"]
    walker.visit("stiffid", str(data["root"]), ["stiffid"])
    lines = sorted(f"{kind} {path}" for path, kind in walker.seen.values())
    files = sorted(walker.files | {"crates/stiffid/src/lib.rs"})
    head = ["# The API of the facade `stiffid`: every item a program linking it can name, one a line",
            "# (kind, path). Generated by crates/stiffid/tools/public_api.py from rustdoc's JSON; a change",
            "# here is a change of the API, reviewed. The files its items are declared in and the",
            "# fingerprint of their `pub` lines (the test api.rs checks it):"]
    head += [f"# source {name}" for name in files]
    head += [f"# fingerprint {fingerprint(root, files)}", f"# {len(lines)} items"]
    sys.stdout.write("".join(line + "\n" for line in head + lines))
    print(f"{len(lines)} items, {len(files)} files", file=sys.stderr)


if __name__ == "__main__":
    main()
