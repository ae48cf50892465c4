"""The value folders of a sweep root ('phdslam run' of an experiment with a sweep): the names its
sweep.json lists, checked, so that every script reads them the same way."""

from __future__ import annotations

import json
from pathlib import Path

from .results_format_error import ResultsFormatError


def sweep_folder_names(root: Path) -> list[str] | None:
    """The names of sweep.json's 'folders' (None when `root` has no sweep.json). Raises
    ResultsFormatError naming the file when it cannot be read, is not JSON, or 'folders' is not a
    non-empty list of plain folder names."""
    sweep_file = root / "sweep.json"
    if not sweep_file.is_file():
        return None
    try:
        sweep = json.loads(sweep_file.read_text(encoding="utf-8-sig"))
    except (OSError, ValueError) as error:
        raise ResultsFormatError(f"{sweep_file}: {error}") from error
    folders = sweep.get("folders") if isinstance(sweep, dict) else None
    if (not isinstance(folders, list) or not folders
            or not all(isinstance(f, str) and f not in ("", ".", "..") and "/" not in f
                       for f in folders)):
        raise ResultsFormatError(f"{sweep_file}: 'folders' must be a non-empty list of folder "
                                 f"names, got {json.dumps(folders)}")
    return folders
