"""The wheel ships the kernels compiled: numba's cache built beside the modules (issue 30, item 2).

``setup.py`` runs :func:`impactmaps.solvers.warm_up.compile_into_package` in the build tree;
the wheel carries numba's cache files. An installed file keeps its content, not its
modification time: numba (≥ 0.68) keys a cache index on the source file's content, so an
installed copy loads the shipped entries, and falls back to compiling when the source
differs or no cache was shipped. Checked on a small module built, then "installed" by a
copy with new modification times (two fresh interpreters, ~1.5 s); the bits of a run from
the package's own shipped cache against a fresh compile in the slow test. A read-only
installation: numba keeps its cache in its user-wide directory, where the shipped files are
copied (:func:`impactmaps._compile.compile_helper.seed_user_cache`).
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

from impactmaps._compile import compile_helper
from impactmaps.solvers import warm_up

_MODULE = "import numba\n\n\n@numba.njit(cache=True)\ndef kernel(x):\n    return 2.0 * x + 1.0\n"
#: Build: compile ``kernel`` into ``__pycache__`` beside the module (argv[1]: its directory).
_BUILD = "import sys; sys.path.insert(0, sys.argv[1]); import shipped_demo; print(shipped_demo.kernel(1.5))"
#: Load each installed copy (argv: their directories): value, cache hits, cache misses.
_LOAD = """
import importlib, json, sys
out = {}
for where in sys.argv[1:]:  # each copy imported under the built module's name, as an installed package is
    sys.path.insert(0, where)
    sys.modules.pop("shipped_demo", None)
    module = importlib.import_module("shipped_demo")
    sys.path.remove(where)
    value, stats = module.kernel(1.5), module.kernel.stats
    out[where] = [value, sum(stats.cache_hits.values()), sum(stats.cache_misses.values())]
print(json.dumps(out))
"""


def _environment() -> dict:
    """numba's cache beside the modules (no ``NUMBA_CACHE_DIR``), no bytecode files."""
    env = {name: value for name, value in os.environ.items() if name != "NUMBA_CACHE_DIR"}
    return dict(env, PYTHONDONTWRITEBYTECODE="1")


def _run(code: str, *args: str) -> str:
    # not from the checkout: ``python -c`` puts its working directory first on sys.path, so run
    # from the test session's working directory it imported the checkout's package (whose numba cache
    # the other tests fill as they go), not the installed one (CI failed when one variant was there yet)
    done = subprocess.run([sys.executable, "-c", code, *args], capture_output=True, text=True, env=_environment(),
                          cwd=tempfile.gettempdir())
    assert done.returncode == 0, done.stderr
    return done.stdout


def _install(build: Path, target: Path, source: str | None = None, cache: bool = True) -> str:
    """Copy ``build`` to ``target`` as pip does (new modification times; without
    ``__pycache__`` unless ``cache``), with the module's text replaced by ``source``."""
    target.mkdir()
    (target / "shipped_demo.py").write_text(source or (build / "shipped_demo.py").read_text())
    os.utime(target / "shipped_demo.py", (1e9, 1e9))  # not the build's time
    if cache:
        shutil.copytree(build / "__pycache__", target / "__pycache__", copy_function=shutil.copy)
    return str(target)


def test_an_installed_copy_loads_the_shipped_cache_and_compiles_without_it(tmp_path):
    build = tmp_path / "build"
    build.mkdir()
    (build / "shipped_demo.py").write_text(_MODULE)
    assert _run(_BUILD, str(build)).strip() == "4.0"
    assert len(list((build / "__pycache__").glob("shipped_demo.kernel-*.nbi"))) == 1
    same = _install(build, tmp_path / "same")
    edited = _install(build, tmp_path / "edited", _MODULE + "# another source: another content\n")
    bare = _install(build, tmp_path / "bare", cache=False)
    loaded = json.loads(_run(_LOAD, same, edited, bare))
    assert loaded[same] == [4.0, 1, 0]  # the shipped entry, nothing compiled
    assert loaded[edited] == [4.0, 0, 1]  # stale for this content: compiled
    assert loaded[bare] == [4.0, 0, 1]  # nothing shipped: compiled


def test_the_package_compile_needs_the_cache_beside_the_modules(monkeypatch):
    monkeypatch.setenv("NUMBA_CACHE_DIR", "/somewhere/else")
    with pytest.raises(ValueError, match="NUMBA_CACHE_DIR = '/somewhere/else'"):
        warm_up.compile_into_package()


def test_an_installed_wheel_ships_the_integrator_compiled():
    """Where this package was installed from a wheel built with its cache (``pip install .``,
    as CI does), both integrator variants are in it; skipped for a checkout or a wheel
    built without it (``IMPACTMAPS_BUILD_NO_KERNELS=1``)."""
    from importlib import metadata

    package = Path(warm_up.__file__).resolve().parents[1]
    # the metadata beside the imported package (not a checkout's egg-info found first on sys.path)
    found = list(metadata.distributions(name="impactmaps", path=[str(package.parent)]))
    shipped = [str(path) for dist in found for path in dist.files or () if str(path).endswith(".nbi")]
    if not shipped:
        pytest.skip("not a wheel install with the shipped kernels")
    code = ("import impactmaps.solvers.integrator.exact_step; "
            "from impactmaps._compile.compile_helper import variant_cached; "
            "print(variant_cached(None), variant_cached(True))")
    assert _run(code).split() == ["True", "True"]


