#!/usr/bin/env python3
"""gen_walks.py - the receive gate's bounds walks, from the .lcm files.

    gen_walks.py WALKS.h TYPES.h FILE.lcm...

Writes to WALKS.h one C function per struct, walk_<struct>(cursor *), that steps over
an encoding of the struct's fields (after the fingerprint, for a message)
field by field, checking every length against the bytes that remain
without allocating: libmpbench/src/net/wire.c includes OUT.h and gives
the cursor and its steps (string, skip, dim, elems). LCM's generated
decoders allocate an array by its count before they read it, so a count
must be proved to fit the message first (wire.h). Generated at build time
beside lcm-gen's bindings, never committed: a message is its .lcm file
and one line of MPB_MESSAGES (mpbench/messages.h).

The .lcm subset read: a package line, one struct per file, fields of the
primitive types, string and other structs of the package, one-dimensional
arrays of a fixed size or sized by an integer field declared before them,
and constants (skipped). Anything else is an error naming the file and
line. TYPES.h includes lcm-gen's header of every struct, for the
headers that name them all (mpbench/auth.h).
"""
import re
import sys

SIZES = {"int8_t": 1, "byte": 1, "boolean": 1, "int16_t": 2, "int32_t": 4,
         "int64_t": 8, "float": 4, "double": 8}
FIELD = re.compile(r"^([A-Za-z_][A-Za-z0-9_.]*)\s+([A-Za-z_][A-Za-z0-9_]*)"
                   r"\s*(?:\[\s*([A-Za-z0-9_]+)\s*\])?\s*;$")


def fail(path, line, what):
    sys.exit(f"{path}:{line}: {what}")


def parse(path):
    """(struct name, [(type, name, dim or None, line)])."""
    text = open(path, encoding="utf-8").read()
    text = re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group(0).count("\n"), text,
                  flags=re.S)
    name, fields, depth = None, [], 0
    for no, raw in enumerate(text.split("\n"), 1):
        line = raw.split("//", 1)[0].strip()
        if not line or line.startswith("package "):
            continue
        m = re.match(r"^struct\s+([A-Za-z_][A-Za-z0-9_]*)\s*(\{)?$", line)
        if m:
            if name is not None:
                fail(path, no, "one struct per file")
            name, depth = m.group(1), 1 if m.group(2) else 0
            continue
        if line == "{":
            depth += 1
            continue
        if line == "}":
            depth -= 1
            continue
        if line.startswith("const "):
            continue
        m = FIELD.match(line)
        if m is None or name is None or depth != 1:
            fail(path, no, f"not read by gen_walks.py: '{line}'")
        fields.append((m.group(1), m.group(2), m.group(3), no))
    if name is None:
        fail(path, 1, "no struct")
    return name, fields


def min_size(t, structs, seen=()):
    """The fewest bytes an encoding of a value of type t takes."""
    if t in SIZES:
        return SIZES[t]
    if t == "string":
        return 5                      # its length and the NUL
    if t in seen:
        sys.exit(f"gen_walks.py: {t} contains itself")
    total = 0
    for ft, _, dim, _ in structs[t][1]:
        if dim is None:
            total += min_size(ft, structs, seen + (t,))
        elif dim.isdigit():
            total += int(dim) * min_size(ft, structs, seen + (t,))
    return total


def walk_value(t, structs, indent):
    if t in SIZES:
        return [f"{indent}skip(c, {SIZES[t]});"]
    if t == "string":
        return [f"{indent}string(c);"]
    return [f"{indent}walk_{t}(c);"]


def emit(name, fields, structs, path, out):
    out.append(f"/* {name}, from {path} */")
    out.append(f"static void walk_{name}(cursor *c)")
    out.append("{")
    ints = {fn: ft for ft, fn, dim, _ in fields if dim is None and ft in SIZES}
    dims = {dim for _, _, dim, _ in fields if dim is not None and not dim.isdigit()}
    declared = set()
    for ft, fn, dim, no in fields:
        if ft not in SIZES and ft != "string" and ft not in structs:
            fail(path, no, f"type '{ft}' is not one of the package's")
        if dim is None:
            if fn in dims:
                if ft not in ("int8_t", "int16_t", "int32_t", "int64_t"):
                    fail(path, no, f"'{fn}' sizes an array: an integer")
                out.append(f"    int64_t {fn} = dim(c, {SIZES[ft]});")
                declared.add(fn)
            else:
                out += [ln + f"  /* {fn} */" if i == 0 else ln
                        for i, ln in enumerate(walk_value(ft, structs, "    "))]
            continue
        if dim.isdigit():
            n = int(dim)
            if ft in SIZES:
                out.append(f"    skip(c, {n * SIZES[ft]});  /* {fn}[{n}] */")
            else:
                out.append(f"    for (int i = 0; i < {n} && !c->bad; i++)  /* {fn} */")
                out += walk_value(ft, structs, "        ")
            continue
        if dim not in declared:
            fail(path, no, f"'{fn}' is sized by '{dim}', not an integer "
                 "field before it" if dim not in ints else
                 f"'{fn}' is sized by '{dim}', declared after it")
        size = min_size(ft, structs)
        if ft in SIZES:
            out.append(f"    if (elems(c, {dim}, {size}))  /* {fn} */")
            out.append(f"        skip(c, (size_t){dim} * {size});")
        else:
            out.append(f"    if (elems(c, {dim}, {size}))  /* {fn} */")
            out.append(f"        for (int64_t i = 0; i < {dim} && !c->bad; i++)")
            out += walk_value(ft, structs, "            ")
    out.append("}")
    out.append("")


def write_if_changed(path, text):
    """Unchanged, the file keeps its time: nothing rebuilds."""
    try:
        if open(path, encoding="utf-8").read() == text:
            return
    except OSError:
        pass
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


def main(argv):
    if len(argv) < 4:
        sys.exit("usage: gen_walks.py WALKS.h TYPES.h FILE.lcm...")
    structs = {}
    for path in argv[3:]:
        name, fields = parse(path)
        structs[name] = (path, fields)
    head = ["/* Generated by lcmtypes/gen_walks.py from the .lcm files: do not",
            " * edit. */", ""]
    out = head[:1] + [" * edit. Included by libmpbench/src/net/wire.c, which "
                      "gives the", " * cursor and its steps. */", ""]
    for name in sorted(structs):
        out.append(f"static void walk_{name}(cursor *c);")
    out.append("")
    for name in sorted(structs):
        path, fields = structs[name]
        emit(name, fields, structs, path.split("/")[-1], out)
    write_if_changed(argv[1], "\n".join(out) + "\n")
    types = head + ["#ifndef MPB_LCMTYPES_H", "#define MPB_LCMTYPES_H", ""]
    types += [f'#include "mpb_{name}.h"' for name in sorted(structs)]
    types += ["", "#endif"]
    write_if_changed(argv[2], "\n".join(types) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
