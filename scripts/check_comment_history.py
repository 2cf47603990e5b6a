#!/usr/bin/env python3
"""Checks that code comments say why in terms of geometry, sensors or data,
not which run prompted them: no comment names a random scene's seed (a
number of 7 or more digits after "scene" or "seed") or a date (YYYY-MM-DD).
The reason for a rule belongs in the comment; the history is in the commits.

Usage: check_comment_history.py PATH...             (exit 1 on a finding)
       check_comment_history.py --expect N PATH...  (exit 0 exactly when N
              findings: the check's own test, on a planted example)
PATH: files, or folders searched for C++ sources and headers.
"""
import os
import re
import sys

SUFFIXES = (".cpp", ".hpp", ".h", ".cc", ".in")
SEED = re.compile(r"\b(scene|seed)s?\b[^0-9\n]{0,40}?\b\d{7,}\b", re.IGNORECASE)
DATE = re.compile(r"\b20\d\d-[01]\d-[0-3]\d\b")


def files(paths):
    for path in paths:
        if os.path.isdir(path):
            for root, _, names in os.walk(path):
                for name in sorted(names):
                    if name.endswith(SUFFIXES):
                        yield os.path.join(root, name)
        else:
            yield path


def comments(text):
    """(line number, comment text) of each // comment and each line of a /* */ comment."""
    in_block = False
    for number, line in enumerate(text.splitlines(), 1):
        if in_block:
            end = line.find("*/")
            yield number, line if end < 0 else line[:end]
            in_block = end < 0
            continue
        slash = line.find("//")
        block = line.find("/*")
        if slash >= 0 and (block < 0 or slash < block):
            yield number, line[slash:]
        elif block >= 0:
            end = line.find("*/", block + 2)
            yield number, line[block:] if end < 0 else line[block:end]
            in_block = end < 0


def findings(paths):
    for path in files(paths):
        with open(path, encoding="utf-8", errors="replace") as source:
            text = source.read()
        for number, comment in comments(text):
            for pattern, what in ((SEED, "a scene's seed"), (DATE, "a date")):
                match = pattern.search(comment)
                if match:
                    yield f"{path}:{number}: comment names {what} ({match.group(0)!r}): say why in terms of the geometry, sensors or data"


def main(argv):
    expect = None
    if len(argv) > 2 and argv[1] == "--expect":
        expect = int(argv[2])
        argv = argv[2:]
    found = list(findings(argv[1:]))
    if expect is not None:
        if len(found) != expect:
            print(f"check_comment_history: expected {expect} findings, got {len(found)}:", *found, sep="\n")
            return 1
        return 0
    for line in found:
        print(line)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
