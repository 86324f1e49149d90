#!/usr/bin/env python3
"""Usage: campaign5.py AMRVK SCRATCH [DATA_DIR]. The fifth hostile-input campaign (issue 52,
docs/fuzzing.md): over 100 generated cases on surfaces round 4's list does not name, each one run
of the amrvk binary that must end clean:

- exit 0 (the case is valid) or 1 with exactly one line on stderr, "amrvk CMD: error: ...", that
  names what the case changed where the case says what that is;
- never a signal, a timeout (each case has its own bound), another status, an uncaught exception,
  a sanitizer report or a Vulkan validation error;
- after a failure no output the case named exists, and never a temporary (*.tmp-*) is left.

Surfaces: every `bench` option at values it must refuse (refused before any work); saved
sessions under seeded random edits (a key dropped, a value of another type, out of range, not
finite, very long); viewer scripts under seeded random edits, run headless; and every reader on
real data with seeded random byte flips, under a time bound and a 6 GiB address-space cap
(`info`, which reads and validates everything). The random edits come from a fixed seed, so the
cases are the same on every run; a case that fails prints how to rerun it.
"""
import json
import os
import random
import resource
import shutil
import subprocess
import sys
from pathlib import Path

AMRVK, SCRATCH = Path(sys.argv[1]).resolve(), Path(sys.argv[2]).resolve()
DATA = Path(sys.argv[3]).resolve() if len(sys.argv) > 3 else None
BAD_WORDS = ("Segmentation", "terminate called", "AddressSanitizer", "runtime error:", "Validation Error",
             "Traceback", "Aborted", "core dumped", "std::")
PIC = ["--size", "8x8", "--spp", "1", "--grid", "4", "--mode", "ae"]

failures, counts = [], {}


def address_cap():
    resource.setrlimit(resource.RLIMIT_AS, (6 << 30, 6 << 30))


def case(surface, args, *, cwd, expect=None, names=None, outputs=(), timeout=60, cap=False):
    """One run of amrvk ARGS in `cwd`: clean as the module says. expect: "ok", "error" or None
    (either); names: a fragment the one-line error must hold; outputs: files that must not exist
    after a failure."""
    counts[surface] = counts.get(surface, 0) + 1
    for o in outputs:
        (cwd / o).unlink(missing_ok=True)
    label = f"{surface} #{counts[surface]}: amrvk {' '.join(str(a)[:80] for a in args)}"
    try:
        run = subprocess.run([str(AMRVK), *map(str, args)], cwd=cwd, capture_output=True, timeout=timeout,
                             preexec_fn=address_cap if cap else None, env=dict(os.environ, AMRVK_VALIDATION="1"))
    except subprocess.TimeoutExpired:
        failures.append(f"{label}: no end within {timeout} s")
        return None
    err = run.stderr.decode("utf-8", "replace")
    lines = err.splitlines()
    why = []
    if run.returncode not in (0, 1):
        why.append(f"exit status {run.returncode}")
    if any(w in err for w in BAD_WORDS):
        why.append("a crash, sanitizer, validation or raw exception report")
    if args[0] == "view":  # a script's trace ("amrvk view: frame N: ACTION") is not an error line
        lines = [line for line in lines if not (line.startswith("amrvk view: frame ") and ": error: " not in line)]
    if run.returncode == 1:
        if len(lines) != 1 or not lines[0].startswith("amrvk ") or ": error: " not in lines[0]:
            why.append(f"{len(lines)} stderr lines, not one 'amrvk CMD: error: ...'")
        if names and lines and names not in lines[-1]:
            why.append(f"the error does not name {names!r}")
        why += [f"{o} written by a failed run" for o in outputs if (cwd / o).exists()]
    if expect == "ok" and run.returncode != 0:
        why.append("refused a valid case")
    if expect == "error" and run.returncode != 1:
        why.append("accepted a case it must refuse")
    left = [str(p) for p in cwd.rglob("*.tmp-*")]
    if left:
        why.append(f"temporaries left: {left[:3]}")
        for p in left:
            Path(p).unlink()
    if why:
        failures.append(f"{label}: {'; '.join(why)}; stderr: {err.strip()[-400:]}")
    return run


