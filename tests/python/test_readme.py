"""The README and the docs as a reader meets them.

- The README's fmpy example runs as written and prints what the README says it prints.
- Every relative link of the README and of the docs resolves to a file of the repository.
- No tracked file narrates how the product was made: no numbered stages of its making, no
  issue numbers, no names of who did the work (history lives in the git log and CHANGELOG.md).
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

from conftest import REPO

README = REPO / "README.md"


def _block_after(text: str, heading: str, language: str, start: int = 0) -> tuple[str, int]:
    """The first fenced block of `language` after `heading` (from `start`), and its end."""
    at = text.index(heading, start)
    m = re.compile(r"^```" + language + r"\n(.*?)^```", re.S | re.M).search(text, at)
    assert m, f"no ```{language} block after {heading!r}"
    return m.group(1), m.end()


def test_the_readme_fmpy_example_prints_what_the_readme_says(fmu_path, tmp_path):
    text = README.read_text()
    code, end = _block_after(text, "## Use the FMU", "python")
    expected, _ = _block_after(text, "It prints", "text", end)
    # the example names the FMU relative to the checkout, as a reader runs it
    (tmp_path / "target" / "fmu").mkdir(parents=True)
    (tmp_path / "target" / "fmu" / fmu_path.name).symlink_to(fmu_path)
    (tmp_path / "example.py").write_text(code)
    env = dict(os.environ, MPLBACKEND="Agg")
    proc = subprocess.run([sys.executable, "example.py"], cwd=tmp_path, env=env, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout == expected, f"printed:\n{proc.stdout}\nthe README says:\n{expected}"
    assert (tmp_path / "torque.png").stat().st_size > 1000


def test_the_readme_install_line_names_what_the_example_imports_at_the_harness_pins():
    """The one-line install before the example: every package the example imports, at the
    version tests/python/requirements.txt pins (what the example is checked with above)."""
    text = README.read_text()
    at = text.index("## Use the FMU")
    m = re.compile(r"^ {4}python3 -m venv venv && venv/bin/pip install (.+)$", re.M).search(text, at)
    assert m, "no install line after '## Use the FMU'"
    assert m.start() < text.index("```python", at), "the install line must come before the example"
    named = dict(req.split("==") for req in m.group(1).split())
    pins = {}
    for line in (REPO / "tests" / "python" / "requirements.txt").read_text().splitlines():
        line = line.split("#")[0].strip()
        if "==" in line:
            name, version = line.split("==")
            pins[name.lower()] = version
    code, _ = _block_after(text, "## Use the FMU", "python")
    imported = {m.group(1) for m in re.finditer(r"^(?:from|import) (\w+)", code, re.M)} - set(sys.stdlib_module_names)
    assert imported == set(named), f"the example imports {sorted(imported)}, the line installs {sorted(named)}"
    for name, version in named.items():
        assert pins.get(name) == version, f"README installs {name}=={version}, requirements.txt pins {pins.get(name)}"


def _markdown_files() -> list[Path]:
    return [README, *sorted((REPO / "docs").glob("*.md"))]


_LINK = re.compile(r"\]\(([^)\s]+)\)|<img [^>]*src=\"([^\"]+)\"")


def test_every_relative_link_resolves():
    broken = []
    for md in _markdown_files():
        text = md.read_text()
        # links inside code blocks are examples, not links
        text = re.sub(r"^```.*?^```", "", text, flags=re.S | re.M)
        for m in _LINK.finditer(text):
            target = m.group(1) or m.group(2)
            if re.match(r"^[a-z][a-z0-9+.-]*:", target) or target.startswith("#"):
                continue
            path = (md.parent / target.split("#")[0]).resolve()
            if not path.exists():
                broken.append(f"{md.relative_to(REPO)}: {target}")
    assert not broken, "links that resolve to nothing:\n" + "\n".join(broken)


# What a text that narrates its own making says (the words are assembled so that this file
# does not match itself).
_NARRATION = [
    r"\bsess" + r"ions? \d",
    r"\biss" + r"ues? #?\d",
    r"\bproject iss" + r"ue\b",
    r"\bthe le" + r"ad\b",
    r"\bsub" + r"agents?\b",
    r"\bhel" + r"per-\d",
    r"\bwork peri" + r"ods?\b",
]


def test_no_tracked_file_narrates_its_making():
    files = subprocess.run(["git", "ls-files"], cwd=REPO, capture_output=True, text=True, check=True).stdout.split()
    pattern = re.compile("|".join(_NARRATION), re.I)
    hits = []
    for name in files:
        path = REPO / name
        if path.suffix in {".png", ".parquet", ".fmu", ".zip"} or not path.is_file():
            continue
        try:
            lines = path.read_text().splitlines()
        except UnicodeDecodeError:
            continue
        for number, line in enumerate(lines, 1):
            if pattern.search(line):
                hits.append(f"{name}:{number}: {line.strip()[:120]}")
    assert not hits, "history, issue numbers or who did the work, in tracked files:\n" + "\n".join(hits)
