"""Blank, in a copy of src, every line that states a signature or a table row rather than
logic: declarations (a `::` line), comments, and deck-key rows (`call r%...` with their
continuation lines). Line numbers are kept, so `duplicates` on the copy points at the same
lines of src. doc/reference/modules.md measures with it what `duplicates` lists that is not
an argument list or a key row:

    rm -rf /tmp/x && mkdir /tmp/x && cp -r src /tmp/x/ && python3 .ci/strip_declarations.py \
        /tmp/x/src && duplicates --repo /tmp/x/src --most 80 --seconds 120
"""
import pathlib
import re
import sys

KEEP_STARTS = ("call", "if", "do", "allocate", "where")


def strip(text):
    out, continued = [], False
    for line in text.splitlines():
        s = line.strip()
        drop = continued or s.startswith("!") or re.match(r"call r%", s) is not None
        if "::" in s and not s.startswith(KEEP_STARTS):
            drop = True
        continued = drop and s.endswith("&") and not s.startswith("!")
        out.append("" if drop else line)
    return "\n".join(out) + "\n"


def main(root):
    for path in sorted(pathlib.Path(root).rglob("*.[fF]90")):
        path.write_text(strip(path.read_text()))


if __name__ == "__main__":
    main(sys.argv[1])
