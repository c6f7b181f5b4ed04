"""Writes python/stiffid/_documents.pyi: every JSON document of stiffid as a TypedDict, generated
from its JSON Schema in docs/schemas (the test tests/test_stubs.py keeps the two equal).

    python3 crates/stiffid-py/tools/stubs.py          # write the stubs
    python3 crates/stiffid-py/tools/stubs.py --check  # exit 1 if they differ

A document's TypedDict is named for its ``kind`` (``register-postures``: ``RegisterPosturesDocument``),
its parts for the document and the part's type (``CompensateBudget``). A key the document may leave
out is ``NotRequired``; a key the schema allows any value for is ``Any``. The stubs describe the
documents as the command writes them: where a function returns some keys as NumPy arrays, its
stub says so instead."""

import json
import sys
from pathlib import Path

CRATE = Path(__file__).resolve().parents[1]
SCHEMAS = CRATE.parents[1] / "docs" / "schemas"
STUBS = CRATE / "python" / "stiffid" / "_documents.pyi"

HEADER = '''"""The JSON documents of stiffid as TypedDicts, generated from the JSON Schemas in docs/schemas by
crates/stiffid-py/tools/stubs.py (do not edit; tests/test_stubs.py keeps them equal)."""

from typing import Any, Literal, Optional, TypedDict, Union

from typing_extensions import NotRequired
'''

SCALARS = {"string": "str", "number": "float", "integer": "int", "boolean": "bool", "null": "None"}


def pascal(name):
    return "".join(part[:1].upper() + part[1:] for part in name.replace("_", "-").split("-"))


class Schema:
    """One schema's types: its parts ($defs) named for the document."""

    def __init__(self, name, schema):
        self.prefix = pascal(name)
        self.schema = schema
        self.defs = schema.get("$defs", {})

    def def_name(self, name):
        kind = self.defs[name].get("properties", {}).get("kind", {}).get("const")
        return pascal(kind) + "Document" if kind else self.prefix + pascal(name)

    def type_of(self, s):
        if s is True or s == {}:
            return "Any"
        if "$ref" in s:
            return self.def_name(s["$ref"].rsplit("/", 1)[1])
        for key in ("anyOf", "oneOf"):
            if key in s:
                return union([self.type_of(x) for x in s[key]])
        if "allOf" in s and len(s["allOf"]) == 1:
            return self.type_of(s["allOf"][0])
        if "const" in s:
            return literal([s["const"]])
        if "enum" in s:
            return literal(s["enum"])
        types = s.get("type", [])
        types = types if isinstance(types, list) else [types]
        return union([self.one_type(t, s) for t in types]) if types else "Any"

    def one_type(self, t, s):
        if t == "array":
            items = s.get("items")
            if items is None and "prefixItems" in s:
                return "list[%s]" % union([self.type_of(x) for x in s["prefixItems"]])
            return "list[%s]" % (self.type_of(items) if items is not None else "Any")
        if t == "object":
            extra = s.get("additionalProperties")
            if "properties" not in s and isinstance(extra, dict):
                return "dict[str, %s]" % self.type_of(extra)
            return "dict[str, Any]"
        return SCALARS[t]

    def typed_dict(self, name, s):
        required = set(s.get("required", []))
        lines = [f"{name} = TypedDict(\"{name}\", {{"]
        for key, value in s.get("properties", {}).items():
            t = self.type_of(value)
            t = t if key in required else f"NotRequired[{t}]"
            lines.append(f"    {json.dumps(key)}: {t},")
        lines.append("})")
        return "\n".join(lines)

    def stubs(self):
        out = []
        root = self.schema
        if "properties" in root:
            kind = root["properties"].get("kind", {}).get("const")
            name = pascal(kind) + "Document" if kind else self.prefix + "Document"
            out.append(self.typed_dict(name, root))
        else:
            out.append(f"{self.prefix}Document = {self.type_of(root)}")
        for def_name, s in self.defs.items():
            if "properties" in s:
                out.append(self.typed_dict(self.def_name(def_name), s))
            else:
                out.append(f"{self.def_name(def_name)} = {self.type_of(s)}")
        return out


def literal(values):
    strings = [json.dumps(v) for v in values if v is not None]
    parts = [f"Literal[{', '.join(strings)}]"] if strings else []
    return union(parts + (["None"] if None in values else []))


def union(types):
    unique = []
    for t in types:
        for part in split(t):
            if part not in unique:
                unique.append(part)
    literals = [t[len("Literal["):-1] for t in unique if t.startswith("Literal[")]
    if len(literals) > 1:
        rest = [t for t in unique if not t.startswith("Literal[")]
        unique = [f"Literal[{', '.join(literals)}]"] + rest
    if len(unique) == 1:
        return unique[0]
    if "None" in unique:
        rest = [t for t in unique if t != "None"]
        return f"Optional[{union(rest)}]"
    return f"Union[{', '.join(unique)}]"


def split(t):
    """The members of a Union written by `union` (an Optional as its type and None)."""
    if t.startswith("Optional[") and t.endswith("]"):
        return split(t[len("Optional["):-1]) + ["None"]
    if t.startswith("Union[") and t.endswith("]"):
        parts, depth, start = [], 0, len("Union[")
        for i, c in enumerate(t[start:-1], start):
            depth += c == "["
            depth -= c == "]"
            if c == "," and depth == 0:
                parts.append(t[start:i].strip())
                start = i + 1
        return parts + [t[start:-1].strip()]
    return [t]


def generate():
    """The text of _documents.pyi from every schema in docs/schemas, in name order."""
    blocks = [HEADER]
    for path in sorted(SCHEMAS.glob("*.schema.json")):
        name = path.name[: -len(".schema.json")]
        blocks.append(f"# {name}: docs/schemas/{path.name}")
        blocks.extend(Schema(name, json.loads(path.read_text())).stubs())
    return "\n\n".join(blocks) + "\n"


def main(argv):
    text = generate()
    if "--check" in argv:
        return 0 if STUBS.exists() and STUBS.read_text() == text else 1
    STUBS.write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
