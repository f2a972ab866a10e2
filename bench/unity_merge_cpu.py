#!/usr/bin/env python3
"""CPU seconds of each target's unity batches compiled one by one, against the same batches joined
into one file: what one batch per target saves, free of the scatter of whole parallel builds.

Usage: bench/unity_merge_cpu.py BUILD_DIR
BUILD_DIR is a configured and built tree with batches of 8 (-DSEDWAVE_UNITY_BATCH=8); its
compile_commands.json gives each batch's command. Every compilation runs alone, without a compiler
cache, output to a scratch file; prints user + system CPU seconds per target with more than one
batch, then the totals.
"""
import collections
import json
import os
import resource
import subprocess
import sys
import tempfile


def cpu_seconds(command, directory):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(command, shell=True, cwd=directory, check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__.split("\n\n")[1])
    entries = json.load(open(os.path.join(sys.argv[1], "compile_commands.json")))
    batches = collections.defaultdict(list)
    for e in entries:
        if "/Unity/unity_" in e["file"]:
            batches[e["file"].split("/Unity/")[0]].append(e)
    scratch = tempfile.mkdtemp()
    joined_file, object_file = os.path.join(scratch, "joined.cxx"), os.path.join(scratch, "out.o")
    totals = [0.0, 0.0]
    print(f"{'target':<28} {'batches':>7} {'one by one s':>12} {'joined s':>9}")
    for target, group in sorted(batches.items()):
        if len(group) < 2:
            continue
        # The command without its output and source, the cache launcher dropped.
        stem = lambda e: e["command"].replace("ccache ", "").split(" -o ")[0]
        apart = sum(cpu_seconds(f"{stem(e)} -o {object_file} -c {e['file']}", e["directory"]) for e in group)
        with open(joined_file, "w") as out:
            out.write("".join(open(e["file"]).read() for e in group))
        joined = cpu_seconds(f"{stem(group[0])} -o {object_file} -c {joined_file}", group[0]["directory"])
        totals[0] += apart
        totals[1] += joined
        print(f"{os.path.basename(target):<28} {len(group):>7} {apart:>12.1f} {joined:>9.1f}", flush=True)
    print(f"{'total':<28} {'':>7} {totals[0]:>12.1f} {totals[1]:>9.1f}")


if __name__ == "__main__":
    main()
