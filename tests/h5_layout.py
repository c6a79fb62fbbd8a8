#!/usr/bin/env python3
"""h5_layout.py: results files held to docs/hdf5-layout.md.

    python3 tests/h5_layout.py docs/hdf5-layout.md FILE.h5 [FILE.h5 ...]

Reads the layout's tables (a heading naming an HDF5 path in backticks opens
the tables of that object: `attribute`, `column` (of a compound table) and
`dataset` (members of a group) tables, each row naming one or more objects
with their type and units, and for a two-dimensional dataset its columns),
then walks every group, dataset, attribute and compound column of each file
with h5py and checks that each is documented, with the documented type,
units (a dataset's `units` attribute, a table's `units_<column>`) and
columns (`columns`), and that every name carrying a unit suffix (`_s`,
`_g`, `_m_s2` ...) has that unit.  Prints one line per fault, naming the
table of docs/hdf5-layout.md to put it in, and exits 1 if there is any.
Used by tests/test_report_h5_layout.c.
"""
import re
import sys

import h5py
import numpy as np

SUFFIX_UNITS = [("_m_s2", "m/s^2"), ("_mps2", "m/s^2"), ("_m_s", "m/s"), ("_kgm2", "kg m^2"),
                ("_rad", "rad"), ("_deg", "deg"), ("_hz", "Hz"), ("_kg", "kg"), ("_s", "s"),
                ("_m", "m"), ("_j", "J"), ("_g", "g")]


def pattern(name):
    """A documented path or name as a regular expression: NNN and NNNNN are
    indices, RRRRR_AAA_SSS a run, [r] and [_azDEG] optional parts, <...> any
    text."""
    out, i = "", 0
    while i < len(name):
        m = re.match(r"RRRRR_AAA_SSS|N{3,}|\[r\]|\[_azDEG\]|<[^>]*>", name[i:])
        if m:
            tok = m.group(0)
            out += {"RRRRR_AAA_SSS": r"\d{5}_\d{3}_\d{3}", "[r]": "r?",
                    "[_azDEG]": r"(_az[-+0-9.e]+)?"}.get(
                        tok, r"\d{%d}" % len(tok) if tok[0] == "N" else r".+")
            i += len(tok)
        else:
            out += re.escape(name[i])
            i += 1
    return re.compile(out + r"\Z")


def clean(cell):
    return cell.replace("`", "").strip()


def parse_layout(path):
    """{path_pattern: {'attribute'|'column'|'dataset': [(regex, name, type, units, columns)]}}"""
    doc, where, table = {}, None, None
    for line in open(path, encoding="utf-8"):
        line = line.rstrip("\n")
        if line.startswith("#"):
            m = re.search(r"`(/[^`]*)`", line)
            where = m.group(1) if m else None
            table = None
            continue
        if not line.startswith("|"):
            table = None
            continue
        cells = [c.strip() for c in re.split(r"(?<!\\)\|", line)[1:-1]]
        if table is None:
            head = [clean(c).lower() for c in cells]
            kind = {"field": "column"}.get(head[0], head[0])
            if where and kind in ("attribute", "column", "dataset") and "type" in head:
                table = (kind, head)
            else:
                table = ("other", head)
            continue
        if set(line) <= set("|-: "):
            continue
        kind, head = table
        if kind == "other":
            continue
        col = {h: clean(cells[k]) if k < len(cells) else "" for k, h in enumerate(head)}
        units = col.get("units", "")
        for name in re.findall(r"`([^`]+)`", cells[0]):
            entry = (pattern(name), name, col["type"], units, col.get("columns", ""))
            doc.setdefault(where, {}).setdefault(kind, []).append(entry)
    return doc


