#!/usr/bin/env python3
"""daemon_layers.py - the daemon's files call and include downwards only.

Reads the daemon's object files (which functions each defines, which it
uses, by `nm`) and its sources' #include lines, and fails, naming them, on
every circle between files: a file that calls (or includes) one that
calls it back, however long the way round. A circle means no file of it
can be read, tested or changed alone.

usage: daemon_layers.py OBJECT_DIR SOURCE_DIR
"""
import os
import re
import subprocess
import sys


def symbols(obj):
    """Functions obj defines and those it uses (external ones included)."""
    out = subprocess.run(["nm", obj], check=True, capture_output=True,
                         text=True).stdout
    defined, used = set(), set()
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 3 and parts[1] in "TD":
            defined.add(parts[2])
        elif len(parts) == 2 and parts[0] == "U":
            used.add(parts[1])
    return defined, used


def circles(graph):
    """Strongly connected components of more than one node (Tarjan)."""
    index, low, stack, on, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                found.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def call_graph(objdir):
    objs = sorted(f for f in os.listdir(objdir) if f.endswith(".c.o"))
    if not objs:
        sys.exit(f"{objdir}: no object files (is the daemon built?)")
    owner, uses = {}, {}
    for o in objs:
        name = o[:-2]                     # "scheduler.c"
        defined, used = symbols(os.path.join(objdir, o))
        for s in defined:
            owner[s] = name
        uses[name] = used
    graph = {}
    for name, used in uses.items():
        graph[name] = {owner[s] for s in used if s in owner and owner[s] != name}
    return graph


def include_graph(srcdir):
    graph = {}
    for f in sorted(os.listdir(srcdir)):
        if not f.endswith((".c", ".h")):
            continue
        with open(os.path.join(srcdir, f), encoding="utf-8") as fh:
            incs = re.findall(r'^#include "([^"/]+\.h)"', fh.read(), re.M)
        graph[f] = {i for i in incs if os.path.exists(os.path.join(srcdir, i))
                    and i != f}
    return graph


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__.strip().splitlines()[-1])
    objdir, srcdir = sys.argv[1], sys.argv[2]
    bad = 0
    for kind, graph in (("call", call_graph(objdir)),
                        ("include", include_graph(srcdir))):
        for comp in circles(graph):
            bad += 1
            print(f"daemon/: {kind} circle among {', '.join(comp)}: "
                  + "; ".join(f"{a} -> {', '.join(sorted(graph[a] & set(comp)))}"
                              for a in comp))
    if bad:
        return 1
    print("daemon/: no call or include circle")
    return 0


if __name__ == "__main__":
    sys.exit(main())
