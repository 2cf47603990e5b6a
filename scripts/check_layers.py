#!/usr/bin/env python3
"""Checks that the folders under src/ form layers: no folder includes a folder
that includes it back, directly or through others.

The graph: folder A depends on folder B when a source or header under src/A
includes a file of src/B (`#include "B/..."`) or a public header that B
implements (`#include <l2s/...>`). A public header l2s/.../NAME.hpp belongs
to the folder of NAME.cpp; without a NAME.cpp, to the folder of the sources
that include it first, as a source includes its own header (STYLE.md), when
they have no header of their own name and share a word of the header's
(pcd_reader.cpp and pcd_writer.cpp implement l2s/io/pcd.hpp). A public
header that no source implements (plain types, errors, export macros)
belongs to no folder. src/tools is the top:
nothing may include it, so it is left out.

Usage: check_layers.py SRC_DIR INCLUDE_DIR            (exit 1 on a cycle)
       check_layers.py --expect-cycle SRC_DIR INCLUDE_DIR
              (exit 0 exactly when there is a cycle: the check's own test,
              on a planted tree)
       check_layers.py --graph SRC_DIR INCLUDE_DIR    (print the edges)
"""
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]', re.MULTILINE)
SOURCE_SUFFIXES = (".cpp", ".hpp", ".h", ".cc")


def sources(src_dir):
    """(folder, path) of every source and header under src_dir's sub-folders."""
    for folder in sorted(os.listdir(src_dir)):
        top = os.path.join(src_dir, folder)
        if not os.path.isdir(top) or folder == "tools":
            continue
        for root, _, files in os.walk(top):
            for name in sorted(files):
                if name.endswith(SOURCE_SUFFIXES):
                    yield folder, os.path.join(root, name)


def includes(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        return INCLUDE.findall(f.read())


def stem(path):
    return os.path.splitext(os.path.basename(path))[0]


def public_header_owners(all_sources, include_dir):
    """Public header (as included, "l2s/...") -> the folder of `all_sources`
    ((folder, path) pairs) that implements it."""
    implementations = {stem(path): folder for folder, path in all_sources if path.endswith((".cpp", ".cc"))}
    header_stems = {stem(path) for _, path in all_sources if path.endswith((".hpp", ".h"))}
    for root, _, files in os.walk(include_dir):
        header_stems.update(stem(name) for name in files)
    owners = {}
    for root, _, files in os.walk(os.path.join(include_dir, "l2s")):
        for name in files:
            header = os.path.relpath(os.path.join(root, name), include_dir)
            if stem(name) in implementations:
                owners[header] = implementations[stem(name)]
    for folder, path in all_sources:
        if not path.endswith((".cpp", ".cc")) or stem(path) in header_stems:
            continue
        found = includes(path)
        if found and found[0][0] == "<" and found[0][1].startswith("l2s/"):
            if set(stem(path).split("_")) & set(stem(found[0][1]).split("_")):
                owners.setdefault(found[0][1], folder)
    return owners


def dependency_graph(src_dir, include_dir):
    all_sources = list(sources(src_dir))
    owners = public_header_owners(all_sources, include_dir)
    folders = {folder for folder, _ in all_sources}
    edges = {}  # (from, to) -> an example "file includes header"
    for folder, path in all_sources:
        for kind, header in includes(path):
            if kind == '"':
                target = header.split("/")[0] if "/" in header else folder
                if target not in folders:
                    continue
            else:
                target = owners.get(header)
                if target is None:
                    continue
            if target != folder:
                edges.setdefault((folder, target), f"{os.path.relpath(path, os.path.dirname(src_dir))} includes {header}")
    return folders, edges


def find_cycle(folders, edges):
    """One cycle as a list of folders [a, b, ..., a], or None."""
    graph = {f: sorted(b for (a, b) in edges if a == f) for f in folders}
    state = {}  # folder -> 1 on the current path, 2 done
    path = []

    def visit(node):
        state[node] = 1
        path.append(node)
        for nxt in graph[node]:
            if state.get(nxt) == 1:
                return path[path.index(nxt):] + [nxt]
            if nxt not in state:
                cycle = visit(nxt)
                if cycle:
                    return cycle
        path.pop()
        state[node] = 2
        return None

    for folder in sorted(folders):
        if folder not in state:
            cycle = visit(folder)
            if cycle:
                return cycle
    return None


def main(args):
    expect_cycle = graph_only = False
    if args[:1] == ["--expect-cycle"]:
        expect_cycle, args = True, args[1:]
    elif args[:1] == ["--graph"]:
        graph_only, args = True, args[1:]
    if len(args) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    folders, edges = dependency_graph(args[0], args[1])
    if graph_only:
        for (a, b), example in sorted(edges.items()):
            print(f"{a} -> {b}   ({example})")
        return 0
    cycle = find_cycle(folders, edges)
    if cycle:
        print("layers: a cycle between folders of " + args[0] + ": " + " -> ".join(cycle))
        for a, b in zip(cycle, cycle[1:]):
            print(f"  {a} -> {b}: {edges[(a, b)]}")
    if expect_cycle:
        return 0 if cycle else 1
    return 1 if cycle else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
