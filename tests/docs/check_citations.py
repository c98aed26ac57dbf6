#!/usr/bin/python3
"""Every citation in the repository resolves inside it: nothing cites a document it does not have.

Over every tracked text file (`git ls-files`; outside a git checkout, the tree without .git and
build*/), a line fails when it
  - mentions "digest": the sources were once cited through a private restatement of them (a
    "design digest" with its own section numbers) that the repository does not hold; they are
    cited by their own sections, equations and tables instead. A file that handles hashes
    (it names sha1/sha256/sha512/md5) may say digest for a hash, unless in a citation's form
    ("digest 3.7", "design digest", "digest's (4.4)");
  - cites architecture.md other than as docs/architecture.md or a relative link to it;
  - names a page docs/...md that does not exist;
  - cites a source by a short name "paper 0NN" (also paper0NN in identifiers) that
    docs/references.md does not define (the first column of its table of short names).
  - names, in backticks, a path of the repository that it does not have: in docs/ and README.md
    anywhere, in code only inside comments (`server/sim/contour_server.cpp`, `tests/components`;
    a path starts with a top-level folder of the repository; one with a placeholder, a wildcard
    or an ellipsis is no path).
This script itself is not scanned.

Usage: check_citations.py REPOSITORY_ROOT
Exit 0 when every citation resolves; 1 with each failure named (file:line: what).
"""
import os
import re
import subprocess
import sys

SELF = "tests/docs/check_citations.py"
REFERENCES = "docs/references.md"

DIGEST = re.compile(r"digest", re.IGNORECASE)
HASH_FILE = re.compile(r"\b(sha-?(1|224|256|384|512)(sum)?|md5(sum)?|hashlib)\b", re.IGNORECASE)
DIGEST_CITATION = re.compile(
    r"(design|seeds?)[ -]digest|digest('s)?\s*(\(?\s*§|\(?\s*\d|\[[ADG]\])", re.IGNORECASE)
ARCHITECTURE = re.compile(r"([\w./-]*)architecture\.md")
DOCS_PAGE = re.compile(r"([\w./-]*docs/[\w./-]*\.md)\b")
TOP_FOLDERS = ("bench", "client", "cmake", "control", "docker", "docs", "examples", "idl", "netsim", "plant",
               "python", "scripts", "server", "tests")
BACKTICKED_PATH = re.compile(r"`((?:" + "|".join(TOP_FOLDERS) + r")/[^`\s]*)`")
NOT_A_PATH = re.compile(r"[*{}<>%$|]|\.\.\.|…|[A-Z]{3,}")
COMMENT = re.compile(r"(//|#|/\*|^\s*\*)")
SHORT_NAME = re.compile(r"\bpaper[ _-]?(0\d\d)(?!\d)", re.IGNORECASE)
DEFINED_NAME = re.compile(r"^\|\s*paper (0\d\d)\b", re.IGNORECASE)


def tracked_files(root):
    """Repository-relative paths of the files to scan."""
    if os.path.exists(os.path.join(root, ".git")):
        try:
            out = subprocess.run(["git", "-C", root, "ls-files", "-z"], check=True, capture_output=True).stdout
            return sorted(p for p in out.decode("utf-8").split("\0") if p)
        except (OSError, subprocess.CalledProcessError):
            pass
    found = []
    for folder, dirs, files in os.walk(root):
        dirs[:] = sorted(d for d in dirs if d != ".git" and not d.startswith("build"))
        for name in sorted(files):
            found.append(os.path.relpath(os.path.join(folder, name), root))
    return found


def read_text(path):
    """The file's lines, or None for a binary (NUL byte, not UTF-8) or unreadable file."""
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError:
        return None
    if b"\0" in data:
        return None
    try:
        return data.decode("utf-8").splitlines()
    except UnicodeDecodeError:
        return None


