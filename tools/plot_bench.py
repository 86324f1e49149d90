#!/usr/bin/env python3
"""Plots of `amrvk bench` from DIR/results.json, as PNG and PDF into DIR (matplotlib only).

Usage: python3 tools/plot_bench.py DIR

  error_<data>_<tf>_<mode>   RMSE against GPU time, log-log, per data set x TF x mode: every
                             structure combination, the dense sampler (dashed), the --auto pick,
                             and a slope -1/2 guide (unbiased Monte Carlo error)
  error_<data>_<tf>_dvr      the dvr ray marcher over its step sizes against ae tracking: RMSE
                             against GPU time, and the final RMSE against the step
  grid_sweep_<data>_<tf>     frames/s against macrocells on the longest axis (grid-dda, grid-bvh)
  memory_<data>              device memory per structure combination, after the build and peak
                             (the first TF and mode of the data set)

Prints the name of every file it writes (relative to DIR), one per line; `amrvk bench` links the
PNG files from results.md. Failed runs and points that are null or not positive on a log axis
are left out; a plot with nothing to show is not written. Exit status 1 on unreadable input.
"""
import json
import math
import os
import re
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (the back-end is chosen first)
import matplotlib.ticker  # noqa: E402

FORMATS = ("png", "pdf")
METADATA_KEY = {"png": "Software", "pdf": "Creator"}
GUIDE_COLOR = "0.45"
DVR_KINDS = ("dvr", "pt-ae")


def file_tag(text):
    """`text` with every character but ASCII letters, digits, '-' and '_' replaced by '_'."""
    return re.sub(r"[^A-Za-z0-9_-]", "_", text)


def ok_runs(results):
    return [r for r in results.get("runs", []) if not isinstance(r.get("error"), str)]


def positive(v):
    return isinstance(v, (int, float)) and math.isfinite(v) and v > 0


def curve_points(run):
    """(GPU seconds, RMSE) of a run's error curve, both > 0."""
    pts = [(e.get("seconds"), e.get("rmse")) for e in run.get("error", [])]
    return [(t, e) for t, e in pts if positive(t) and positive(e)]


def unique(items):
    out = []
    for item in items:
        if item not in out:
            out.append(item)
    return out


def run_label(run):
    if run.get("label"):
        return run["label"]
    return "{}/{}/{}".format(run.get("traversal"), run.get("sampler"), run.get("backend"))


def size_text(results):
    return "{}x{}, {}".format(results.get("width"), results.get("height"), results.get("device", "unknown device"))


