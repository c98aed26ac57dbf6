#!/usr/bin/python3
"""Pulls a recipe's shell blocks out of the docs, in order, so a test runs what a reader reads.

A recipe block is a ```sh fence right after a marker line
    <!-- recipe NAME host=HOST [background] [ready="REGEX"] -->
(HOST: the lab host it runs on; background: each command line is a long-running process, as in
its own terminal, ready once its output matches REGEX; otherwise the block runs as one script).

Usage: doc_recipes.py RECIPE OUT_DIR MARKDOWN...
Writes OUT_DIR/N.sh per block (N = 1, 2, ... in document order) and prints one line per block:
    N HOST MODE READY
MODE is background or foreground, READY the regex ("-" if none). Exits 1 if RECIPE has no block.
"""
import os
import re
import shlex
import sys

MARKER = re.compile(r"^\s*<!--\s*recipe\s+(.*?)\s*-->\s*$")
FENCE = re.compile(r"^(\s*)```")


def blocks_of(path):
    with open(path, encoding="utf-8") as markdown:
        lines = markdown.read().splitlines()
    i = 0
    while i < len(lines):
        marker = MARKER.match(lines[i])
        i += 1
        if not marker:
            continue
        words = shlex.split(marker.group(1))
        name, options = words[0], {}
        for word in words[1:]:
            key, _, value = word.partition("=")
            options[key] = value
        fence = FENCE.match(lines[i]) if i < len(lines) else None
        if not fence:
            sys.exit(f"{path}:{i}: recipe marker '{name}' is not followed by a ``` block")
        indent = len(fence.group(1))
        body = []
        i += 1
        while i < len(lines) and not FENCE.match(lines[i]):
            body.append(lines[i][indent:] if lines[i][:indent].strip() == "" else lines[i])
            i += 1
        i += 1
        yield name, options, "\n".join(body) + "\n"


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    recipe, out_dir, documents = sys.argv[1], sys.argv[2], sys.argv[3:]
    os.makedirs(out_dir, exist_ok=True)
    count = 0
    for path in documents:
        for name, options, body in blocks_of(path):
            if name != recipe:
                continue
            count += 1
            if "host" not in options:
                sys.exit(f"{path}: a block of recipe '{recipe}' names no host=")
            with open(os.path.join(out_dir, f"{count}.sh"), "w", encoding="utf-8") as out:
                out.write(body)
            mode = "background" if "background" in options else "foreground"
            print(count, options["host"], mode, options.get("ready") or "-")
    if count == 0:
        sys.exit(f"no block of recipe '{recipe}' in {' '.join(documents)}")


if __name__ == "__main__":
    main()
