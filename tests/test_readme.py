"""The README is the front door: its quick start runs as written, its command lines parse, and it
stays short; the documents it links exist."""

import re
import shlex

from conftest import REPO
from uvfeat.cli import build_parser

README = (REPO / "README.md").read_text()


def fenced_blocks(language: str) -> list[str]:
    return re.findall(rf"```{language}\n(.*?)```", README, re.S)


def test_the_python_quick_start_runs_as_written(capsys):
    (quick_start,) = [block for block in fenced_blocks("python") if "uvfeat.examples.spot()" in block]
    exec(compile(quick_start, "README.md quick start", "exec"), {})
    printed = capsys.readouterr().out
    assert "<uvfeat.Mesh 'spot.obj'" in printed
    percent_ae = float(re.search(r"%AE ([0-9.]+)", printed).group(1))
    assert 0.5 < percent_ae < 5.0, "the README promises about 2.4 against the reference"


def test_every_quick_start_command_line_parses():
    commands = [line.split("#")[0].strip() for block in fenced_blocks("sh") for line in block.splitlines()]
    uvfeat_commands = [shlex.split(c)[1:] for c in commands if c.startswith("uvfeat ") and "--help" not in c]
    assert len(uvfeat_commands) >= 5
    for argv in uvfeat_commands:
        build_parser().parse_args(argv)


def test_the_readme_is_a_front_door_and_its_links_exist():
    assert len(README.splitlines()) < 150
    for link in re.findall(r"\]\(([^)#]+)\)", README):
        assert (REPO / link).exists(), link
