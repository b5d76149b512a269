"""The README's Python example runs as printed (one game on canyon, played to its end)."""

import pathlib
import re

README = pathlib.Path(__file__).resolve().parents[2] / "README.md"


def test_the_readmes_example_plays_a_game_to_its_end():
    blocks = re.findall(r"```python\n(.*?)```", README.read_text(), re.S)
    assert blocks, "README.md holds no Python example"
    scope = {}
    exec(compile(blocks[0], "README.md", "exec"), scope)  # noqa: S102 - the documented example itself
    env = scope["env"]
    assert env.agents == [] and env.possible_agents == ["pursuer_0"]
    assert set(scope["rewards"]) == {"pursuer_0"}


def test_the_readme_lists_every_doc_and_every_shipped_map():
    root = README.parent
    text = README.read_text()
    missing = [f"docs/{p.name}" for p in sorted((root / "docs").glob("*.md")) if p.name not in text]
    missing += [f"maps/{p.name}" for p in sorted((root / "maps").glob("*.yaml")) if f"`{p.stem}`" not in text]
    assert not missing, f"README.md does not list {', '.join(missing)}"
    assert "arXiv" in text and "../shared" not in text
