"""The README's Python quick start runs as written."""

from __future__ import annotations

import re

from tests.conftest import REPO


def test_readme_python_blocks_run(tmp_path, monkeypatch, capsys):
    text = (REPO / "README.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    assert blocks, "README has no python block"
    monkeypatch.chdir(tmp_path)
    for code in blocks:
        exec(compile(code, "README.md", "exec"), {})
    out = capsys.readouterr().out
    assert "0/r0 ogee (65, 3)" in out
    from auszug.formats import load

    doc = load(tmp_path / "tn-2.network.json", kind="network")
    assert doc["version"] == 2 and doc["tolerance"] > 0 and len(doc["curves"][0]["points"]) > 65