def series_styles(count):
    """Colour and line style per series: tab10 colours, then the same colours dashed-dotted, ..."""
    colors = plt.get_cmap("tab10").colors
    styles = ("-", "-.", ":", (0, (5, 1)))
    return [(colors[i % len(colors)], styles[(i // len(colors)) % len(styles)]) for i in range(count)]


def add_slope_guide(ax, points, label="slope -1/2 (unbiased)"):
    """Line of slope -1/2 in log-log from the first of `points` (seconds, RMSE) to the time of the last."""
    (t0, e0), t1 = points[0], max(points[-1][0], points[0][0] * 10)
    ax.plot([t0, t1], [e0, e0 * math.sqrt(t0 / t1)], color=GUIDE_COLOR, linestyle="--", linewidth=1.2, label=label,
            zorder=1)


def label_log_axis(axis):
    """Labels some minor ticks too when a log axis spans less than two decades (else one label)."""
    axis.set_minor_formatter(matplotlib.ticker.LogFormatterSciNotation(labelOnlyBase=False, minor_thresholds=(2, 0.5)))


def plain_numbers(axis):
    axis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: "{:g}".format(v)))


def place_legend(ax, entries):
    if entries > 8:
        ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize="small", borderaxespad=0)
    else:
        ax.legend(loc="best", fontsize="small")


def save(fig, directory, stem, written):
    """Writes STEM.png and STEM.pdf, each to a temporary name renamed into place."""
    fig.tight_layout()
    for fmt in FORMATS:
        name = "{}.{}".format(stem, fmt)
        temporary = directory / "{}.tmp-{}".format(name, os.getpid())
        try:
            fig.savefig(temporary, format=fmt, dpi=110, metadata={METADATA_KEY[fmt]: "amrvk tools/plot_bench.py"})
            os.replace(temporary, directory / name)
        except OSError as e:  # named as the plot, not results.json (a full disk blamed the input)
            raise OSError(e.errno, "cannot write {}: {}".format(directory / name, e.strerror or e)) from e
        finally:
            if temporary.exists():
                temporary.unlink()
        written.append(name)
    plt.close(fig)


def plot_error_group(results, runs, dataset, tf, mode, directory, written):
    group = [r for r in runs if r.get("dataset") == dataset and r.get("tf") == tf and r.get("mode") == mode
             and r.get("kind") not in DVR_KINDS and r.get("kind") != "grid-sweep" and curve_points(r)]
    if not group:
        return
    fig, ax = plt.subplots(figsize=(10.5, 6.0))
    for (color, style), run in zip(series_styles(len(group)), group):
        pts = curve_points(run)
        kind = run.get("kind")
        label = run_label(run) + {"dense": " (dense: cost floor)", "auto": " (--auto pick)"}.get(kind, "")
        ax.plot([t for t, _ in pts], [e for _, e in pts], color=color, linestyle="--" if kind == "dense" else style,
                marker="o", markersize=3.5, linewidth=1.4, label=label)
    add_slope_guide(ax, curve_points(group[0]))
    ax.set_xscale("log")
    ax.set_yscale("log")
    label_log_axis(ax.yaxis)
    ax.set_xlabel("GPU time [s] (1 spp per frame; points at 1, 2, 4, ... spp)")
    ax.set_ylabel("RMSE against the reference [linear radiance]")
    ax.set_title("{}, TF {}, mode {}: error against time\n{}".format(dataset, tf, mode, size_text(results)))
    ax.grid(True, which="major", alpha=0.35)
    ax.grid(True, which="minor", alpha=0.12)
    place_legend(ax, len(group) + 1)
    save(fig, directory, "error_{}_{}_{}".format(file_tag(dataset), file_tag(tf), file_tag(mode)), written)


def plot_dvr_group(results, runs, dataset, tf, directory, written):
    group = [r for r in runs if r.get("dataset") == dataset and r.get("tf") == tf and r.get("kind") in DVR_KINDS
             and curve_points(r)]
    if not group:
        return
    tracking = [r for r in group if r.get("kind") == "pt-ae"]
    marching = sorted((r for r in group if r.get("kind") == "dvr"), key=lambda r: r.get("dt") or 0, reverse=True)
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(13.0, 5.6), gridspec_kw={"width_ratios": [3, 2]})
    styles = series_styles(len(marching))
    for run in tracking:
        pts = curve_points(run)
        ax.plot([t for t, _ in pts], [e for _, e in pts], color="black", marker="s", markersize=3.5, linewidth=1.8,
                label=run_label(run))
    for (color, _), run in zip(styles, marching):
        pts = curve_points(run)
        ax.plot([t for t, _ in pts], [e for _, e in pts], color=color, marker="o", markersize=3.5, linewidth=1.3,
                label="dvr, step {:g} cells".format(run.get("dt")))
    if tracking:
        add_slope_guide(ax, curve_points(tracking[0]))
    ax.set_xscale("log")
    ax.set_yscale("log")
    label_log_axis(ax.yaxis)
    ax.set_xlabel("GPU time [s]")
    ax.set_ylabel("RMSE against the ae reference [linear radiance]")
    ax.set_title("error against time")
    ax.grid(True, which="major", alpha=0.35)
    ax.grid(True, which="minor", alpha=0.12)
    place_legend(ax, len(group) + 1)

    steps = [(r.get("dt"), curve_points(r)[-1][1]) for r in marching if positive(r.get("dt"))]
    if steps:
        bx.plot([s for s, _ in steps], [e for _, e in steps], color="tab:red", marker="o", linewidth=1.4,
                label="dvr, final RMSE")
    for run in tracking:
        final = curve_points(run)[-1][1]
        bx.axhline(final, color="black", linewidth=1.4, label="ae tracking, final RMSE")
    bx.set_xscale("log", base=2)
    plain_numbers(bx.xaxis)
    bx.set_yscale("log")
    label_log_axis(bx.yaxis)
    bx.set_xlabel("dvr step [finest cell widths]")
    bx.set_ylabel("final RMSE [linear radiance]")
    bx.set_title("bias of the step (after {} frames)".format(results.get("frames")))
    bx.grid(True, which="both", alpha=0.3)
    bx.legend(loc="best", fontsize="small")
    fig.suptitle("{}, TF {}: dvr ray marching over step sizes against ae tracking ({})".format(
        dataset, tf, size_text(results)))
    save(fig, directory, "error_{}_{}_dvr".format(file_tag(dataset), file_tag(tf)), written)


def grid_cells(run):
    try:
        return float(run.get("grid"))
    except (TypeError, ValueError):
        return None


