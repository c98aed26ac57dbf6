"""Writes netmc/__init__.pyi: the hand-written stubs (python/netmc/__init__.pyi) followed by
sim(), sweep() and sweep_csv() with one keyword per flag the CLI registers, taken from the built
package itself (its flags and its keyword rules), so that an editor completes exactly the
keywords netmc.sim() takes.

Usage: write_stubs.py PACKAGE_PARENT_DIR TEMPLATE OUT"""
import sys

package_parent, template_path, out_path = sys.argv[1:4]
sys.path.insert(0, package_parent)
import netmc  # noqa: E402  (the package just built, not an installed one)


def keywords(command):
    out = []
    for name, flag in netmc._FLAGS[command].items():
        if name in netmc._NOT_KEYWORDS[command]:
            continue
        kind = "bool" if not flag["takes_value"] else "_Values"
        out.append(f"    {name.replace('-', '_')}: Optional[{kind}] = ...,")
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
