"""The Python snippets of docs/python.md run, in order, in one namespace (from a scratch folder
that sees the source tree's scenes/ and data/), so the documented calls exist and work."""
import os
import re


def test_docs_python_md_snippets_run(source_dir, tmp_path, monkeypatch):
    text = open(os.path.join(source_dir, "docs", "python.md"), encoding="utf-8").read()
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    assert len(blocks) >= 4
    for name in ("scenes", "data"):
        os.symlink(os.path.join(os.path.abspath(source_dir), name), tmp_path / name)
    monkeypatch.chdir(tmp_path)
    namespace = {}
    for i, block in enumerate(blocks):
        exec(compile(block, f"docs/python.md block {i + 1}", "exec"), namespace)
    print(f"{len(blocks)} snippets of docs/python.md ran")
    assert (tmp_path / "mine.json").exists()
    assert namespace["img"].rgba.shape[2] == 4
