"""The README's Python example runs and writes its PNG (into $HAPSTAB_EXAMPLE_DIR when set,
so that CI keeps it under target/, else into a temporary directory)."""

import os
import re
import subprocess
import sys

from conftest import ROOT


def readme_example() -> str:
    text = (ROOT / "README.md").read_text()
    section = text.split("\n## Python\n", 1)[1].split("\n## ", 1)[0]
    blocks = re.findall(r"```python\n(.*?)```", section, re.S)
    assert len(blocks) == 1, "the Python section has one example"
    return blocks[0]


def test_readme_example_writes_a_png(tmp_path):
    out = os.environ.get("HAPSTAB_EXAMPLE_DIR", str(tmp_path))
    os.makedirs(out, exist_ok=True)
    script = tmp_path / "readme_example.py"
    script.write_text(readme_example())
    subprocess.run([sys.executable, str(script)], cwd=out, check=True)
    png = os.path.join(out, "region.png")
    with open(png, "rb") as f:
        head = f.read(8)
    assert head == b"\x89PNG\r\n\x1a\n"
    assert os.path.getsize(png) > 20_000
