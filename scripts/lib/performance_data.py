"""The JSON behind docs/performance.md: reading it, checking every key and type, naming the
file and key of anything wrong (scripts/performance-page renders it and takes benchmark figures
into it)."""
import json
import math
import os
import re

FORMAT = re.compile(r"^[^{}]*\{(:[+ -]?[,_]?(\.[0-9]{1,2})?[efg%]?)?\}[^{}]*$")
KEY = re.compile(r"^[a-z][a-z0-9_]*$")
DATE = re.compile(r"^[0-9]{4}-[0-9]{2}-[0-9]{2}")
# Google Benchmark's additions to a benchmark's name (run options, not part of what it measures).
OPTION = re.compile(r"^(iterations|repeats|threads|min_time|min_warmup_time):[0-9.a-z]+$|^(real_time|manual_time|process_time)$")


class InputError(Exception):
    """Bad input: the message names the file and the key."""


# ---------------------------------------------------------------- reading and checking JSON


def load_json(path, shown):
    def no_duplicates(pairs):
        seen = {}
        for k, v in pairs:
            if k in seen:
                raise InputError("%s: key %r appears twice in one object" % (shown, k))
            seen[k] = v
        return seen

    def no_constant(name):
        raise InputError("%s: %s is not a number JSON allows" % (shown, name))

    try:
        with open(path, "rb") as f:
            raw = f.read()
    except OSError as e:
        raise InputError("%s: cannot read: %s" % (shown, e.strerror or e))
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as e:
        raise InputError("%s: not UTF-8 (byte %d)" % (shown, e.start))
    try:
        return json.loads(text, object_pairs_hook=no_duplicates, parse_constant=no_constant)
    except json.JSONDecodeError as e:
        raise InputError("%s: not valid JSON: %s (line %d, column %d)" % (shown, e.msg, e.lineno, e.colno))
    except RecursionError:
        raise InputError("%s: nested too deeply" % shown)


class Where:
    """A file and a key path inside it, for messages."""

    def __init__(self, file, path=""):
        self.file, self.path = file, path

    def __getitem__(self, key):
        step = "[%d]" % key if isinstance(key, int) else ("." + key if self.path else key)
        return Where(self.file, self.path + step)

    def fail(self, what):
        raise InputError("%s: %s: %s" % (self.file, self.path or "(top level)", what))


def kind(value):
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "a boolean"
    if isinstance(value, (int, float)):
        return "a number"
    if isinstance(value, str):
        return "a string"
    if isinstance(value, list):
        return "a list"
    return "an object"


def obj(value, where, required=(), optional=()):
    if not isinstance(value, dict):
        where.fail("should be an object, is %s" % kind(value))
    for k in required:
        if k not in value:
            where[k].fail("missing")
    unknown = [k for k in value if k not in required and k not in optional]
    if unknown:
        where[unknown[0]].fail("unknown key (known: %s)" % ", ".join(list(required) + list(optional)))
    return value


def string(value, where, one_line=True, nonempty=False):
    if not isinstance(value, str):
        where.fail("should be a string, is %s" % kind(value))
    if one_line and ("\n" in value or "\r" in value):
        where.fail("should be one line")
    if nonempty and not value.strip():
        where.fail("should not be empty")
    return value


def text(value, where):
    """Markdown: a string, or a list of strings (the lines)."""
    if isinstance(value, list):
        return "\n".join(string(line, where[i]) for i, line in enumerate(value))
    return string(value, where, one_line=False)


def number(value, where):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        where.fail("should be a finite number, is %s" % kind(value))
    return float(value)


def check_index(index, where):
    obj(index, where, ("title", "sections"), ("intro",))
    string(index["title"], where["title"], nonempty=True)
    text(index.get("intro", ""), where["intro"])
    sections = index["sections"]
    if not isinstance(sections, list) or not sections:
        where["sections"].fail("should be a non-empty list of section names")
    for i, name in enumerate(sections):
        if not isinstance(name, str) or not KEY.match(name) or name == "index":
            where["sections"][i].fail("should be a section's file name without .json (a-z, 0-9, _), not %r" % (name,))
        if name in sections[:i]:
            where["sections"][i].fail("%r is listed twice" % name)


