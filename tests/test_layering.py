"""Layering: the package's modules import each other without loops (counting the imports inside
functions too), so each can be read, tested and moved on its own."""

import ast

from conftest import REPO

PACKAGE = REPO / "python" / "uvfeat"


def module_name(path) -> str:
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def import_graph() -> dict[str, set[str]]:
    modules = {module_name(p): p for p in PACKAGE.rglob("*.py")}
    known = set(modules) | {"uvfeat._core"}
    graph = {}
    for name, path in modules.items():
        package = name.split(".") if path.name == "__init__.py" else name.split(".")[:-1]
        imported = set()
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Import):
                imported |= {alias.name for alias in node.names}
            elif isinstance(node, ast.ImportFrom):
                base = package[:len(package) - node.level + 1] if node.level else []
                target = ".".join(base + ([node.module] if node.module else []))
                # `from . import x` imports the module x when there is one, else a name of the package.
                imported |= {f"{target}.{a.name}" if f"{target}.{a.name}" in known else target for a in node.names}
        graph[name] = {m for m in imported if m in known and m != name}
    return graph


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one module (Tarjan)."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def test_the_cycle_finder_finds_a_loop():
    assert cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]


def test_the_package_has_no_import_loops():
    graph = import_graph()
    assert {"uvfeat.atlas", "uvfeat.features", "uvfeat.cli", "uvfeat.cli.animate"} <= set(graph)
    assert "uvfeat.features" in graph["uvfeat.atlas"]
    assert cycles(graph) == []


CORE = REPO / "crates" / "uvfeat-core" / "src"


def core_graphs() -> tuple[dict[str, set[str]], dict[str, set[str]]]:
    """The Rust core's module graphs: between its stages (top-level modules, from `crate::` paths)
    and between the files of each stage's folder (from `super::` paths). Comments and the unit
    tests at the end of a file are left out."""
    import re

    stages, files = {}, {}
    for path in CORE.rglob("*.rs"):
        relative = path.relative_to(CORE)
        code = re.sub(r"#\[cfg\(test\)\]\s*mod tests.*", "", path.read_text(), flags=re.S)
        code = re.sub(r"//.*", "", code)
        if relative.name != "lib.rs":
            stage = relative.parts[0].removesuffix(".rs")
            stages.setdefault(stage, set()).update(m for m in re.findall(r"crate::([a-z_]+)", code)
                                                   if m != stage and ((CORE / m).exists() or (CORE / f"{m}.rs").exists()))
        if len(relative.parts) == 2 and relative.name != "mod.rs":
            folder = relative.parts[0]
            files[f"{folder}/{relative.stem}"] = {f"{folder}/{m}" for m in re.findall(r"super::([a-z_]+)", code)
                                                  if (CORE / folder / f"{m}.rs").exists()}
    return stages, files


def test_the_core_has_no_module_loops():
    stages, files = core_graphs()
    assert {"sampling", "features", "settings"} <= stages["evaluation"]
    assert "sampling/domain" in files["sampling/gather"]
    assert cycles(stages) == []
    assert cycles(files) == []


def test_the_package_stays_a_page_of_modules_a_newcomer_can_scan():
    # Pictures, written files, commands, animation and batch runs live in their own subpackages.
    top_level = sorted(p.name for p in PACKAGE.glob("*.py"))
    assert len(top_level) <= 20, top_level
    assert {"pictures", "files", "cli", "animation", "batch"} <= {p.name for p in PACKAGE.iterdir() if p.is_dir()}
