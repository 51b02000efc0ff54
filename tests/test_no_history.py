"""The code and the docs describe the product as it is: no line speaks of the sessions or turns of
work that built it or of issue numbers (that history lives in git and in the issue tracker)."""

import re
import subprocess

from conftest import REPO

#: What history sounds like: a session or an issue with its number, the code at a session's start
#: or end, one session spoken of before or after another, calls alternating "in" "turns". A pytest
#: "test session" is not.
HISTORY = re.compile(
    r"\bsessions? \d|\bsession-(start|end)\b|\b(this|last|previous|earlier|later|next|same|another) sessions?\b"
    r"|\bissues?[ -]#?\d|\bin turns\b|\bturns? of work\b",
    re.IGNORECASE,
)

#: Where the rule holds.
TREES = ["docs", "crates", "python", "tests", "benches", "README.md"]


def tracked_text_files() -> list[str]:
    listed = subprocess.run(["git", "ls-files", "--", *TREES], cwd=REPO, capture_output=True, text=True, check=True)
    return [name for name in listed.stdout.splitlines()
            if not name.endswith((".png", ".npz", ".npy", ".glb", ".ply", ".obj", ".so", ".jpg"))]


def test_no_line_speaks_of_sessions_turns_or_issue_numbers():
    found = []
    for name in tracked_text_files():
        try:
            text = (REPO / name).read_text(encoding="utf-8")
        except (UnicodeDecodeError, FileNotFoundError):
            continue
        found += [f"{name}:{number}: {line.strip()[:120]}" for number, line in enumerate(text.splitlines(), 1)
                  if HISTORY.search(line)]
    assert not found, f"{len(found)} lines speak of history:\n" + "\n".join(found[:40])


def test_the_rule_catches_history_and_leaves_the_test_session():
    # Put together here, so that this file holds no such line itself.
    for line in ("Session %d (issue %d): faster" % (22, 12), "on the session-%s code" % "start",
                 "as in an earlier %s" % "session", "see issue #%d" % 4, "the issue-%d table" % 16,
                 "the calls ran in %s" % "turns"):
        assert HISTORY.search(line), line
    for line in ('@pytest.fixture(scope="session")', "a folder of this test run", "the methods alternate"):
        assert not HISTORY.search(line), line
