#!/usr/bin/python3
"""The include rules of docs/architecture.md ("Layers and include rules"), held on every build.

Reads every C and C++ source of the libraries and programs (not tests/, bench/, examples/,
python/: those use whatever they test or wrap), maps each file to its layer by its folder, and
checks each quoted #include of a repository path against the layers that layer may include.
Then draws the graph between folders (a file's folder to its include's folder) and reports every
cycle of it. Exits 1 naming each offending file, line and rule; prints a summary either way.

Usage: check_includes.py REPOSITORY [--plant FILE:INCLUDE]
(--plant adds one include to one file in memory: the test that the check fails on a violation.)
"""
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')
SOURCES = ('.cpp', '.hpp', '.h', '.c')
ROOTS = ('netsim', 'plant', 'control', 'server', 'client')

# Layer of a file: the longest matching folder prefix. Each layer may include the prefixes listed
# (its own folder always). The table of docs/architecture.md, in its order.
PURE = ('netsim/', 'plant/', 'control/')
LAYERS = {
    'netsim/': ('netsim/',),
    'plant/': ('plant/', 'netsim/random_stream.hpp'),
    'control/': ('control/',),
    # The plugin ABI header names the plant interface (docs: compiled into no library).
    'control/plugin/': ('control/', 'plant/axis_plant.hpp'),
    'server/drive/': PURE + ('server/drive/',),
    'server/drive/emulator/': PURE + ('server/drive/', 'server/log/'),
    'server/sim/': PURE + ('server/sim/', 'server/drive/'),
    'server/fmu/': PURE + ('server/fmu/',),
    'server/plugins/': PURE + ('server/plugins/',),
    'server/job/': PURE + ('server/job/', 'server/sim/', 'server/drive/', 'server/fmu/', 'server/plugins/', 'idl/'),
    'server/dds/': ('server/dds/',),
    'server/management/': ('server/management/', 'idl/'),
    'server/store/': ('server/store/', 'idl/'),
    'server/realtime/': ('server/realtime/',),
    'server/log/': ('server/log/',),
    'server/service/': PURE + ('server/service/', 'server/dds/', 'server/job/', 'server/sim/', 'server/drive/',
                               'server/fmu/', 'server/plugins/', 'server/management/', 'server/realtime/',
                               'server/log/', 'server/store/', 'idl/'),
    'server/axis/': PURE + ('server/axis/', 'server/dds/', 'server/job/', 'server/sim/', 'server/drive/',
                            'server/fmu/', 'server/plugins/', 'server/realtime/', 'server/log/', 'idl/'),
    'server/console/': PURE + ('server/console/', 'server/service/', 'server/dds/', 'server/job/', 'server/sim/',
                               'server/drive/', 'server/fmu/', 'server/plugins/', 'server/management/',
                               'server/realtime/', 'server/log/', 'server/store/', 'idl/'),
    'client/': PURE + ('client/', 'server/job/', 'server/sim/', 'server/drive/', 'server/fmu/', 'server/plugins/',
                       'server/management/', 'server/store/', 'server/log/', 'idl/'),
}
# Known breaches, each to be removed by moving code, never added to: a new include that breaks a
# rule, or a new edge that closes a cycle between folders, fails the check.
KNOWN_INCLUDES = set()  # none left: the presets moved below both server and client (server/job/presets/)
KNOWN_EDGES = set()  # none left: control/'s folders form no cycle since its groups moved to group/
# The programs' main.cpp wire the process: they may include what their program links.
MAINS = {
    'server/service/main.cpp': LAYERS['server/console/'] + ('server/console/',),
    'server/axis/main.cpp': LAYERS['server/axis/'],
}


def layer_of(path):
    best = None
    for prefix in LAYERS:
        if path.startswith(prefix) and (best is None or len(prefix) > len(best)):
            best = prefix
    return best


def allowed(path, target):
    rules = MAINS.get(path) or LAYERS[layer_of(path)]
    return any(target.startswith(rule) if rule.endswith('/') else target == rule for rule in rules)


def sources(root):
    for top in ROOTS:
        for folder, _, files in os.walk(os.path.join(root, top)):
            for name in sorted(files):
                if name.endswith(SOURCES):
                    full = os.path.join(folder, name)
                    yield os.path.relpath(full, root).replace(os.sep, '/')


def includes(root, path, planted):
    with open(os.path.join(root, path), encoding='utf-8', errors='replace') as source:
        lines = source.read().splitlines()
    for number, line in enumerate(lines, 1):
        match = INCLUDE.match(line)
        if match:
            yield number, match.group(1)
    for file, target in planted:
        if file == path:
            yield len(lines) + 1, target


def folder_of(path):
    return os.path.dirname(path)


def cycles(edges):
    """Every elementary cycle's folders, one per strongly connected component of two or more
    folders (Tarjan), listed with the file includes that close it."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []
    counter = [0]

    def visit(node):
        index[node] = low[node] = counter[0]
        counter[0] += 1
        stack.append(node)
        on_stack.add(node)
        for nxt in sorted(edges.get(node, ())):
            if nxt not in index:
                visit(nxt)
                low[node] = min(low[node], low[nxt])
            elif nxt in on_stack:
                low[node] = min(low[node], index[nxt])
        if low[node] == index[node]:
            component = []
            while True:
                top = stack.pop()
                on_stack.discard(top)
                component.append(top)
                if top == node:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    sys.setrecursionlimit(10000)
    for node in sorted(edges):
        if node not in index:
            visit(node)
    return found


def main():
    args = sys.argv[1:]
    if not args:
        sys.exit(__doc__)
    root = args[0]
    planted = []
    if len(args) == 3 and args[1] == '--plant':
        file, _, target = args[2].partition(':')
        planted.append((file, target))
    problems = []
    edges, witnesses = {}, {}
    files = 0
    repository = set(sources(root))
    for file, _ in planted:
        if file not in repository:
            sys.exit(f'check_includes: --plant: no source {file} in the repository')
    for path in sorted(repository):
        if layer_of(path) is None:
            continue
        files += 1
        for number, target in includes(root, path, planted):
            # Generated headers (dds_types.h, idl/*.pb.h) and system headers in quotes are not
            # repository paths of these layers; idl/ is checked by name.
            if not (target in repository or target.startswith('idl/')):
                continue
            if not allowed(path, target) and (path, target) not in KNOWN_INCLUDES:
                problems.append(f'{path}:{number}: includes "{target}", which layer {layer_of(path)} may not '
                                f'(docs/architecture.md, Layers and include rules)')
            a, b = folder_of(path), folder_of(target)
            # A program's main.cpp is the program, not its folder's library.
            if a != b and os.path.basename(path) != 'main.cpp' and (a, b) not in KNOWN_EDGES:
                edges.setdefault(a, set()).add(b)
                witnesses.setdefault((a, b), f'{path}:{number} -> {target}')
    for component in cycles(edges):
        inside = set(component)
        closing = [witnesses[(a, b)] for a in component for b in sorted(edges.get(a, ())) if b in inside]
        problems.append('folders include each other (a cycle): ' + ', '.join(component) + ' (' + '; '.join(closing) + ')')
    for problem in problems:
        print(problem)
    print(f'check_includes: {files} files, {sum(len(v) for v in edges.values())} edges between folders, '
          f'{len(problems)} problems')
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