# ---- setup: a small cloud, its saved session --------------------------------------------------
shutil.rmtree(SCRATCH, ignore_errors=True)
SCRATCH.mkdir(parents=True)
work = SCRATCH / "work"
work.mkdir()
subprocess.run([str(AMRVK), "gen", "cloud", "--cells", "2e3", "--seed", "1", "-o", "c"], cwd=work, check=True,
               capture_output=True)
subprocess.run([str(AMRVK), "view", "c.cells", *PIC, "--headless", "--frames", "1", "--save-session", "s.json"],
               cwd=work, check=True, capture_output=True, env=dict(os.environ, AMRVK_VALIDATION="1"))
rng = random.Random(52005)

# ---- 1. every bench option at a value it refuses, before any work ----------------------------
bench_cases = [
    (["--frames", "0"], "--frames"), (["--frames", "1e9"], "--frames"), (["--warmup", "-1"], "--warmup"),
    (["--reference-spp", "0"], "--reference-spp"), (["--reference-spp", "x"], "--reference-spp"),
    (["--target-rmse", "-1"], "--target-rmse"), (["--target-rmse", "nan"], "--target-rmse"),
    (["--target-rmse", "inf"], "--target-rmse"), (["--dvr-steps", "0"], "--dvr-steps"),
    (["--dvr-steps", ","], "--dvr-steps"), (["--dvr-steps", "65"], "--dvr-steps"), (["--grid-sweep", ","], "--grid-sweep"),
    (["--grid-sweep", "0"], "--grid-sweep"), (["--grid-sweep", "4097"], "--grid-sweep"),
    (["--tfs", ""], "--tfs"), (["--tfs", "nosuch"], "nosuch"), (["--tfs", ","], "--tfs"),
    (["--modes", ""], "--modes"), (["--modes", "ae,xx"], "xx"), (["--traversals", ""], "--traversals"),
    (["--samplers", "dense,grid"], "--samplers"), (["--backends", "gpu"], "gpu"),
    (["--sub-majorants", "32"], "--sub-majorants"), (["--transmittances", ""], "--transmittance"),
    (["--control-extinctions", "minorant,x"], "--control-extinction"), (["--tf-colors", "hsv"], "--tf-colors"),
    (["--size", "0x8"], "--size"), (["--size", "8x"], "--size"), (["--size", "20000x2"], "--size"),
    (["--camera", "0", "0", "0", "0", "0", "0", "0", "1", "0"], "--camera"),
    (["--camera", "nan", "0", "0", "1", "0", "0", "0", "1", "0"], "--camera"), (["--fov", "180"], "--fov"),
    (["--fov", "0"], "--fov"), (["--seed", "-1"], "--seed"), (["--seed", "4294967296"], "--seed"),
    (["--density-scale", "-1"], "--density-scale"), (["--density-scale", "inf"], "--density-scale"),
    (["--g", "1.5"], "--g"), (["--ambient", "-1", "0", "0"], "--ambient"),
    (["--background", "nan", "0", "0"], "--background"), (["--light-dir", "0", "0", "0", "1", "1", "1"], "--light-dir"),
    (["--light-point", "0", "0", "0", "-1", "1", "1"], "--light-point"),
    (["--crop", "1", "1", "1", "0", "0", "0"], "--crop"), (["--clip", "0", "0", "0", "0", "0", "0"], "--clip"),
    (["--gpu-timeout", "-1"], "--gpu-timeout"), (["--samples-per-invocation", "65"], "--samples-per-invocation"),
    (["--kd-leaves", "0"], "--kd-leaves"), (["--dense-max-mib", "0"], "--dense-max-mib"), (["--grid", "0"], "--grid"),
    (["--grid", "4x4"], "--grid"), (["--tf-range", "1", "0"], "--tf-range"), (["--tf-range", "0", "inf"], "--tf-range"),
    (["--scale", "sqrt"], "--scale"), (["--log-floor", "-1"], "--log-floor"), (["--nan", "keep"], "--nan"),
    (["--field", "nosuch"], "nosuch"), (["--device", "99"], "99"), (["--format", "vtk"], "--format"),
]
(work / "afile").write_text("x")
# The smallest bench, so that a case taken by mistake ends soon; each case replaces its option.
small = {"--frames": ["2"], "--warmup": ["0"], "--reference-spp": ["4"], "--size": ["8x8"], "--tfs": ["foggy"],
         "--modes": ["ae"], "--traversals": ["grid-dda"], "--samplers": ["ext-brick"], "--backends": ["sw"],
         "--dvr-steps": ["none"], "--grid-sweep": ["none"], "--sub-majorants": ["off"]}
