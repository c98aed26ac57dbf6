"""Writes netmc/__init__.pyi: the hand-written stubs (python/netmc/__init__.pyi) followed by
sim(), sweep() and sweep_csv() with one keyword per flag the CLI registers, taken from the built
module itself, so that an editor completes exactly the flags `netmc sim --help` lists."""
import importlib.util
import sys

core_path, template_path, out_path = sys.argv[1:4]
spec = importlib.util.spec_from_file_location("_core", core_path)
core = importlib.util.module_from_spec(spec)
spec.loader.exec_module(core)

# As the package's own keyword rules (python/netmc/__init__.py, _NOT_KEYWORDS).
not_keywords = {
    "sim": {"json", "csv", "plot", "plot-format", "print-spec", "list-presets", "list-controllers",
            "list-compensators", "plant-parameters", "fail-on-unstable"},
    "sweep": {"csv", "json", "plot", "server", "shard"},
}


def keywords(command):
    out = []
    for flag in core.command_flags(command):
        if flag["name"] in not_keywords[command]:
            continue
        kind = "bool" if not flag["takes_value"] else "_Values"
        out.append(f"    {flag['name'].replace('-', '_')}: Optional[{kind}] = ...,")
    return "\n".join(out)


with open(template_path) as template:
    text = template.read()
text += f"""
def sim(
    *,
    traces: str = ...,
{keywords("sim")}
    spec: Optional[Union[str, PathLike[str], Dict[str, Any]]] = ...,
) -> Study: ...

def sweep_csv(
    *,
    client: Any = ...,
    tasks: Optional[int] = ...,
{keywords("sweep")}
) -> str: ...

def sweep(
    *,
    client: Any = ...,
    tasks: Optional[int] = ...,
{keywords("sweep")}
) -> pandas.DataFrame: ...
"""
# A keyword listed twice (spec is a flag too) keeps its first, wider form.
seen, lines = set(), []
for line in text.splitlines():
    stripped = line.strip()
    if stripped.startswith("spec:") and ("spec" in seen):
        continue
    if stripped.startswith("spec:"):
        seen.add("spec")
    if stripped.startswith("def "):
        seen.clear()
    lines.append(line)
with open(out_path, "w") as out:
    out.write("\n".join(lines) + "\n")
