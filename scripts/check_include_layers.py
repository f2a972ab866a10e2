#!/usr/bin/env python3
"""Fails when the folders of forward/ include each other in a loop, or io/ includes any of them.

Each folder of forward/ (dem, channel, linear, table, ...) is one layer: a layer may include the
layers below it, never one above. Every source and header under forward/src/<folder>/ and
forward/include/sedwave/forward/<folder>/ belongs to <folder>; files directly under forward/src/ and
forward/include/sedwave/forward/ belong to the layer "forward". The top-level io/ (the project's
files in and out, sedwave/io/...) is the layer "io", below all of forward/: it includes none of
them. An include names its folder by its path ("sedwave/forward/linear/x.hpp", "sedwave/io/x.hpp")
or, for private headers, relative to the including file ("../table/hdf5_table_io.hpp").

Above forward/, the top-level folders are layers too, each including only those below it:
io < forward < sampling < sediment < inversion < plot < apps. sampling/, sediment/ and inversion/
run without MPI: they include neither <mpi.h> nor a layer of forward/ that uses MPI (dem, channel,
linear, experiment, parallel, interface), so a program linked against them needs no MPI.

Prints the folder graph (with the files behind each edge on request) and every loop found; the exit
status is 1 when there is a loop, io/ includes a layer of forward/, or a top-level folder includes
one above it or MPI where it may not.
"""
import argparse
import pathlib
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+[<"]([^>"]+)[>"]', re.MULTILINE)
ROOT_LAYER = "forward"
IO_LAYER = "io"


def layer_of(path, forward):
    """The layer of a file under forward/ or io/, or None for files outside the layers (CMake lists)."""
    io = forward.parent / "io"
    if io in path.parents:
        return IO_LAYER if path.suffix in {".hpp", ".cpp", ".h"} else None
    parts = path.relative_to(forward).parts
    if parts[:3] == ("include", "sedwave", "forward"):
        rest = parts[3:]
    elif parts[0] == "src":
        rest = parts[1:]
    else:
        return None
    return rest[0] if len(rest) > 1 else ROOT_LAYER


def included_layer(name, including, forward):
    """The layer an include refers to, or None for system and third-party headers."""
    if name.startswith("sedwave/forward/"):
        rest = name.split("/")[2:]
        return rest[0] if len(rest) > 1 else ROOT_LAYER
    if name.startswith("sedwave/io/"):
        return IO_LAYER
    local = (including.parent / name).resolve()
    roots = (forward.resolve(), forward.resolve().parent / "io")
    if local.is_file() and any(root in local.parents for root in roots):
        return layer_of(local, forward.resolve())
    return None


def include_graph(forward):
    """{layer: {included layer: [including files]}} over every C++ file of forward/ and io/."""
    graph = {}
    for path in sorted(list(forward.rglob("*")) + list((forward.parent / "io").rglob("*"))):
        if path.suffix not in {".hpp", ".cpp", ".h"}:
            continue
        source = layer_of(path, forward)
        if source is None:
            continue
        graph.setdefault(source, {})
        for name in INCLUDE.findall(path.read_text(encoding="utf-8")):
            target = included_layer(name, path, forward)
            if target is not None and target != source:
                graph[source].setdefault(target, []).append(str(path.relative_to(forward.parent)))
    return graph


def loops(graph):
    """Every elementary loop, each once, as a list of layers starting from its smallest name."""
    found = set()

    def walk(start, node, trail):
        for nxt in graph.get(node, {}):
            if nxt == start:
                found.add(tuple(trail))
            elif nxt > start and nxt not in trail:
                walk(start, nxt, trail + [nxt])

    for start in sorted(graph):
        walk(start, start, [start])
    return sorted(found, key=lambda loop: (len(loop), loop))


# The top-level folders from the lowest layer up; each may include only the folders before it.
TOP_LAYERS = ["io", "forward", "sampling", "sediment", "inversion", "plot", "apps"]
MPI_FREE = {"sampling", "sediment", "inversion"}
MPI_FORWARD_LAYERS = {"dem", "channel", "linear", "experiment", "parallel", "interface"}


def top_level_problems(root):
    """Includes of a higher top-level folder, and MPI in a folder that must run without it."""
    problems = []
    for rank, folder in enumerate(TOP_LAYERS):
        for path in sorted((root / folder).rglob("*")):
            if path.suffix not in {".hpp", ".cpp", ".h"}:
                continue
            where = path.relative_to(root)
            for name in INCLUDE.findall(path.read_text(encoding="utf-8")):
                parts = name.split("/")
                if parts[0] == "sedwave" and len(parts) > 2 and parts[1] in TOP_LAYERS:
                    if TOP_LAYERS.index(parts[1]) > rank:
                        problems.append(f"{where} includes {name}: {parts[1]}/ sits above {folder}/")
                    if folder in MPI_FREE and parts[1] == "forward" and len(parts) > 3 and parts[2] in MPI_FORWARD_LAYERS:
                        problems.append(f"{where} includes {name}: {folder}/ runs without MPI")
                if folder in MPI_FREE and name == "mpi.h":
                    problems.append(f"{where} includes <mpi.h>: {folder}/ runs without MPI")
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("forward", nargs="?", default=pathlib.Path(__file__).resolve().parent.parent / "forward",
                        type=pathlib.Path, help="the forward/ folder (default: this checkout's)")
    parser.add_argument("--files", action="store_true", help="name the files behind every edge")
    args = parser.parse_args()
    graph = include_graph(args.forward)
    for layer in sorted(graph):
        print(f"{layer} -> {', '.join(sorted(graph[layer])) or '(nothing)'}")
        if args.files:
            for target, files in sorted(graph[layer].items()):
                for name in sorted(set(files)):
                    print(f"    {target}: {name}")
    found = loops(graph)
    above_io = graph.get(IO_LAYER, {})
    for target, files in sorted(above_io.items()):
        print(f"io includes {target} (io sits below forward/): {', '.join(sorted(set(files)))}")
    for loop in found:
        print("include loop: " + " -> ".join(loop + (loop[0],)))
        for a, b in zip(loop, loop[1:] + (loop[0],)):
            print(f"    {a} -> {b}: {', '.join(sorted(set(graph[a][b])))}")
    if found:
        print(f"{len(found)} include loop(s) between the folders of {args.forward}")
    misplaced = top_level_problems(args.forward.resolve().parent)
    for problem in misplaced:
        print(problem)
    if found or above_io or misplaced:
        return 1
    print("no include loops between the folders of forward/; io/ includes none of them")
    print("the top-level folders include only those below them; sampling/, sediment/ and inversion/ no MPI")
    return 0


if __name__ == "__main__":
    sys.exit(main())
