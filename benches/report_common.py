"""What the benchmark reports share: the machine line, and rewriting the generated section of a
Markdown file between its two marker comments."""

from __future__ import annotations

import os
import platform
import re
from pathlib import Path


def machine() -> str:
    """Processor, cores (and rayon threads), Python and uvfeat versions."""
    import uvfeat

    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    threads = os.environ.get("RAYON_NUM_THREADS", str(cores))
    return (f"{platform.processor() or platform.machine()}, {cores} cores ({threads} threads), "
            f"Python {platform.python_version()}, uvfeat {uvfeat.__version__}")


def write_section(path: Path, start: str, end: str, body: str, template: str) -> None:
    """Replaces what lies between ``start`` and ``end`` in ``path`` by ``body``; a missing file
    starts from ``template``, and a file without the markers gets them appended."""
    text = path.read_text() if path.exists() else template
    pattern = re.compile(re.escape(start) + ".*?" + re.escape(end), re.S)
    if not pattern.search(text):
        text += f"\n{start}\n{end}\n"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(pattern.sub(lambda _: f"{start}\n{body}{end}", text))
