#!/usr/bin/python3
"""Benchmark (not a test): `--traversal auto` against the best measured combination, per data set
and TF preset (issue 31, point 4; docs/benchmarks.md sections 17 and 25).

For each INPUT[:FIELD] and TF: `amrvk render --traversal auto` runs AUTO_RUNS times (its picks from
--json's "auto"), then every distinct pick and every combination of the GPU protocol (step d of
tools/gpu-protocol-run.sh: grid-dda/grid, grid-dda/grid at grid 256, grid-bvh/grid, abr/abr,
brick/grid, kdtree/grid, abr/ext-brick) render in ROUNDS alternating rounds with the same options.
Every combination estimates the same image with the same per-path variance, so the efficiency
ratio is the ratio of paths/s (medians over the rounds): the pick's over the fastest combination's.
A render of a fast combination at --spp takes a few tens of milliseconds on lavapipe, and its
paths/s then varies by 1.5x from run to run; so each candidate first renders once at --spp, and
its rounds take as many samples as give at least --min-seconds of GPU time (at most 64x --spp).

Usage: tools/bench_auto.py [--rounds 3] [--auto-runs 2] [--size 128x128] [--spp 24] [--min-seconds 0.5]
                           [--tfs spiky,foggy] [--amrvk build/bin/amrvk] OUTDIR INPUT[:FIELD]...
Writes OUTDIR/auto.md (the table) and OUTDIR/auto.json (every render's figures).
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys

COMBOS = ["grid-dda/grid", "grid-dda/grid@256", "grid-bvh/grid", "abr/abr", "brick/grid", "kdtree/grid",
          "abr/ext-brick"]


def main():
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--amrvk", default=os.path.join(here, "build", "bin", "amrvk"))
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--auto-runs", type=int, default=2)
    ap.add_argument("--size", default="128x128")
    ap.add_argument("--spp", type=int, default=24)
    ap.add_argument("--min-seconds", type=float, default=0.5)
    ap.add_argument("--tfs", default="spiky,foggy")
    ap.add_argument("outdir")
    ap.add_argument("inputs", nargs="+")
    a = ap.parse_args()
    if not os.access(a.amrvk, os.X_OK):
        sys.exit(f"bench_auto.py: {a.amrvk} is missing: build first (tools/run.sh build)")
    os.makedirs(a.outdir, exist_ok=True)
    env = dict(os.environ, AMRVK_PROGRESS="0")
    common = ["--size", a.size, "--samples-per-invocation", "1", "--mode", "ms", "--ambient", "1", "1", "1",
              "--backend", "sw"]
    log, rows = [], []

    def render(inp, tf, extra, tag, spp=a.spp):
        path, _, field = inp.partition(":")
        j = os.path.join(a.outdir, tag + ".json")
        cmd = [a.amrvk, "render", path, *(["--field", field] if field else []), *common, "--spp", str(spp), "--tf", tf,
               *extra,
               "--json", j, "-o", os.path.join(a.outdir, tag + ".pfm")]
        r = subprocess.run(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if r.returncode != 0:
            sys.exit(f"bench_auto.py: {' '.join(cmd)} failed: {r.stderr.strip().splitlines()[-1:]}")
        with open(j) as f:
            out = json.load(f)
        log.append({"command": cmd[1:], "pathsPerSecond": out["pathsPerSecond"],
                    "majorantViolations": out.get("majorantViolations"), "auto": out.get("auto", {}).get("pick")})
        return out

    def optionsOf(combo):
        trav, _, rest = combo.partition("/")
        samp, _, grid = rest.partition("@")
        return ["--traversal", trav, "--sampler", samp] + (["--grid", grid] if grid else [])

    for inp in a.inputs:
        name = os.path.basename(inp.partition(":")[0].rstrip("/")) or inp
        for tf in a.tfs.split(","):
            picks = []
            for k in range(a.auto_runs):
                out = render(inp, tf, ["--traversal", "auto"], f"{name}.{tf}.auto{k}")
                trav, samp, _ = out["auto"]["pick"].split("/")
                grid = out["auto"]["pickGrid"]
                uses = trav.startswith("grid") or samp == "grid"
                pick = f"{trav}/{samp}" + (f"@{grid}" if uses and grid != "auto" else "")  # as COMBOS name it
                picks.append(pick)
                print(f"{name} {tf}: auto run {k + 1} picked {pick}", file=sys.stderr)
            candidates = list(dict.fromkeys(picks)) + [c for c in COMBOS if c not in picks]
            speed = {c: [] for c in candidates}
            tags = {c: f"{name}.{tf}.{c.replace('/', '-').replace('@', '-grid')}" for c in candidates}
            spp = {}
            for c in candidates:  # calibration: samples for --min-seconds of GPU time
                out = render(inp, tf, optionsOf(c), tags[c])
                gpuSeconds = out["paths"] / out["pathsPerSecond"]
                spp[c] = min(64 * a.spp, max(a.spp, math.ceil(a.spp * a.min_seconds / gpuSeconds)))
            for r in range(a.rounds):
                for c in candidates:
                    speed[c].append(render(inp, tf, optionsOf(c), tags[c], spp[c])["pathsPerSecond"])
            med = {c: statistics.median(v) for c, v in speed.items()}
            best = max((c for c in COMBOS), key=lambda c: med[c])
            ratios = [med[p] / med[best] for p in picks]
            rows.append((name, tf, picks, [med[p] for p in picks], best, med[best], ratios))
            print(f"{name} {tf}: picks {picks} ratios {[round(x, 2) for x in ratios]} (best {best})", file=sys.stderr)
    with open(os.path.join(a.outdir, "auto.json"), "w") as f:
        json.dump(log, f, indent=1)
    with open(os.path.join(a.outdir, "auto.md"), "w") as f:
        f.write(f"`render DATA {' '.join(common)} --spp N --tf TF` (N from {a.spp} up to {a.min_seconds} s of GPU time), "
                f"{a.rounds} alternating rounds, medians\n\n")
        f.write("| data set | TF | picks | pick M paths/s | fastest combination | its M paths/s | ratios |\n")
        f.write("|---|---|---|---|---|---|---|\n")
        for name, tf, picks, ps, best, b, ratios in rows:
            f.write(f"| {name} | {tf} | {'; '.join(picks)} | {'; '.join(f'{p / 1e6:.3f}' for p in ps)} | {best} | "
                    f"{b / 1e6:.3f} | **{'; '.join(f'{x:.2f}' for x in ratios)}** |\n")
        violations = sum(r["majorantViolations"] or 0 for r in log)
        f.write(f"\nMajorant violations summed over the {len(log)} renders: **{violations}**.\n")
    print(open(os.path.join(a.outdir, "auto.md")).read())


if __name__ == "__main__":
    main()
