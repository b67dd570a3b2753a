#!/usr/bin/env python3
"""same_database.py - whether two SQLite databases hold the same data, cell
by cell: the comparison of `mpb import -p` with OMPL's
ompl_benchmark_statistics.py (tests/integration/test_import_parity.sh,
bench/import.sh).

  same_database.py [--properties [--values]] WANT.db GOT.db

Every table and view of WANT must be in GOT with the same columns (names,
declared types, in order), the same number of rows, and in each row (in
rowid order, a view's in all its columns' order) the same value in every
cell, of the same SQLite type (integer 1 is not real 1.0 nor text '1'),
reals to the last bit. GOT may have no table that WANT lacks.

--properties compares what the experiments and runs are, not how the
database names things: the tables experiments, runs and progress only,
the columns of WANT's (GOT may have more; one that WANT never fills, a
property a log declares and no run measured, must be there too, as
NULLs), without the ids (id, experimentid, plannerid, runid), for the
round trip through an mpbench database (mpb import -d, mpb export), whose
planners are named mpbench's way and whose experiments have mpbench's
parameters too.
--values then takes numbers by value, not type (1 is 1.0), exactly (an
integer past 2^53 is not the double nearest it).

Prints each difference (at most 20), then "same" or "DIFFERENT: N
differences"; exit 0 when the same, 1 when not, 2 on a bad command line.
"""
import sqlite3
import struct
import sys

IDS = {"id", "experimentid", "plannerid", "runid"}


def q(name):
    return '"' + name.replace('"', '""') + '"'


def objects(db):
    return {name: kind for name, kind in db.execute(
        "SELECT name, type FROM sqlite_master WHERE type IN ('table', 'view')")}


def columns(db, table):
    return [(r[1], r[2], r[3], r[4], r[5])
            for r in db.execute("SELECT * FROM pragma_table_info(?)", (table,))]


def cell(v):
    """A value with its SQLite type, reals as their bits."""
    if isinstance(v, float):
        return ("real", struct.pack(">d", v).hex(), repr(v))
    if isinstance(v, int):
        return ("integer", v, repr(v))
    if isinstance(v, bytes):
        return ("blob", v, repr(v))
    if v is None:
        return ("null", None, "NULL")
    return ("text", v, repr(v))


def rows(db, table, kind, cols):
    sel = ",".join(q(c) for c in cols)
    if kind == "table" and not db.execute(
            "SELECT 1 FROM sqlite_master WHERE name = ? AND sql LIKE "
            "'%WITHOUT ROWID%'", (table,)).fetchone():
        order = "rowid"
    else:
        order = ",".join(str(i + 1) for i in range(len(cols)))
    return db.execute("SELECT %s FROM %s ORDER BY %s" % (sel, q(table), order))


def main(argv):
    runs_only = values = False
    if argv and argv[0] == "--properties":
        runs_only, argv = True, argv[1:]
        if argv and argv[0] == "--values":
            values, argv = True, argv[1:]
    if len(argv) != 2:
        sys.stderr.write(__doc__.split("\n\n")[1] + "\n")
        return 2
    want, got = (sqlite3.connect("file:%s?mode=ro" % p, uri=True) for p in argv)
    diffs = []

    def differ(text):
        diffs.append(text)
        if len(diffs) <= 20:
            print(text)

    wo, go = objects(want), objects(got)
    names = sorted(wo)
    if runs_only:
        names = [n for n in names if n in ("experiments", "runs", "progress")]
    else:
        for n in sorted(set(go) - set(wo)):
            differ("%s: only in %s" % (n, argv[1]))
    for name in names:
        if name not in go:
            differ("%s: not in %s" % (name, argv[1]))
            continue
        wc, gc = columns(want, name), columns(got, name)
        if runs_only:
            have = {c[0] for c in gc}
            cols = [c[0] for c in wc if c[0] not in IDS]
            for c in cols:
                if c not in have:
                    differ("%s.%s: not in %s" % (name, c, argv[1]))
            cols = [c for c in cols if c in have]
        else:
            if wc != gc:
                show = lambda cs: ", ".join(
                    " ".join(str(x) for x in c[:2]) for c in cs)
                differ("%s: columns (%s), not (%s)" % (name, show(gc), show(wc)))
            # The cells of the columns both have, still.
            have = {c[0] for c in gc}
            cols = [c[0] for c in wc if c[0] in have]
        if not cols:        # nothing filled: the rows' count only
            count = "SELECT count(*) FROM %s" % q(name)
            wr = [()] * want.execute(count).fetchone()[0]
            gr = [()] * got.execute(count).fetchone()[0]
        else:
            wr = rows(want, name, wo[name], cols).fetchall()
            gr = rows(got, name, go[name], cols).fetchall()
        if len(wr) != len(gr):
            differ("%s: %d rows, not %d" % (name, len(gr), len(wr)))
        for i, (a, b) in enumerate(zip(wr, gr)):
            for c, x, y in zip(cols, a, b):
                if values and isinstance(x, (int, float)) and \
                        isinstance(y, (int, float)) and x == y:
                    continue
                cx, cy = cell(x), cell(y)
                if cx[:2] != cy[:2]:
                    differ("%s row %d %s: %s %s, not %s %s"
                           % (name, i + 1, c, cy[0], cy[2], cx[0], cx[2]))
    if diffs:
        print("DIFFERENT: %d differences" % len(diffs))
        return 1
    print("same")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
