#!/usr/bin/python3
"""MPI scaling of amrvk render on one machine (docs/benchmarks.md, "MPI"): per-rank memory, work
and communication, for both --distribute modes.

    tools/bench_mpi.py OUT_DIR [--amrvk PATH] [--cells N] [--ranks 1,2,4] [--size WxH] [--spp N]

Writes into OUT_DIR only: the generated clouds (amrvk gen cloud), one --json per run and
results.json, and prints a markdown table per experiment:
  memory  data-parallel at each rank count on the N-cell cloud: held cells, host and device
          peak per rank against (total / ranks), the halo share; the fixed overhead (a rank of the
          32k-cell sample) is measured too.
  strong  the same picture at each rank count, both modes: per-rank density lookups and render
          seconds, MPI seconds, bytes moved per path.
  weak    data-parallel with N / max(ranks) cells per rank (clouds of N * r / max(ranks) cells).
Ranks share this machine's cores, so wall time is not a speed-up: compare per-rank work and
communication. Open MPI runs as root with its run-as-root settings and --oversubscribe.
"""
import argparse
import json
import os
import pathlib
import subprocess
import sys

SOURCE = pathlib.Path(__file__).resolve().parents[1]


def run(cmd, env):
    r = subprocess.run(cmd, env=env, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("failed: %s\n%s" % (" ".join(map(str, cmd)), r.stderr))
    return r


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--amrvk", default=str(SOURCE / "build" / "bin" / "amrvk"))
    ap.add_argument("--cells", type=float, default=3.2e7)
    ap.add_argument("--ranks", default="1,2,4")
    ap.add_argument("--size", default="64x64")
    ap.add_argument("--spp", type=int, default=8)
    a = ap.parse_args()
    out = pathlib.Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    ranks = [int(r) for r in a.ranks.split(",")]
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", AMRVK_PROGRESS="0")
    env.setdefault("XDG_RUNTIME_DIR", "/tmp")
    mpirun = ["mpirun", "-q", "--oversubscribe"]
    picture = ["--size", a.size, "--spp", str(a.spp), "--mode", "ms", "--tf-range", "0", "1.5", "--light-dir", "1",
               "1", "0", "2", "2", "2"]

    def cloud(cells):
        base = out / ("cloud%d" % int(cells))
        if not (base.with_suffix(".cells")).exists():
            run([a.amrvk, "gen", "cloud", "--cells", "%d" % int(cells), "--seed", "1", "-o", str(base)], env)
        return str(base) + ".cells"

    def render(n, data, distribute, tag):
        j = out / ("%s.json" % tag)
        run(mpirun + ["-n", str(n), a.amrvk, "render", data] + picture +
            ["--distribute", distribute, "-o", str(out / ("%s.pfm" % tag)), "--json", str(j)], env)
        return json.load(open(j))

    results = {"command": " ".join(sys.argv), "cells": int(a.cells), "ranks": ranks, "picture": picture}
    big = cloud(a.cells)
    small = str(SOURCE / "assets" / "samples" / "cloud.cells")
    fixed = render(1, small, "data", "fixed")["mpi"]["perRank"][0]
    results["fixedHostBytes"] = fixed["hostPeakBytes"]
    results["fixedDeviceBytes"] = fixed["deviceMemoryPeakBytes"]

    print("## memory: data-parallel, %s cells (fixed overhead: host %.0f MB, device %.0f MB)" %
          (f"{int(a.cells):,}", fixed["hostPeakBytes"] / 1e6, fixed["deviceMemoryPeakBytes"] / 1e6))
    print("| ranks | held cells (max) | halo | host peak MB (max) | host - fixed vs 1.25 x (1-rank - fixed) / N |"
          " device peak MB (max) | device vs 1.25 x 1-rank / N |")
    print("|---|---|---|---|---|---|---|")
    strong = {}
    for n in ranks:
        strong[("data", n)] = render(n, big, "data", "data-%d" % n)
    one = strong[("data", ranks[0])]["mpi"]["perRank"][0]
    rows = []
    for n in ranks:
        pr = strong[("data", n)]["mpi"]["perRank"]
        held = max(r["heldCells"] for r in pr)
        halo = sum(r["heldCells"] - r["ownedCells"] for r in pr) / max(1, sum(r["ownedCells"] for r in pr))
        host = max(r["hostPeakBytes"] for r in pr)
        dev = max(r["deviceMemoryPeakBytes"] for r in pr)
        host_bound = 1.25 * (one["hostPeakBytes"] - fixed["hostPeakBytes"]) / n
        dev_bound = 1.25 * one["deviceMemoryPeakBytes"] / n
        rows.append({"ranks": n, "heldMax": held, "halo": halo, "hostPeakMax": host, "devicePeakMax": dev,
                     "hostDataBound": host_bound, "deviceBound": dev_bound})
        print("| %d | %s | %.2f%% | %.0f | %.0f vs %.0f | %.0f | %.0f vs %.0f |" %
              (n, f"{held:,}", 100 * halo, host / 1e6, (host - fixed["hostPeakBytes"]) / 1e6, host_bound / 1e6,
               dev / 1e6, dev / 1e6, dev_bound / 1e6))
    results["memory"] = rows

    print("\n## strong scaling: %s cells, %s, %d spp, ms" % (f"{int(a.cells):,}", a.size, a.spp))
    print("| mode | ranks | lookups per rank (max / mean) | render s per rank (max) | MPI s (max) | bytes moved per path |")
    print("|---|---|---|---|---|---|")
    rows = []
    for mode in ("samples", "data"):
        for n in ranks:
            j = strong[(mode, n)] if (mode, n) in strong else render(n, big, mode, "%s-%d" % (mode, n))
            strong[(mode, n)] = j
            pr = j["mpi"]["perRank"]
            look = [r.get("densityLookups", 0) for r in pr]
            if mode == "samples":  # sample-parallel ranks report their paths; lookups are the job's
                look = [j["densityLookups"] * r["paths"] / j["paths"] for r in pr]
            rsec = max(r["renderSeconds"] for r in pr)
            mpis = max(r.get("mpiSeconds", r.get("reduceSeconds", 0)) for r in pr)
            row = {"mode": mode, "ranks": n, "lookupsMax": max(look), "lookupsMean": sum(look) / n,
                   "renderSecondsMax": rsec, "mpiSecondsMax": mpis, "bytesPerPath": j["mpi"]["bytesMovedPerPath"],
                   "bounces": j["mpi"].get("bounces")}
            rows.append(row)
            print("| %s | %d | %.3g / %.3g | %.2f | %.3f | %.1f |" %
                  (mode, n, max(look), sum(look) / n, rsec, mpis, j["mpi"]["bytesMovedPerPath"]))
    results["strong"] = rows

    print("\n## weak scaling: data-parallel, %s cells per rank" % f"{int(a.cells / max(ranks)):,}")
    print("| ranks | cells | lookups per rank (max) | render s per rank (max) | MPI s (max) | bytes moved per path |")
    print("|---|---|---|---|---|---|")
    rows = []
    for n in ranks:
        cells = a.cells * n / max(ranks)
        j = render(n, cloud(cells), "data", "weak-%d" % n)
        pr = j["mpi"]["perRank"]
        row = {"ranks": n, "cells": j["mpi"]["cells"], "lookupsMax": max(r["densityLookups"] for r in pr),
               "renderSecondsMax": max(r["renderSeconds"] for r in pr),
               "mpiSecondsMax": max(r["mpiSeconds"] for r in pr), "bytesPerPath": j["mpi"]["bytesMovedPerPath"]}
        rows.append(row)
        print("| %d | %s | %.3g | %.2f | %.3f | %.1f |" %
              (n, f"{row['cells']:,}", row["lookupsMax"], row["renderSecondsMax"], row["mpiSecondsMax"],
               row["bytesPerPath"]))
    results["weak"] = rows
    json.dump(results, open(out / "results.json", "w"), indent=1)


if __name__ == "__main__":
    main()