for extra, names in bench_cases:
    given = dict(small)
    given[extra[0]] = extra[1:]
    argv = [w for k, v in given.items() for w in (k, *v)] + ["--no-dense"]
    shutil.rmtree(work / "b", ignore_errors=True)
    case("bench options", ["bench", "c.cells", "-o", "b", *argv], cwd=work, expect="error", names=names, timeout=120)
    if (work / "b" / "results.json").exists():
        failures.append(f"bench options: {extra}: wrote results.json after refusing")
# Empty items between names are skipped (as documented: "spiky,,foggy" is spiky, foggy): taken, and
# the bench runs what they name.
for extra in (["--grid-sweep", "8,,16"], ["--tfs", "foggy,"], ["--traversals", "grid-dda,,abr"]):
    given = dict(small)
    given[extra[0]] = extra[1:]
    argv = [w for k, v in given.items() for w in (k, *v)] + ["--no-dense"]
    shutil.rmtree(work / "b", ignore_errors=True)
    case("bench options", ["bench", "c.cells", "-o", "b", *argv], cwd=work, expect="ok", timeout=120)
case("bench options", ["bench", "c.cells", "-o", "afile", "--frames", "2"], cwd=work, expect="error", names="afile")
case("bench options", ["bench", "c.cells", "-o", "c.cells", "--frames", "2"], cwd=work, expect="error",
     names="c.cells")

# ---- 2. saved sessions under random edits ------------------------------------------------------
base = json.loads((work / "s.json").read_text())


def leaves(node, path=()):
    if isinstance(node, dict):
        for k, v in node.items():
            yield from leaves(v, path + (k,))
    elif isinstance(node, list) and node and not isinstance(node[0], (dict, list)):
        yield path, node
        for i, v in enumerate(node):
            yield path + (i,), v
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from leaves(v, path + (i,))
    else:
        yield path, node


def edited(doc, path, value, drop=False):
    doc = json.loads(json.dumps(doc))
    node = doc
    for k in path[:-1]:
        node = node[k]
    if drop:
        del node[path[-1]]
    else:
        node[path[-1]] = value
    return doc


replacements = [None, "", "x" * 5000, -1, 0, 1e308, -1e308, 2 ** 64, 0.5, True, [], {}, [1, 2, 3],
                "NaN", "Infinity", {"a": 1}, "\u00e9\n\x1b"]
all_leaves = [p for p, _ in leaves(base) if p]
for k in range(30):
    path = rng.choice(all_leaves)
    drop = rng.random() < 0.2 and not isinstance(path[-1], int)
    value = rng.choice(replacements)
    text = json.dumps(edited(base, path, value, drop), allow_nan=True)
    if value in ("NaN", "Infinity") and not drop:  # the bare JSON tokens, which JSON does not allow
        text = text.replace(f'"{value}"', value)
    (work / f"m{k}.json").write_text(text)
    case("sessions", ["render", "--session", f"m{k}.json", "-o", f"m{k}.png"], cwd=work, outputs=[f"m{k}.png"],
         timeout=120)