def check_section(section, where):
    obj(section, where, ("title", "columns", "rows"), ("intro", "commands", "notes"))
    string(section["title"], where["title"], nonempty=True)
    text(section.get("intro", ""), where["intro"])
    text(section.get("notes", ""), where["notes"])
    commands = section.get("commands", [])
    if not isinstance(commands, list):
        where["commands"].fail("should be a list, is %s" % kind(commands))
    for i, c in enumerate(commands):
        obj(c, where["commands"][i], ("lines",), ("lang",))
        string(c.get("lang", ""), where["commands"][i]["lang"])
        text(c["lines"], where["commands"][i]["lines"])
    columns = section["columns"]
    if not isinstance(columns, list) or not columns:
        where["columns"].fail("should be a non-empty list")
    keys = []
    for i, c in enumerate(columns):
        obj(c, where["columns"][i], ("key", "title"))
        key = string(c["key"], where["columns"][i]["key"])
        if not KEY.match(key) or key == "source":
            where["columns"][i]["key"].fail("should be a-z, 0-9, _ and not 'source', is %r" % key)
        if key in keys:
            where["columns"][i]["key"].fail("%r is used twice" % key)
        keys.append(key)
        string(c["title"], where["columns"][i]["title"], nonempty=True)
    rows = section["rows"]
    if not isinstance(rows, list):
        where["rows"].fail("should be a list, is %s" % kind(rows))
    for i, row in enumerate(rows):
        w = where["rows"][i]
        obj(row, w, keys, ("source",))
        for key in keys:
            string(row[key], w[key])
        if "source" in row:
            check_source(row["source"], w["source"], keys)


def check_source(source, where, keys):
    obj(source, where, ("file", "benchmark", "cells"))
    files = source["file"]
    if isinstance(files, str):
        files = [files]
    if not isinstance(files, list) or not files:
        where["file"].fail("should be a path or a non-empty list of paths")
    for i, f in enumerate(files):
        string(f, where["file"][i] if isinstance(source["file"], list) else where["file"], nonempty=True)
    string(source["benchmark"], where["benchmark"], nonempty=True)
    if "date" not in keys:
        where.fail("a row with a source needs a 'date' column")
    cells = source["cells"]
    if not isinstance(cells, dict) or not cells:
        where["cells"].fail("should be a non-empty object: column key -> where its figure comes from")
    for key, cell in cells.items():
        w = where["cells"][key]
        if key not in keys or key in ("date", "machine"):
            w.fail("not a column of this table that takes a figure (columns: %s)" % ", ".join(keys))
        obj(cell, w, (), ("field", "fields", "scale", "format", "join"))
        if ("field" in cell) == ("fields" in cell):
            w.fail("needs one of 'field' (a name) and 'fields' (a list of names)")
        fields = cell["fields"] if "fields" in cell else [cell["field"]]
        if not isinstance(fields, list) or not fields:
            w["fields"].fail("should be a non-empty list of field names")
        for j, f in enumerate(fields):
            string(f, w["fields"][j] if "fields" in cell else w["field"], nonempty=True)
        number(cell.get("scale", 1), w["scale"])
        fmt = string(cell.get("format", "{}"), w["format"])
        if not FORMAT.match(fmt):
            w["format"].fail("should be \"{}\" or \"{:SPEC}\" (SPEC: sign, ',', .N, e/f/g/%%) with text around it, "
                             "is %r" % fmt)
        string(cell.get("join", " / "), w["join"])


def files_of(source):
    return source["file"] if isinstance(source["file"], list) else [source["file"]]


def shown(path, root):
    path = os.path.abspath(path)
    rel = os.path.relpath(path, root)
    return path if rel.startswith("..") else rel


def load_data(data, root):
    """(index, [(name, path, section)]) from the data folder, every file checked."""
    index_path = os.path.join(data, "index.json")
    index = load_json(index_path, shown(index_path, root))
    check_index(index, Where(shown(index_path, root)))
    try:
        present = sorted(f[:-5] for f in os.listdir(data) if f.endswith(".json") and f != "index.json")
    except OSError as e:
        raise InputError("%s: cannot list: %s" % (shown(data, root), e.strerror or e))
    unlisted = [p for p in present if p not in index["sections"]]
    if unlisted:
        Where(shown(index_path, root))["sections"].fail(
            "%s.json is in the folder but not listed here (list it, or remove it)" % unlisted[0])
    sections = []
    for name in index["sections"]:
        path = os.path.join(data, name + ".json")
        if not os.path.exists(path):
            Where(shown(index_path, root))["sections"].fail("lists %r, but there is no %s" % (name, shown(path, root)))
        section = load_json(path, shown(path, root))
        check_section(section, Where(shown(path, root)))
        sections.append((name, path, section))
    return index, sections
