"""docs/python.md: every ```python block runs, in order, in one namespace,
from the repository's root (the examples assert what they show)."""
import os
import re

import pytest

import shlab


def test_python_blocks_of_docs_run(root, monkeypatch):
    text = open(os.path.join(root, "docs", "python.md")).read()
    blocks = re.findall(r"^```python\n(.*?)^```", text, flags=re.S | re.M)
    assert len(blocks) >= 2
    if not shlab.verify_available() and any("verify" in b for b in blocks):
        pytest.skip("the loaded libshlab has no verify.h functions yet")
    monkeypatch.chdir(root)
    ns = {}
    for b in blocks:
        exec(compile(b, "docs/python.md", "exec"), ns)
    assert "result" in ns and ns["result"].failed > 0