# ---- 3. viewer scripts under random edits, headless ---------------------------------------------
script = ["0 orbit 10 5", "1 zoom 1.2", "1 tf-range 0.3 2", "2 density 2", "2 mode ss", "3 crop 0 0 0 1 1 1",
          "3 cut-off", "4 legend off", "4 screenshot shot.png", "5 save-session out.json", "6 quit"]
tokens = ["-1", "0", "1e308", "nan", "inf", "-0", "99999999999999999999", "", "\"a b\"", "\"", "x" * 3000,
          "../escape.png", "/dev/full", "shot.exr", "0x10", "1,5"]
for k in range(14):
    lines = [line.split(" ") for line in script]
    row = rng.randrange(len(lines))
    col = rng.randrange(len(lines[row]) + 1)
    word = rng.choice(tokens)
    if col == len(lines[row]):
        lines[row].append(word)
    else:
        lines[row][col] = word
    (work / f"v{k}.txt").write_text("\n".join(" ".join(w) for w in lines) + "\n")
    case("viewer scripts", ["view", "c.cells", *PIC, "--headless", "--script", f"v{k}.txt"], cwd=work, timeout=120)
    # A script's outputs go where its lines name them (../escape.png too: only edit-shader is
    # confined, to the shader sources); removed for the next case.
    for name in ("shot.png", "out.json", "shot.exr", "../escape.png"):
        (work / name).unlink(missing_ok=True)

# ---- 4. readers with random byte flips, under a time bound and an address-space cap ------------
formats = [
    ("exabrick", work / "c.cells", "c.cells", None),
    ("enzo", "enzo_tiny_cosmology", "DD0018/DD0018", ["DD0018/DD0018.hierarchy", "DD0018/DD0018.cpu0000"]),
    ("amrex", "amrex_pelelm_3d", "example_plt_3d", ["example_plt_3d/Header", "example_plt_3d/Level_0/Cell_H"]),
    ("ramses", "ramses_sedov_2d", "output_00002", ["output_00002/info_00002.txt", "output_00002/amr_00002.out00001"]),
    ("chombo", "chombo_mushy_layer_2d", "plt000100.2d.hdf5", ["plt000100.2d.hdf5"]),
    ("carpet", "carpet_wavetoy_3d", "CarpetWaveToyCheckpoint_test.it_64.h5", ["CarpetWaveToyCheckpoint_test.it_64.h5"]),
]
for fmt, source, entry, flipped in formats:
    if flipped is None:  # the cloud made above
        copy, files = work, [entry, "c.scalars"]
    else:
        if DATA is None or not (DATA / source).exists():
            print(f"skip: {fmt}: no {source} in the data directory")
            continue
        copy = SCRATCH / fmt
        shutil.copytree(DATA / source, copy)
        files = flipped
    for k in range(7):
        name = rng.choice(files)
        target = copy / name
        original = target.read_bytes()
        data = bytearray(original)
        # Half the flips in the first 4 KiB (headers, counts, sizes), the rest anywhere.
        span = min(len(data), 4096) if k % 2 == 0 else len(data)
        for _ in range(rng.choice([1, 1, 2, 8])):
            at = rng.randrange(span)
            data[at] ^= 1 << rng.randrange(8)
        target.write_bytes(bytes(data))
        case(f"byte flips ({fmt})", ["info", entry], cwd=copy, timeout=60, cap=True)
        target.write_bytes(original)

total = sum(counts.values())
print("cases: " + ", ".join(f"{s} {n}" for s, n in counts.items()) + f"; {total} in all")
for f in failures:
    print("FAIL: " + f)
sys.exit(1 if failures or total < 100 else 0)
