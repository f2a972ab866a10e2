#!/usr/bin/env python3
"""Runs the commands a documentation page shows and compares the output it prints.

    check_docs.py --source SRC --build BUILD --bin BIN --scratch DIR PAGE.md
    check_docs.py --runs-mpi PAGE.md      (1 if a block the check would run starts mpirun, else 0)

Conventions for writers of README.md and docs/*.md:

* A fenced block opened with ```sh is a runnable command block. It runs with bash (-e, -o pipefail)
  in a scratch directory holding a fresh copy of SRC/data and a link `build` to BUILD, with BIN
  first on PATH, so both `sedwave ...` and `build/bin/sedwave ...` work. Blocks of one page run in
  order in the same directory, so a later block may use what an earlier one wrote. A block fails
  the check when it exits non-zero or runs past --timeout seconds. Syntax summaries with
  placeholders use a plain ``` fence, which is never run.
  A command that writes a table over a shipped one (data/tables/...) resumes it, as a user's rerun
  would: such a block checks the command line and the files, not the table's values; show values
  with `sedwave show` and an output block to check them.
* <!-- docs-check: file PATH --> right before a block says the block shows the file PATH (relative to
  SRC) whole: its lines must equal the file's. A program shown this way is built and run where that
  file lives (an example's ctest), so the page shows code that runs.
* <!-- docs-check: skip (REASON) --> right before a block (blank lines allowed) skips it; the
  reason is required and printed.
* <!-- docs-check: exit N (REASON) --> right before a block says it is expected to exit with code N
  (e.g. 3: sedwave ran and flagged a result) instead of 0; the reason is required.
* <!-- docs-check: output of the block above --> right before a plain block says the block shows
  what the runnable block before it prints. Each non-blank line shown must appear in the real
  output, in order, with the same words, and its numbers must agree to 3 significant figures
  (relative difference at most 0.5e-2); "(N significant figures)" before "-->" changes N.
  Wall-clock times (a number followed by "s" or "ms") are not compared. A shown line may leave out
  lines of the real output, never change them.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import time

DIRECTIVE = re.compile(r"<!--\s*docs-check:\s*(.*?)\s*-->")
SKIP = re.compile(r"skip \((.+)\)$")
OUTPUT = re.compile(r"output of the block above(?: \((\d+) significant figures\))?$")
EXIT = re.compile(r"exit (\d+) \((.+)\)$")
FILE = re.compile(r"file (\S+)$")
FENCE = re.compile(r"^```(\S*)\s*$")
# A number that stands alone: not a digit inside a name such as run2.h5 or thesis_w3.
NUMBER = re.compile(r"(?<![\w.])[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?(?![\w.]*\w)")
WALL_TIME = re.compile(r"\s*m?s\b")


class Block:
    def __init__(self, line, language, text, directive):
        self.line = line  # 1-based line of the opening fence
        self.language = language
        self.text = text
        self.directive = directive  # (kind, argument) or None


def read_blocks(page):
    """The fenced blocks of a page, each with the docs-check directive that precedes it."""
    blocks, pending, problems = [], None, []
    lines = open(page, encoding="utf-8").read().split("\n")
    i = 0
    while i < len(lines):
        line = lines[i]
        found = DIRECTIVE.search(line)
        if found:
            if pending:
                problems.append(f"{page}:{pending[2]}: docs-check directive not followed by a fenced block")
            pending = parse_directive(page, i + 1, found.group(1), problems)
        elif FENCE.match(line):
            end = i + 1
            while end < len(lines) and lines[end].strip() != "```":
                end += 1
            blocks.append(Block(i + 1, FENCE.match(line).group(1), "\n".join(lines[i + 1:end]),
                                pending[:2] if pending else None))
            pending, i = None, end
        elif line.strip() and pending:
            problems.append(f"{page}:{pending[2]}: docs-check directive not followed by a fenced block")
            pending = None
        i += 1
    return blocks, problems


def parse_directive(page, line, text, problems):
    skip, output, exit_code, file = SKIP.match(text), OUTPUT.match(text), EXIT.match(text), FILE.match(text)
    if file:
        return ("file", file.group(1), line)
    if skip:
        return ("skip", skip.group(1), line)
    if exit_code:
        return ("exit", int(exit_code.group(1)), line)
    if output:
        return ("output", int(output.group(1) or 3), line)
    problems.append(f"{page}:{line}: unknown docs-check directive '{text}' "
                    "(expected 'skip (REASON)', 'exit N (REASON)', 'file PATH' or 'output of the block above')")
    return None


def prepare_scratch(args):
    if os.path.exists(args.scratch):
        shutil.rmtree(args.scratch)
    os.makedirs(args.scratch)
    shutil.copytree(os.path.join(args.source, "data"), os.path.join(args.scratch, "data"))
    os.symlink(os.path.abspath(args.build), os.path.join(args.scratch, "build"))


def run_block(block, args, environment):
    started = time.monotonic()
    try:
        done = subprocess.run(["bash", "-e", "-o", "pipefail", "-c", block.text], cwd=args.scratch,
                              env=environment, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              timeout=args.timeout)
        output, code = done.stdout.decode("utf-8", "replace"), done.returncode
    except subprocess.TimeoutExpired as expired:
        output, code = (expired.stdout or b"").decode("utf-8", "replace"), "timeout"
    return output, code, time.monotonic() - started


def shape(line):
    """A line with its numbers replaced by '#' and its runs of blanks by one space."""
    return " ".join(NUMBER.sub("#", line).split())


def numbers_to_compare(line):
    """The line's numbers, None for a wall-clock time (never compared)."""
    values = []
    for match in NUMBER.finditer(line):
        is_time = WALL_TIME.match(line, match.end())
        values.append(None if is_time else float(match.group(0)))
    return values