def defined_short_names(root):
    lines = read_text(os.path.join(root, REFERENCES))
    if lines is None:
        return None
    return {m.group(1) for line in lines for m in [DEFINED_NAME.match(line)] if m}


def resolves_to(relative_file, token, target):
    """Whether `token`, as written in `relative_file`, names `target` (repository-relative): from
    the repository root (docs/architecture.md) or relative to the file's folder (a Markdown link)."""
    token = token.split("#", 1)[0]
    if token.lstrip("/") == target:
        return True
    return os.path.normpath(os.path.join(os.path.dirname(relative_file), token)) == os.path.normpath(target)


def page_exists(root, relative_file, token):
    token = token.split("#", 1)[0]
    if token.startswith("."):
        path = os.path.normpath(os.path.join(root, os.path.dirname(relative_file), token))
        # a test's path from its data folder (.../../docs/x.md) still names the repository's page
        if not os.path.exists(path):
            path = os.path.join(root, token[token.index("docs/"):])
    else:
        path = os.path.join(root, token[token.index("docs/"):])
    return os.path.isfile(path)


def main():
    if len(sys.argv) != 2:
        print("usage: check_citations.py REPOSITORY_ROOT", file=sys.stderr)
        return 2
    root = os.path.abspath(sys.argv[1])
    failures = []
    counts = {"digest": 0, "architecture": 0, "page": 0, "name": 0, "path": 0}
    names = defined_short_names(root)
    if names is None:
        failures.append(f"{REFERENCES}: missing: it defines the short names the sources are cited by")
        names = set()
    scanned = 0
    hash_uses = 0
    for relative in tracked_files(root):
        if relative == SELF:
            continue
        lines = read_text(os.path.join(root, relative))
        if lines is None:
            continue
        scanned += 1
        handles_hashes = any(HASH_FILE.search(line) for line in lines)
        for number, line in enumerate(lines, 1):
            where = f"{relative}:{number}"
            if DIGEST.search(line):
                if handles_hashes and not DIGEST_CITATION.search(line):
                    hash_uses += 1
                else:
                    counts["digest"] += 1
                    failures.append(f"{where}: cites the private digest; cite the source's own section "
                                    f"(docs/references.md): {line.strip()[:100]}")
            for m in ARCHITECTURE.finditer(line):
                if not resolves_to(relative, m.group(0), "docs/architecture.md"):
                    counts["architecture"] += 1
                    failures.append(f"{where}: cites '{m.group(0)}', not docs/architecture.md")
            for m in DOCS_PAGE.finditer(line):
                if not page_exists(root, relative, m.group(1)):
                    counts["page"] += 1
                    failures.append(f"{where}: names {m.group(1)}, which the repository does not have")
            prose = relative.endswith(".md")
            comment = None if prose else COMMENT.search(line)
            if prose or comment:
                text = line if prose else line[comment.start():]
                for m in BACKTICKED_PATH.finditer(text):
                    path = re.sub(r"(:\d+)+$", "", m.group(1)).rstrip(".,:;)")
                    if NOT_A_PATH.search(path) or os.path.exists(os.path.join(root, path)):
                        continue
                    counts["path"] += 1
                    failures.append(f"{where}: names `{path}`, which the repository does not have")
            for m in SHORT_NAME.finditer(line):
                if m.group(1) not in names:
                    counts["name"] += 1
                    failures.append(f"{where}: cites '{m.group(0)}', a short name {REFERENCES} does not define")
    for line in failures:
        print(line)
    defined = ", ".join(f"paper {n}" for n in sorted(names)) or "none"
    print(f"{scanned} files checked ({defined} defined; {hash_uses} hash-digest uses allowed): "
          f"{counts['digest']} digest citations, {counts['architecture']} architecture.md citations outside docs/, "
          f"{counts['page']} missing docs pages, {counts['name']} undefined short names, "
          f"{counts['path']} backticked paths the repository does not have; "
          f"{len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