def test_shipped_cache_files_are_copied_index_by_index(tmp_path):
    """A read-only installation: the shipped files go to numba's user-wide cache, a
    function's data files and index, unless numba has an index of its own there."""
    shipped = tmp_path / "package" / "solvers" / "__pycache__"
    shipped.mkdir(parents=True)
    for name in ("a.f-3.py311.nbi", "a.f-3.py311.1.nbc", "a.f-3.py311.2.nbc", "b.g-5.py311.nbi", "b.g-5.py311.1.nbc"):
        (shipped / name).write_text(f"shipped {name}")
    user = tmp_path / "user"
    (user / "solvers").mkdir(parents=True)
    (user / "solvers" / "b.g-5.py311.nbi").write_text("numba's own")
    copy = compile_helper.copy_shipped_cache
    assert copy(tmp_path / "package", lambda folder: user / folder.name) == 3
    assert sorted(path.name for path in (user / "solvers").iterdir()) == [
        "a.f-3.py311.1.nbc", "a.f-3.py311.2.nbc", "a.f-3.py311.nbi", "b.g-5.py311.nbi"]
    assert (user / "solvers" / "a.f-3.py311.2.nbc").read_text() == "shipped a.f-3.py311.2.nbc"
    assert (user / "solvers" / "b.g-5.py311.nbi").read_text() == "numba's own"
    assert copy(tmp_path / "package", lambda folder: user / folder.name) == 0


def test_nothing_is_copied_where_numba_reads_the_modules_directories():
    from numba.core.caching import UserWideCacheLocator

    from impactmaps.solvers.integrator.exact_step import integrate_impact

    if type(integrate_impact.dispatcher._cache._impl.locator) is UserWideCacheLocator:
        pytest.skip("a read-only installation: numba's user-wide cache is seeded")
    assert compile_helper.seed_user_cache() == 0


@pytest.mark.slow
def test_a_run_from_the_shipped_cache_gives_the_bits_of_a_fresh_compile(tmp_path):
    """The package copied to a build tree, compiled there as the wheel's build does, copied
    again as pip installs it; the example's history from that cache (nothing compiled) and
    from a fresh compile, bit for bit."""
    package = Path(warm_up.__file__).resolve().parents[1]
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc", "*.npz", "*.nc")  # no map data: not read
    shutil.copytree(package, tmp_path / "build" / "impactmaps", ignore=ignore)
    compiled = json.loads(_run("import json, sys; sys.path.insert(0, sys.argv[1]); "
                               "from impactmaps.solvers.warm_up import compile_into_package as c; "
                               "print(json.dumps(c()))", str(tmp_path / "build")).splitlines()[-1])
    assert compiled["files"] > 20 and compiled["bytes"] > 1e6
    shutil.copytree(tmp_path / "build", tmp_path / "site", copy_function=shutil.copy)
    case = Path(__file__).resolve().parents[2] / "examples" / "steel_plate_hertz.toml"
    if not case.exists():
        pytest.skip("the examples are not beside the tests")
    run = ("import sys, json; sys.path.insert(0, sys.argv[1]); from impactmaps.cases import load_case, run_case; "
           "from impactmaps.solvers.integrator.exact_step import integrate_impact; "
           "result, _ = run_case(load_case(sys.argv[2])); d = integrate_impact.dispatcher; "
           "print(json.dumps([result.history.to_numpy().tobytes().hex(), repr(result.peak_force), "
           "sum(d.stats.cache_hits.values()), sum(d.stats.cache_misses.values())]))")
    shipped = json.loads(_run(run, str(tmp_path / "site"), str(case)).splitlines()[-1])
    env_cache = tmp_path / "fresh"
    fresh = subprocess.run([sys.executable, "-c", run, str(tmp_path / "site"), str(case)], capture_output=True,
                           text=True, env=dict(_environment(), NUMBA_CACHE_DIR=str(env_cache)))
    assert fresh.returncode == 0, fresh.stderr
    fresh = json.loads(fresh.stdout.splitlines()[-1])
    assert shipped[2:] == [1, 0] and fresh[2:] == [0, 1]
    assert shipped[:2] == fresh[:2]


def test_build_hook_removes_the_cache_files_warm_up_names(tmp_path):
    """``setup.py``'s clean-up of a build tree reads :data:`warm_up.CACHE_PATTERNS` from the
    package's source (one list of numba's cache files) and removes exactly those."""
    import ast

    root = Path(__file__).resolve().parents[2]
    tree = ast.parse((root / "setup.py").read_text(encoding="utf-8"))
    # the two functions alone: setup.py's imports need the build's own packages (wheel, a recent setuptools)
    functions = [node for node in tree.body if isinstance(node, ast.FunctionDef)
                 and node.name in ("cache_patterns", "remove_cache_files")]
    assert len(functions) == 2
    hook: dict = {"ast": ast, "Path": Path}
    exec(compile(ast.Module(body=functions, type_ignores=[]), "setup.py", "exec"), hook)
    assert hook["cache_patterns"](str(root)) == warm_up.CACHE_PATTERNS
    package = tmp_path / "impactmaps"
    shutil.copytree(root / "impactmaps" / "solvers", package / "solvers",
                    ignore=shutil.ignore_patterns("__pycache__"))
    cache = package / "solvers" / "__pycache__"
    cache.mkdir()
    names = ("k.py311.nbi", "k.py311.1.nbc", "k.py311.nbi.lock", "k.nbc.tmp.7", "k.cpython-311.pyc")
    for name in names:
        (cache / name).write_text("x")
    hook["remove_cache_files"](str(tmp_path))
    assert sorted(path.name for path in cache.iterdir()) == ["k.cpython-311.pyc"]
