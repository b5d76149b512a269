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