def plot_grid_sweep(results, runs, dataset, tf, directory, written):
    sweep = [r for r in runs if r.get("kind") == "grid-sweep" and r.get("dataset") == dataset and r.get("tf") == tf
             and positive(r.get("fps")) and positive(grid_cells(r))]
    if not sweep:
        return
    fig, ax = plt.subplots(figsize=(9.0, 5.6))
    traversals = unique(r.get("traversal") for r in sweep)
    for (color, _), traversal in zip(series_styles(len(traversals)), traversals):
        pts = sorted((grid_cells(r), r["fps"]) for r in sweep if r.get("traversal") == traversal)
        ax.plot([g for g, _ in pts], [f for _, f in pts], color=color, marker="o", linewidth=1.5, label=traversal)
    ax.set_xscale("log", base=2)
    plain_numbers(ax.xaxis)
    ax.set_xlabel("macrocells on the longest axis")
    ax.set_ylabel("frames/s (1 spp per frame)")
    ax.set_ylim(bottom=0)
    ax.set_title("{}, TF {}, mode {}: frames/s against macrocell resolution\n{}".format(
        dataset, tf, sweep[0].get("mode"), size_text(results)))
    ax.grid(True, alpha=0.35)
    ax.legend(loc="best", fontsize="small")
    save(fig, directory, "grid_sweep_{}_{}".format(file_tag(dataset), file_tag(tf)), written)


def plot_memory(results, runs, dataset, directory, written):
    mine = [r for r in runs if r.get("dataset") == dataset and r.get("kind") in ("matrix", "dense")]
    if not mine:
        return
    tf, mode = mine[0].get("tf"), mine[0].get("mode")
    combos = [r for r in mine if r.get("tf") == tf and r.get("mode") == mode
              and positive(r.get("deviceBytesAfterBuild")) and positive(r.get("deviceBytesPeak"))]
    if not combos:
        return
    mib = 1024.0 * 1024.0
    fig, ax = plt.subplots(figsize=(max(8.0, 0.55 * len(combos) + 3.0), 6.0))
    xs = range(len(combos))
    width = 0.4
    after = [r["deviceBytesAfterBuild"] / mib for r in combos]
    peak = [r["deviceBytesPeak"] / mib for r in combos]
    for offset, values, label, color in ((-width / 2, after, "after build", "tab:blue"),
                                         (width / 2, peak, "peak while rendering", "tab:orange")):
        bars = ax.bar([x + offset for x in xs], values, width, label=label, color=color)
        ax.bar_label(bars, fmt="%.3g", fontsize="x-small", padding=2)
    ax.set_xticks(list(xs))
    ax.set_xticklabels([run_label(r) for r in combos], rotation=40, ha="right", fontsize="small")
    if max(peak) > 10 * min(after):  # log where the combinations differ by orders of magnitude
        ax.set_yscale("log")
        label_log_axis(ax.yaxis)
    else:
        ax.set_ylim(0, max(peak) * 1.12)
    ax.set_xlabel("traversal / sampler / back-end")
    ax.set_ylabel("device memory [MiB]")
    ax.set_title("{}: device memory per structure combination (TF {}, mode {})\n{}".format(
        dataset, tf, mode, size_text(results)))
    ax.grid(True, axis="y", which="both", alpha=0.3)
    ax.legend(loc="best", fontsize="small")
    save(fig, directory, "memory_{}".format(file_tag(dataset)), written)


def plot_all(directory):
    results = json.loads((directory / "results.json").read_text(encoding="utf-8"))
    runs = ok_runs(results)
    written = []
    for dataset, tf, mode in unique((r.get("dataset"), r.get("tf"), r.get("mode")) for r in runs
                                    if r.get("kind") not in DVR_KINDS and r.get("kind") != "grid-sweep"):
        plot_error_group(results, runs, dataset, tf, mode, directory, written)
    for dataset, tf in unique((r.get("dataset"), r.get("tf")) for r in runs if r.get("kind") in DVR_KINDS):
        plot_dvr_group(results, runs, dataset, tf, directory, written)
    for dataset, tf in unique((r.get("dataset"), r.get("tf")) for r in runs if r.get("kind") == "grid-sweep"):
        plot_grid_sweep(results, runs, dataset, tf, directory, written)
    for dataset in unique(r.get("dataset") for r in runs):
        plot_memory(results, runs, dataset, directory, written)
    return written


def main(argv):
    if len(argv) != 2 or argv[1] in ("-h", "--help"):
        print(__doc__.strip(), file=sys.stderr if len(argv) != 2 else sys.stdout)
        return 0 if len(argv) == 2 else 2
    directory = Path(argv[1])
    try:
        written = plot_all(directory)
    except OSError as e:  # what could not be read or written, by its own name
        what = e.strerror if e.filename is None else "{}: {}".format(e.filename, e.strerror)
        print("plot_bench.py: error: {}".format(what or e), file=sys.stderr)
        return 1
    except ValueError as e:
        print("plot_bench.py: error: {}: {}".format(directory / "results.json", e), file=sys.stderr)
        return 1
    for name in written:
        print(name)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
