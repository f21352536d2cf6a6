"""Build hook: the wheel ships the modal solver's kernels compiled (numba's cache).

Everything else about the package is declared in ``pyproject.toml``. A non-editable build
(``pip install .``, ``pip wheel .``, ``python -m build``) runs, once ``build_py`` has laid
the package out in the build tree, :func:`impactmaps.solvers.warm_up.compile_into_package`
there, in a child process: numba writes the compiled kernels beside the built modules
(``impactmaps/*/__pycache__/*.nbi``, ``*.nbc``), and the wheel carries them. numba loads
them where the source files have the same content, numba and Python the same versions and
the CPU the same name and features — a wheel installed where it was built, as ``pip install
.`` does, starts warm; anywhere else numba compiles on first use, as without the cache. The
wheel is tagged for this Python and platform (it holds machine code).

``IMPACTMAPS_BUILD_NO_KERNELS=1`` skips the compile (a wheel without the cache); a compile
that fails leaves a wheel without the cache and a warning, never a failed build. Editable
installs (``pip install -e .``) compile nothing here: numba's cache is then beside the
sources, as in any checkout.
"""

from __future__ import annotations

import ast
import json
import os
import subprocess
import sys
import time
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py

try:
    from setuptools.command.bdist_wheel import bdist_wheel
except ImportError:  # setuptools < 70.1
    from wheel.bdist_wheel import bdist_wheel

#: Turns the compile off (any value but "" and "0").
SKIP_ENV = "IMPACTMAPS_BUILD_NO_KERNELS"
#: The compile, in a child process importing the built package (argv[1]: the build tree).
_COMPILE = ("import json, sys; sys.path.insert(0, sys.argv[1]); import impactmaps; "
            "from pathlib import Path; assert Path(impactmaps.__file__).parent == Path(sys.argv[1], 'impactmaps'); "
            "from impactmaps.solvers.warm_up import compile_into_package; print(json.dumps(compile_into_package()))")
#: numba's settings that would send the cache elsewhere or compile nothing.
_NUMBA_ENV = ("NUMBA_CACHE_DIR", "NUMBA_CACHE_LOCATOR_CLASSES", "NUMBA_DISABLE_JIT")


def cache_patterns(root: str) -> tuple:
    """``impactmaps.solvers.warm_up.CACHE_PATTERNS`` of the package under ``root``, read from its
    source: one list of numba's cache files, and this hook does not import the package."""
    source = Path(root) / "impactmaps" / "solvers" / "warm_up.py"
    for node in ast.parse(source.read_text(encoding="utf-8")).body:
        if isinstance(node, ast.Assign) and any(getattr(target, "id", None) == "CACHE_PATTERNS"
                                                for target in node.targets):
            return tuple(ast.literal_eval(node.value))
    raise RuntimeError(f"CACHE_PATTERNS not found in {source}")


def remove_cache_files(build_lib: str) -> None:
    """Remove numba's cache files (and what its saves leave) from the package in ``build_lib``:
    setuptools keeps the build tree between builds, and a wheel built without the compile, or
    whose compile failed, must not ship an earlier build's cache."""
    for pattern in cache_patterns(build_lib):
        for stale in Path(build_lib).glob(f"impactmaps/**/__pycache__/{pattern}"):
            stale.unlink()


def compile_kernels(build_lib: str) -> bool:
    """Compile the kernels into numba's cache inside ``build_lib``; True if it worked (else
    the build tree is left without cache files)."""
    build = Path(build_lib).resolve()
    env = {name: value for name, value in os.environ.items() if name not in _NUMBA_ENV}
    env.update(IMPACTMAPS_NO_BACKGROUND_WARMUP="1", PYTHONDONTWRITEBYTECODE="1")
    start = time.perf_counter()
    done = subprocess.run([sys.executable, "-c", _COMPILE, str(build)], cwd=build, env=env,
                          stdin=subprocess.DEVNULL, capture_output=True, text=True)
    if done.returncode == 0:
        report = json.loads(done.stdout.strip().splitlines()[-1])
        print(f"impactmaps: kernels compiled into the wheel in {time.perf_counter() - start:.1f} s "
              f"({report['files']} files, {report['bytes'] / 1e6:.1f} MB)", file=sys.stderr)
        return True
    remove_cache_files(build_lib)
    tail = "\n".join(done.stderr.strip().splitlines()[-5:])
    print(f"impactmaps: compiling the kernels failed; the wheel ships none (numba compiles them on first "
          f"use):\n{tail}", file=sys.stderr)
    return False


class BuildPyWithKernels(build_py):
    """``build_py``, then :func:`compile_kernels` into the build tree (not for editable installs)."""

    def run(self):
        super().run()
        if getattr(self, "editable_mode", False):
            return
        remove_cache_files(self.build_lib)
        if os.environ.get(SKIP_ENV, "") in ("", "0"):
            compile_kernels(self.build_lib)


class PlatformWheel(bdist_wheel):
    """A wheel tagged for this Python and platform: it holds numba's compiled code."""

    def finalize_options(self):
        super().finalize_options()
        self.root_is_pure = False


setup(cmdclass={"build_py": BuildPyWithKernels, "bdist_wheel": PlatformWheel})
