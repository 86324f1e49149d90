"""The picture settings declared once (src/session/setting_table.h; issue 54, point 1). Every
setting of the table round-trips command line -> session file -> Python -> session file with the
same value, and a value outside its limits (or not one of its choices) is refused with the same
words by all three, after each front end's own name for the setting. Before the table the three
worded them apart ("--density-scale: '-1' is outside [0, inf)", "render.densityScale: -1 must be
>= 0", "density_scale -1 must be finite and >= 0"), which this test rejects."""
import json
import math
import re
import subprocess

import pytest

from conftest import SAMPLE, amrvk_binary

SMALL = ["--size", "16x12", "--scale", "linear", "--tf", "ramp"]


def example(row):
    """A value of the setting other than its default."""
    if row["kind"] == "choice":
        return next(c for c in row["choices"].split("|") if c != row["default"])
    if row["kind"] == "flag":
        return not row["default"]
    lo, hi = row["lo"], row["hi"]
    v = lo + 2.5 if math.isinf(hi) else lo + (hi - lo) * 0.25
    return int(round(v)) if row["kind"] == "integer" else v


def outside(row):
    """A value the setting refuses: 'nonsense' for a choice, else just outside its limits."""
    if row["kind"] == "choice":
        return "nonsense"
    if row["lo_open"]:
        return int(row["lo"]) if row["kind"] == "integer" else row["lo"]
    return int(row["lo"]) - 1 if row["kind"] == "integer" else row["lo"] - 1


def text(v):
    return repr(v) if isinstance(v, float) else str(v)


def cli(*args):
    binary = amrvk_binary()
    if not binary.exists():
        pytest.skip(f"{binary} is not built")
    return subprocess.run([str(binary), *map(str, args)], capture_output=True, text=True)


def words_after(line, name):
    """The refusal's words after `name: ` in one line of stderr (the CLI adds a hint in brackets)."""
    at = line.index(name + ": ") + len(name) + 2
    return re.sub(r" \(see amrvk \w+ --help\)$", "", line[at:].strip())


def test_the_table_is_what_every_front_end_takes(amrvk):
    rows = amrvk._amrvk._settings()
    assert len(rows) >= 10
    for row in rows:
        assert row["keyword"] == row["option"][2:].replace("-", "_"), row
        if row["kind"] in ("number", "integer"):
            d = row["default"]
            assert (d > row["lo"] if row["lo_open"] else d >= row["lo"]) and (d < row["hi"] if row["hi_open"] else d <= row["hi"]), row
        if row["kind"] == "choice":
            assert row["default"] in row["choices"].split("|"), row


def test_every_setting_round_trips_cli_session_python_session(amrvk, tmp_path):
    rows = amrvk._amrvk._settings()
    args = []
    for row in rows:
        v = example(row)
        args += [row["option"]] if row["kind"] == "flag" else [row["option"], text(v)]
    first = tmp_path / "cli.json"
    p = cli("view", SAMPLE, *SMALL, *args, "--headless", "--frames", "1", "--save-session", first)
    assert p.returncode == 0, p.stderr
    saved = json.loads(first.read_text())
    for row in rows:
        assert saved[row["section"]][row["key"]] == example(row), (row["option"], saved[row["section"]])

    r = amrvk.Renderer.from_session(str(first), quiet=True)
    for row in rows:
        got = getattr(r, row["keyword"])
        assert got == example(row), (row["keyword"], got)
    again = tmp_path / "python.json"
    r.save_session(str(again))
    for row in rows:
        assert json.loads(again.read_text())[row["section"]][row["key"]] == example(row), row["option"]

    # Each property set back to its default, the file follows.
    for row in rows:
        setattr(r, row["keyword"], row["default"])
        assert getattr(r, row["keyword"]) == row["default"], row["keyword"]
    r.save_session(str(again))
    back = json.loads(again.read_text())
    for row in rows:
        assert back[row["section"]][row["key"]] == row["default"], row["option"]
    r.close()


def test_a_refused_value_has_the_same_words_everywhere(amrvk, tmp_path):
    rows = [row for row in amrvk._amrvk._settings() if row["kind"] != "flag"]
    base = tmp_path / "base.json"
    assert cli("view", SAMPLE, *SMALL, "--headless", "--frames", "1", "--save-session", base).returncode == 0
    volume = amrvk.Volume(str(SAMPLE), scale="linear")
    r = amrvk.Renderer(volume, width=16, height=12, quiet=True)
    for row in rows:
        bad = outside(row)
        p = cli("render", SAMPLE, *SMALL, row["option"], text(bad), "-o", tmp_path / "x.png")
        assert p.returncode != 0 and not (tmp_path / "x.png").exists(), row["option"]
        from_cli = words_after(p.stderr.strip().splitlines()[-1], row["option"])

        s = json.loads(base.read_text())
        s[row["section"]][row["key"]] = bad
        bad_file = tmp_path / f"{row['key']}.json"
        bad_file.write_text(json.dumps(s))
        p = cli("render", "--session", bad_file, "-o", tmp_path / "x.png")
        assert p.returncode != 0, row["option"]
        from_session = words_after(p.stderr.strip().splitlines()[-1], f"{bad_file}.{row['section']}.{row['key']}")

        with pytest.raises(ValueError) as kw:
            amrvk.Renderer(volume, **{row["keyword"]: bad})
        with pytest.raises(ValueError) as prop:
            setattr(r, row["keyword"], bad)
        assert str(kw.value) == str(prop.value), row["keyword"]
        from_python = words_after(str(kw.value), row["keyword"])

        assert from_cli == from_session == from_python, (row["option"], from_cli, from_session, from_python)
        assert ("is not one of" if row["kind"] == "choice" else "is outside") in from_cli, from_cli
    r.close()