def agree(shown, real, figures):
    return abs(shown - real) <= 0.5 * 10.0 ** (1 - figures) * max(abs(shown), abs(real))


def compare_output(shown_text, output, figures):
    """Problems found comparing a shown output block with the real output (empty when they agree)."""
    real_lines, problems = output.split("\n"), []
    position = 0
    for shown in (line for line in shown_text.split("\n") if line.strip()):
        match = next((i for i in range(position, len(real_lines)) if shape(real_lines[i]) == shape(shown)), None)
        if match is None:
            tail = "\n    ".join(real_lines[position:][-30:])
            return problems + [f"no line like this (in this order) in the output:\n    {shown}\n"
                               f"  output from there on:\n    {tail}"]
        real, position = real_lines[match], match + 1
        pairs = zip(numbers_to_compare(shown), numbers_to_compare(real))
        if any(a is not None and not agree(a, b, figures) for a, b in pairs):
            problems.append(f"numbers differ at {figures} significant figures:\n  shown: {shown}\n  today: {real}")
    return problems


def runs(block):
    """Whether the check runs this block: a ```sh block that no directive skips or marks as output."""
    return block.language == "sh" and (not block.directive or block.directive[0] not in ("skip", "output", "file"))


def check_page(args):
    blocks, problems = read_blocks(args.page)
    name = os.path.relpath(args.page, args.source)
    prepare_scratch(args)
    environment = dict(os.environ, PATH=os.path.abspath(args.bin) + os.pathsep + os.environ.get("PATH", ""))
    last_output = None  # of the last runnable block; None when it was skipped
    for block in blocks:
        where = f"{name}:{block.line}"
        kind = block.directive[0] if block.directive else None
        if kind == "skip":
            print(f"SKIP  {where}: {block.directive[1]}")
            last_output = None
        elif kind == "file":
            path = os.path.join(args.source, block.directive[1])
            shown = open(path, encoding="utf-8").read().rstrip("\n") if os.path.isfile(path) else None
            same = shown == block.text.rstrip("\n")
            print(f"{'OK' if same else 'FAIL':<5} {where}: the block shows {block.directive[1]}")
            if not same:
                problems.append(f"{where}: the block is not the file {block.directive[1]}"
                                + (" (no such file)" if shown is None else ": copy the file into the page"))
        elif kind == "output":
            if last_output is None:
                print(f"SKIP  {where}: output of a block that was not run")
                continue
            found = compare_output(block.text, last_output, block.directive[1])
            print(f"{'FAIL' if found else 'OK':<5} {where}: output compared at {block.directive[1]} significant figures")
            problems += [f"{where}: {p}" for p in found]
        elif runs(block):
            last_output, code, seconds = run_block(block, args, environment)
            expected = block.directive[1] if kind == "exit" else 0
            print(f"{'OK' if code == expected else 'FAIL':<5} {where}: ran in {seconds:.1f} s (exit {code})")
            if code != expected:
                tail = "\n".join(last_output.rstrip().split("\n")[-20:])
                problems.append(f"{where}: exit status {code} (expected {expected}) from\n{block.text}\n--- last lines of output ---\n{tail}")
    for problem in problems:
        print(f"\ndocs-check: {problem}", file=sys.stderr)
    return 1 if problems else 0


def runs_mpi(page):
    """Whether a block the check runs on this page starts mpirun (a page may name it in its text
    without running it)."""
    blocks, _ = read_blocks(page)
    return any(runs(b) and "mpirun" in b.text for b in blocks)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--runs-mpi", action="store_true",
                        help="print 1 if a block the check runs starts mpirun, else 0, and run nothing")
    parser.add_argument("--source", help="source tree (data/ is copied from it)")
    parser.add_argument("--build", help="build tree, linked as ./build")
    parser.add_argument("--bin", help="directory of the sedwave executable, put on PATH")
    parser.add_argument("--scratch", help="working directory (emptied first)")
    parser.add_argument("--timeout", type=float, default=150.0, help="seconds one block may run")
    parser.add_argument("page")
    args = parser.parse_args()
    if args.runs_mpi:
        print(1 if runs_mpi(args.page) else 0)
        return 0
    missing = [f"--{name}" for name in ("source", "build", "bin", "scratch") if getattr(args, name) is None]
    if missing:
        parser.error("the check needs " + ", ".join(missing))
    return check_page(args)


if __name__ == "__main__":
    sys.exit(main())
