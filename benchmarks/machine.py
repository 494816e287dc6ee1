"""The machine a benchmark ran on: CPU model, cores, versions, date and load average."""
from __future__ import annotations

import datetime
import os
import platform
from importlib import metadata
from pathlib import Path

#: The libraries whose version a report names (read from the installed distributions).
LIBRARIES = ("numpy", "scipy", "numba", "panel", "bokeh")


def cpu_model() -> str:
    """The CPU's model name (``/proc/cpuinfo``), else what ``platform`` knows."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine() or "unknown"


def version(name: str) -> str:
    try:
        return metadata.version(name)
    except metadata.PackageNotFoundError:
        return "not installed"


def machine() -> dict:
    """CPU, cores, Python and library versions, and the date (local time, with its offset)."""
    return {"cpu": cpu_model(), "cores": os.cpu_count(), "python": platform.python_version(),
            **{name: version(name) for name in LIBRARIES},
            "date": datetime.datetime.now().astimezone().isoformat(timespec="seconds")}


def loadavg() -> list[float]:
    """The load average over 1, 5 and 15 minutes (runnable processes, not a percentage)."""
    return [round(v, 2) for v in os.getloadavg()]
