#!/usr/bin/python3
"""Every relative link of README.md and docs/ resolves: the file exists in the repository and,
for a link to a heading (page.md#heading), the page has that heading (GitHub's anchor rule).
And every page of docs/ is linked from README.md (the front door), or from a README.md of its own
folder that the front door links (docs/reproductions/).

Usage: check_links.py REPOSITORY_ROOT
Exit 0 when all resolve; 1 with each broken link named (file:line: target).
"""
import os
import re
import sys

LINK = re.compile(r"\]\(([^)\s]+)\)")
FENCE = re.compile(r"^\s*```")


def anchors(path):
    """GitHub's anchors of a Markdown file's headings: lower case, punctuation dropped, spaces to -."""
    found = set()
    fenced = False
    with open(path, encoding="utf-8") as f:
        for line in f:
            if FENCE.match(line):
                fenced = not fenced
                continue
            if fenced or not line.startswith("#"):
                continue
            title = line.lstrip("#").strip().lower()
            slug = re.sub(r"[^\w\- ]", "", title).replace(" ", "-")
            found.add(slug)
    return found


def pages(root):
    yield os.path.join(root, "README.md")
    for folder, _, files in os.walk(os.path.join(root, "docs")):
        for name in sorted(files):
            if name.endswith(".md"):
                yield os.path.join(folder, name)


def relative_links(page):
    """(line number, target) of each link of a Markdown page to this repository, outside code fences."""
    fenced = False
    with open(page, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            if FENCE.match(line):
                fenced = not fenced
                continue
            if fenced:
                continue
            for target in LINK.findall(line):
                if not re.match(r"^[a-z]+:", target):  # http:, https:, mailto: are not this repository's
                    yield number, target


def resolve(page, target):
    """The file a link names (the page itself for a bare #fragment)."""
    path = target.partition("#")[0]
    return os.path.normpath(os.path.join(os.path.dirname(page), path)) if path else page


def linked_from(page):
    """The files a Markdown page links to."""
    return {resolve(page, target) for _, target in relative_links(page)}


def unlinked_pages(root):
    front = linked_from(os.path.join(root, "README.md"))
    reachable = set(front)
    for target in front:  # a folder's own index page counts for the pages it links
        if os.path.basename(target) == "README.md" and target.startswith(os.path.join(root, "docs")):
            reachable |= linked_from(target)
    return [os.path.relpath(page, root) for page in pages(root)
            if not page.endswith(os.sep + "README.md") and page not in reachable]


def main():
    root = os.path.abspath(sys.argv[1])
    broken = []
    checked = 0
    for page in pages(root):
        for number, target in relative_links(page):
            fragment = target.partition("#")[2]
            resolved = resolve(page, target)
            checked += 1
            where = f"{os.path.relpath(page, root)}:{number}: {target}"
            if not resolved.startswith(root + os.sep) and resolved != root:
                broken.append(f"{where} (outside the repository)")
            elif not os.path.exists(resolved):
                broken.append(f"{where} (no such file)")
            elif fragment and resolved.endswith(".md") and fragment not in anchors(resolved):
                broken.append(f"{where} (no such heading)")
    unlinked = unlinked_pages(root)
    for page in unlinked:
        broken.append(f"README.md: does not link {page}")
    for line in broken:
        print(line)
    print(f"{checked} relative links checked, {len(broken) - len(unlinked)} broken; "
          f"{len(unlinked)} of the docs' pages not linked from the README")
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())