class Checker:
    def __init__(self, doc, docname):
        self.doc, self.docname, self.faults = doc, docname, []
        self.sections = [(pattern(p), p, v) for p, v in doc.items()]

    def fault(self, msg):
        self.faults.append(msg)

    def section(self, path):
        for rx, p, v in self.sections:
            if rx.match(path):
                return p, v
        return None, {}

    def entry(self, path, kind, name):
        p, v = self.section(path)
        for e in v.get(kind, []):
            if e[0].match(name):
                return p, e
        return p, None

    def dataset_entry(self, path):
        """A dataset or group documented in its parent's `dataset` table."""
        parent, name = path.rsplit("/", 1)
        return self.entry(parent or "/", "dataset", name)

    # --- types ---------------------------------------------------------

    @staticmethod
    def type_of(dtype, shape, is_attr):
        """The file's type in the layout's words."""
        base = None
        if dtype.names:
            return "compound"
        s = h5py.check_string_dtype(dtype)
        if s is not None:
            base = "string (variable length)" if s.length is None else "string"
        elif dtype.kind == "f":
            base = "double" if dtype.itemsize == 8 else "float%d" % (8 * dtype.itemsize)
        elif dtype.kind in "iu":
            base = "int64" if dtype.itemsize == 8 and dtype.kind == "i" else \
                "%sint%d" % ("u" if dtype.kind == "u" else "", 8 * dtype.itemsize)
        else:
            base = str(dtype)
        if len(shape) == 0:
            return base
        if len(shape) == 1:
            return base.split(" ")[0] + "[n]"
        return base.split(" ")[0] + "[n×%d]" % shape[1]

    @staticmethod
    def same_type(got, want):
        # a fixed or a variable-length string where the layout says "string";
        # [n×k]: any number of columns
        if want.endswith("[n×k]"):
            want, got = want[:-2], re.sub(r"×\d+\]$", "×", got)
        return want == got or want == "string" and got == "string (variable length)"

    # --- units ---------------------------------------------------------

    @staticmethod
    def text(v):
        if isinstance(v, bytes):
            return v.decode()
        if isinstance(v, np.ndarray):
            return " ".join(Checker.text(x) for x in v.tolist())
        return str(v)

    def suffix_rule(self, where, name, units):
        for suf, u in SUFFIX_UNITS:
            if name.endswith(suf):
                if not units.startswith(u):
                    self.fault("%s: %s: the name says %s (suffix %s), its units are %r: rename "
                               "it or fix its units" % (where, name, u, suf, units))
                return

    # --- the walk ------------------------------------------------------

    def attrs(self, path, obj, fname):
        ds = isinstance(obj, h5py.Dataset)
        for name in obj.attrs:
            # what describes a dataset: documented with it, not as attributes
            if ds and (name in ("units", "columns") or name.startswith("units_") and
                       obj.dtype.names and name[6:] in obj.dtype.names):
                continue
            aid = obj.attrs.get_id(name)
            sec, e = self.entry(path, "attribute", name)
            got = self.type_of(aid.dtype, aid.shape, True)
            if e is None:
                self.fault("%s: %s: attribute %s (%s) is not in %s: add a row `| `%s` | %s | "
                           "UNITS | MEANING |` to the attribute table under the heading of `%s`"
                           % (fname, path, name, got, self.docname, name, got,
                              sec or path))
                continue
            if not self.same_type(got, e[2]):
                self.fault("%s: %s: attribute %s is %s, %s says %s (table of `%s`)"
                           % (fname, path, name, got, self.docname, e[2], sec))
            if not got.startswith("string"):
                self.suffix_rule("%s: %s" % (fname, path), name, e[3])

    def dataset(self, path, d, fname):
        sec, e = self.dataset_entry(path)
        got = self.type_of(d.dtype, d.shape, False)
        if e is None:
            self.fault("%s: %s: dataset (%s) is not in %s: add a row `| `%s` | %s | UNITS | "
                       "MEANING |` to the dataset table under the heading of `%s`"
                       % (fname, path, got, self.docname, path.rsplit("/", 1)[1], got,
                          path.rsplit("/", 1)[0] or "/"))
        elif not self.same_type(got, e[2]):
            self.fault("%s: %s: dataset is %s, %s says %s (table of `%s`)"
                       % (fname, path, got, self.docname, e[2], sec))
        if d.dtype.names:
            self.table(path, d, fname)
        elif not got.startswith("string"):
            units = d.attrs.get("units")
            if units is None:
                self.fault("%s: %s: a dataset of numbers without a units attribute"
                           % (fname, path))
            elif e is not None:
                u = self.text(units)
                if e[3] == "one per row":
                    n = np.asarray(units).size
                    if n != d.shape[0]:
                        self.fault("%s: %s: %d units for %d rows" % (fname, path, n, d.shape[0]))
                elif e[3] == "one per column":
                    n = np.asarray(units).size
                    if n != (d.shape[1] if d.ndim == 2 else 1):
                        self.fault("%s: %s: %d units for %s columns" % (fname, path, n,
                                                                       d.shape[1:]))
                elif u != e[3]:
                    self.fault("%s: %s: units %r, %s says %r (table of `%s`)"
                               % (fname, path, u, self.docname, e[3], sec))
                if d.ndim == 1 and e[3] != "one per row":
                    self.suffix_rule(fname, path.rsplit("/", 1)[1], u)
            if d.ndim == 2:
                cols = d.attrs.get("columns")
                if cols is None:
                    self.fault("%s: %s: a table of %d columns without a columns attribute"
                               % (fname, path, d.shape[1]))
                else:
                    c = self.text(cols).split()
                    u = [self.text(x) for x in np.asarray(units).reshape(-1)] \
                        if units is not None else []
                    if len(c) != d.shape[1] or len(u) != d.shape[1]:
                        self.fault("%s: %s: %d columns, %d names, %d units: one of each per "
                                   "column" % (fname, path, d.shape[1], len(c), len(u)))
                    if e is not None and not self.same_columns(c, e[4].split()):
                        self.fault("%s: %s: columns %r, %s says %r (table of `%s`)"
                                   % (fname, path, " ".join(c), self.docname, e[4], sec))
                    for cn, cu in zip(c, u):
                        self.suffix_rule("%s: %s" % (fname, path), cn, cu)
        self.attrs(path, d, fname)

    @staticmethod
    def same_columns(got, want):
        """The columns as documented: in order; a documented name with a
        placeholder (sa_<T>s_g) stands for any number of columns after the
        literal ones, each matching one such name."""
        fixed = [w for w in want if "<" not in w]
        free = [pattern(w) for w in want if "<" in w]
        if not free:
            return got == want
        return got[:len(fixed)] == fixed and \
            all(any(p.match(c) for p in free) for c in got[len(fixed):])

    def table(self, path, d, fname):
        for name in d.dtype.names:
            sec, e = self.entry(path, "column", name)
            got = self.type_of(d.dtype[name], (), False)
            units = d.attrs.get("units_" + name)
            if e is None:
                self.fault("%s: %s: column %s (%s) is not in %s: add a row `| `%s` | %s | "
                           "UNITS | MEANING |` to the column table under the heading of `%s`"
                           % (fname, path, name, got, self.docname, name, got, path))
                continue
            if not self.same_type(got, e[2]):
                self.fault("%s: %s: column %s is %s, %s says %s (table of `%s`)"
                           % (fname, path, name, got, self.docname, e[2], sec))
            if units is None:
                self.fault("%s: %s: column %s has no units_%s attribute" % (fname, path, name,
                                                                           name))
                continue
            u = self.text(units)
            if u != e[3]:
                self.fault("%s: %s: units_%s is %r, %s says %r (table of `%s`)"
                           % (fname, path, name, u, self.docname, e[3], sec))
            if not got.startswith("string"):
                self.suffix_rule("%s: %s" % (fname, path), name, u)

    def group(self, path, g, fname):
        if path != "/":
            sec, v = self.section(path)
            _, e = self.dataset_entry(path)
            parent = any(p.startswith(path + "/") for _, p, _ in self.sections)
            if sec is None and not parent and (e is None or e[2] != "group"):
                self.fault("%s: %s: group is not in %s: add a heading with `%s` and its "
                           "tables" % (fname, path, self.docname, path))
        self.attrs(path, g, fname)

    def walk(self, fname):
        f = h5py.File(fname, "r")
        n = [0]

        def visit(name, obj):
            n[0] += 1
            path = "/" + name
            if isinstance(obj, h5py.Dataset):
                self.dataset(path, obj, fname)
            else:
                self.group(path, obj, fname)
        self.group("/", f, fname)
        f.visititems(visit)
        return n[0]


def main():
    docname, files = sys.argv[1], sys.argv[2:]
    doc = parse_layout(docname)
    c = Checker(doc, docname)
    objects = sum(c.walk(f) for f in files)
    for msg in c.faults[:int(__import__("os").environ.get("AQ_LAYOUT_MAX", "40"))]:
        print(msg)
    print("%d objects in %d files, %d documented objects, %d faults"
          % (objects, len(files), sum(len(x) for v in doc.values() for x in v.values()),
             len(c.faults)))
    sys.exit(1 if c.faults or objects == 0 else 0)


if __name__ == "__main__":
    main()
