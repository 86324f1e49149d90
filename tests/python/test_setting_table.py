"""The picture settings declared once (src/session/setting_table.h; issue 54, point 1). Every
setting of the table round-trips command line -> session file -> Python -> session file with the
same value, and a value outside its limits (or not one of its choices) is refused with the same
words by all three, after each front end's own name for the setting. Before the table the three
worded them apart ("--density-scale: '-1' is outside [0, inf)", "render.densityScale: -1 must be
>= 0", "density_scale -1 must be finite and >= 0"), which this test rejects."""
import json
import math
import os
import re
import subprocess

import pytest

from conftest import SAMPLE, amrvk_binary

SMALL = ["--size", "16x12", "--scale", "linear", "--tf", "ramp"]
FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf"  # fonts-dejavu-core, not the default
# Text settings: a value other than the default, and one the setting refuses (None: none is refused).
TEXT = {"--grid": ("12x10x8", "0"), "--legend-title": ("Density", "x" * 300), "--legend-units": ("g/cm^3", "u" * 257),
        "--legend-font": (FONT, None)}
# The options of `amrvk render` that are not picture settings: the data's reading, the device, the
# outputs and series. Any other option render takes must be a row of the table.
NOT_SETTINGS = {"--session", "--format", "--field", "--nan", "--scale", "--log-floor", "--dims", "--type", "--threshold",
                "--device", "--shader-dir", "--validation", "--gpu-timeout", "--samples-per-invocation",
                "--path-regeneration", "-h", "--help", "--first-frame", "-o", "--output", "--json", "--until-error", "--variance", "--distribute",
                "--series-range", "--orbit", "--frames", "--fps", "--frames-dir", "--progress", "--quiet"}
# The keys of a session file that are not picture settings: what it is, where the data are and how
# they are read.
SESSION_NOT_SETTINGS = {("", "amrvk"), ("", "version"), ("", "input"), ("", "read"), ("", "field")}


def rows_of(amrvk, *kinds):
    return [row for row in amrvk._amrvk._settings() if row["kind"] in kinds]


def simple(amrvk):
    """The rows with one value each (not the compound ones each front end parses)."""
    return rows_of(amrvk, "number", "integer", "choice", "flag", "text")


def example(row):
    """A value of the setting other than its default."""
    if row["kind"] == "choice":
        return next(c for c in row["choices"].split("|") if c not in (row["default"], row["request"]))
    if row["kind"] == "text":
        return TEXT[row["option"]][0]
    if row["kind"] == "flag":
        return not row["default"]
    lo, hi = row["lo"], row["hi"]
    v = lo + 2.5 if math.isinf(hi) else lo + (hi - lo) * 0.25
    return int(round(v)) if row["kind"] == "integer" else v


def outside(row):
    """A value the setting refuses: 'nonsense' for a choice, else just outside its limits (above where a
    session takes 0 as "no limit")."""
    if row["kind"] == "choice":
        return "nonsense"
    if row["kind"] == "text":
        return TEXT[row["option"]][1]
    if row["zero"]:
        return int(row["hi"]) + 1
    if row["lo_open"]:
        return int(row["lo"]) if row["kind"] == "integer" else row["lo"]
    return int(row["lo"]) - 1 if row["kind"] == "integer" else row["lo"] - 1


def in_file(doc, row):
    """The row's value in a session document."""
    return (doc[row["section"]] if row["section"] else doc)[row["key"]]


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


def test_the_table_is_what_every_front_end_takes(amrvk, tmp_path):
    if not os.path.exists(FONT):
        pytest.skip(f"{FONT} is not installed (fonts-dejavu-core)")
    rows = amrvk._amrvk._settings()
    assert len(rows) >= 34
    for row in simple(amrvk):
        assert row["keyword"] == row["option"][2:].replace("-", "_"), row
        if row["kind"] in ("number", "integer"):
            d = row["default"]
            assert (d > row["lo"] if row["lo_open"] else d >= row["lo"]) and (d < row["hi"] if row["hi_open"] else d <= row["hi"]), row
        if row["kind"] == "choice":
            assert row["default"] in row["choices"].split("|"), row
    # Every option render takes is a row's or named above as no setting (and every row's is taken).
    help_text = cli("render", "--help").stdout
    taken = set(re.findall(r"^\s+((?:-\w, )?--?[\w-]+)", help_text, re.M))
    taken = {t.split(", ")[-1] for t in taken}
    options = {row["option"] for row in rows}
    assert options <= taken, options - taken
    assert taken - options <= NOT_SETTINGS, taken - options - NOT_SETTINGS
    # Every key of a session file is a row's: one written with every compound setting given.
    f = tmp_path / "all.json"
    p = cli("view", SAMPLE, *SMALL, "--camera", "2", "1", "3", "0.5", "0.5", "0.5", "0", "1", "0", "--ambient", "1", "1", "1",
            "--background", "0", "0", "0", "--light-dir", "0", "0", "1", "1", "1", "1", "--light-point", "1", "1", "1", "2", "2", "2",
            "--crop", "0", "0", "0", "1", "1", "1", "--clip", "0.5", "0.5", "0.5", "1", "0", "0", "--legend",
            "--headless", "--frames", "1", "--save-session", f)
    assert p.returncode == 0, p.stderr
    doc = json.loads(f.read_text())
    keys = {("", k) for k in doc if not isinstance(doc[k], dict) or k in ("transferFunction",)}
    keys |= {(k, sub) for k in doc if isinstance(doc[k], dict) and k != "transferFunction" for sub in doc[k]}
    declared = {(row["section"], key) for row in rows for key in row["key"].split("|") if key}
    stray = {k for k in keys - declared - SESSION_NOT_SETTINGS if k[0] != "read"}
    assert not stray, stray
    for section, key in declared:
        assert (section, key) in keys, (section, key)  # every row's key was written
    # Every row's Python keyword is one Renderer() takes: a wrong value is a ValueError or TypeError naming
    # it, never "unexpected keyword argument".
    volume = amrvk.Volume(str(SAMPLE), scale="linear")
    for row in rows:
        for kw in filter(None, row["keyword"].split("|")):
            if kw in ("tf", "camera"):
                continue  # Renderer's own arguments (an amrvk.TransferFunction, an amrvk.Camera)
            with pytest.raises((ValueError, TypeError)) as e:
                amrvk.Renderer(volume, **{kw: object()})
            assert "unexpected keyword" not in str(e.value) and kw in str(e.value), (kw, str(e.value))
    with pytest.raises(TypeError, match="unexpected keyword argument 'colour'"):
        amrvk.Renderer(volume, colour=1)


