"""Makes sure the interpreter has the Debian packages the report needs.

Some machines put another python3 (e.g. pyenv's) first on PATH, without matplotlib. The command
line scripts and the tests then restart themselves once, with the same arguments, under the
system interpreter when it has the packages.
"""

from __future__ import annotations

import importlib.util
import os
import subprocess
import sys

REQUIRED_MODULES = ("matplotlib", "numpy", "scipy", "yaml")
SYSTEM_PYTHON = "/usr/bin/python3"
_RESTARTED = "PHDSLAM_REPORTS_RESTARTED"


def missing_modules() -> list[str]:
    """Required modules this interpreter cannot import."""
    return [m for m in REQUIRED_MODULES if importlib.util.find_spec(m) is None]


def _system_python_has_modules() -> bool:
    if not os.path.exists(SYSTEM_PYTHON) or os.path.realpath(SYSTEM_PYTHON) == os.path.realpath(
            sys.executable):
        return False
    probe = "import " + ", ".join(REQUIRED_MODULES)
    return subprocess.run([SYSTEM_PYTHON, "-c", probe], capture_output=True).returncode == 0


def ensure_dependencies() -> None:
    """Returns when the modules import; else re-runs under /usr/bin/python3, or exits 2."""
    missing = missing_modules()
    if not missing:
        return
    if not os.environ.get(_RESTARTED) and _system_python_has_modules():
        os.environ[_RESTARTED] = "1"
        arguments = list(getattr(sys, "orig_argv", [sys.executable, *sys.argv]))[1:]
        os.execv(SYSTEM_PYTHON, [SYSTEM_PYTHON, *arguments])
    sys.stderr.write(
        f"error: {sys.executable} cannot import {', '.join(missing)}; install the Debian packages "
        "python3-matplotlib python3-numpy python3-scipy python3-yaml (ci/install-deps.sh) and "
        f"run the script with {SYSTEM_PYTHON}\n")
    sys.exit(2)