def test_every_setting_round_trips_cli_session_python_session(amrvk, tmp_path):
    if not os.path.exists(FONT):
        pytest.skip(f"{FONT} is not installed (fonts-dejavu-core)")
    rows = simple(amrvk)
    args = []
    for row in rows:
        v = example(row)
        args += [row["option"]] if row["kind"] == "flag" else [row["option"], text(v)]
    first = tmp_path / "cli.json"
    p = cli("view", SAMPLE, *SMALL, *args, "--headless", "--frames", "1", "--save-session", first)
    assert p.returncode == 0, p.stderr
    saved = json.loads(first.read_text())
    for row in rows:
        assert in_file(saved, row) == example(row), (row["option"], in_file(saved, row))

    r = amrvk.Renderer.from_session(str(first), quiet=True)
    for row in rows:
        if row["python_property"]:
            got = getattr(r, row["keyword"])
            assert got == example(row), (row["keyword"], got)
    again = tmp_path / "python.json"
    r.save_session(str(again))
    for row in rows:
        assert in_file(json.loads(again.read_text()), row) == example(row), row["option"]

    # Each property set back to its default, the file follows.
    for row in rows:
        if row["python_property"]:
            setattr(r, row["keyword"], row["default"])
            assert getattr(r, row["keyword"]) == row["default"], row["keyword"]
    r.save_session(str(again))
    back = json.loads(again.read_text())
    for row in rows:
        if row["python_property"]:
            assert in_file(back, row) == row["default"], row["option"]
    r.close()

    # Python's keywords make the same session as the command line's options.
    volume = amrvk.Volume(str(SAMPLE), scale="linear")
    r = amrvk.Renderer(volume, width=16, height=12, quiet=True, **{row["keyword"]: example(row) for row in rows})
    by_keyword = tmp_path / "keywords.json"
    r.save_session(str(by_keyword))
    for row in rows:
        assert in_file(json.loads(by_keyword.read_text()), row) == example(row), row["keyword"]
    r.close()


def test_a_refused_value_has_the_same_words_everywhere(amrvk, tmp_path):
    rows = [row for row in simple(amrvk) if row["kind"] != "flag" and outside(row) is not None]
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
        (s.setdefault(row["section"], {}) if row["section"] else s)[row["key"]] = bad
        bad_file = tmp_path / f"{row['key']}.json"
        bad_file.write_text(json.dumps(s))
        p = cli("render", "--session", bad_file, "-o", tmp_path / "x.png")
        assert p.returncode != 0, row["option"]
        where = f"{bad_file}.{row['section']}.{row['key']}" if row["section"] else f"{bad_file}.{row['key']}"
        from_session = words_after(p.stderr.strip().splitlines()[-1], where)

        with pytest.raises(ValueError) as kw:
            amrvk.Renderer(volume, **{row["keyword"]: bad})
        from_python = words_after(str(kw.value), row["keyword"])
        if row["python_property"]:
            with pytest.raises(ValueError) as prop:
                setattr(r, row["keyword"], bad)
            assert str(kw.value) == str(prop.value), row["keyword"]

        assert from_cli == from_session == from_python, (row["option"], from_cli, from_session, from_python)
        expected = {"choice": "is not one of", "text": "(got"}.get(row["kind"], "is outside")
        if row["kind"] == "text" and row["option"].startswith("--legend-"):
            expected = "bytes (at most"
        assert expected in from_cli, from_cli
    r.close()


def test_a_session_never_holds_the_request_auto(amrvk, tmp_path):
    """--traversal auto and traversal='auto' probe; a session holds the traversal chosen, and says so."""
    base = tmp_path / "base.json"
    assert cli("view", SAMPLE, *SMALL, "--headless", "--frames", "1", "--save-session", base).returncode == 0
    s = json.loads(base.read_text())
    s["structure"]["traversal"] = "auto"
    bad = tmp_path / "auto.json"
    bad.write_text(json.dumps(s))
    p = cli("render", "--session", bad, "-o", tmp_path / "x.png")
    assert p.returncode != 0 and f"{bad}.structure.traversal: 'auto' asks to probe" in p.stderr, p.stderr
