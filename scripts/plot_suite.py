#!/usr/bin/env python3
"""Plots of `l2s suite` results, in the manner of the paper's Figs. 5-7.

usage: plot_suite.py OUT_DIR    (reads OUT_DIR/results.csv, writes OUT_DIR/*.png)

Only successful runs have errors to plot; failures are counted in each
panel's title (the summary.md beside the plots lists their reasons).
Needs matplotlib (Debian: python3-matplotlib); standard library otherwise.
"""
import csv
import math
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PRESET_COLORS = {"default": "tab:blue", "paper": "tab:orange"}
K_COLORS = ["tab:green", "tab:blue", "tab:orange", "tab:red", "tab:purple"]
LIDAR_NAMES = {"vlp16": "VLP-16", "hdl32": "HDL-32E", "hdl64": "HDL-64E"}
METRICS = [("e_t_m", 1e3, "$e_t$ [mm]"), ("e_r_rad", 180.0 / math.pi, "$e_r$ [deg]")]


def read_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        r["setting"] = int(r["setting"])
        r["frames"] = int(r["frames"])
        r["noise_k"] = float(r["noise_k"])
        r["repetition"] = int(r["repetition"])
        r["success"] = r["success"] == "1"
        for key in ("e_t_m", "e_r_rad"):
            r[key] = float(r[key])
    return rows


def grouped_boxes(ax, groups, series, values, colors, labels, metric_scale):
    """Boxes per group (x axis) with one box per series side by side."""
    width = 0.8 / max(1, len(series))
    for j, s in enumerate(series):
        data, positions = [], []
        for i, g in enumerate(groups):
            v = [x * metric_scale for x in values.get((g, s), [])]
            if v:
                data.append(v)
                positions.append(i + (j - (len(series) - 1) / 2) * width)
        if not data:
            continue
        box = ax.boxplot(data, positions=positions, widths=width * 0.85, patch_artist=True,
                         medianprops={"color": "red"}, flierprops={"markersize": 3})
        for patch in box["boxes"]:
            patch.set_facecolor(colors[j % len(colors)])
            patch.set_alpha(0.6)
        ax.plot([], [], "s", color=colors[j % len(colors)], alpha=0.6, label=labels[j])
    ax.set_xticks(range(len(groups)))
    ax.set_xticklabels([str(g) for g in groups])
    ax.grid(axis="y", alpha=0.3)


def failures_text(rows):
    failed = sum(1 for r in rows if not r["success"])
    return f"{failed} of {len(rows)} runs failed" if failed else f"{len(rows)} runs, all succeeded"


def plot_frames(rows, out_dir):
    presets = sorted({r["preset"] for r in rows})
    settings = sorted({r["setting"] for r in rows})
    fig, axes = plt.subplots(2, len(presets), figsize=(6 * len(presets), 7), squeeze=False)
    cmap = plt.get_cmap("tab10")
    for c, preset in enumerate(presets):
        for m, (key, scale, label) in enumerate(METRICS):
            ax = axes[m][c]
            for s in settings:
                by_n = defaultdict(list)
                for r in rows:
                    if r["preset"] == preset and r["setting"] == s and r["success"]:
                        by_n[r["frames"]].append(r[key] * scale)
                ns = sorted(by_n)
                ax.plot(ns, [median(by_n[n]) for n in ns], color=cmap(s - 1), lw=1, label=f"setting {s}")
            ax.set_xlabel("frames")
            ax.set_ylabel(label)
            ax.set_yscale("log")
            ax.grid(alpha=0.3, which="both")
            preset_rows = [r for r in rows if r["preset"] == preset and r["frames"] == max_frames(rows)]
            ax.set_title(f"{preset} preset: median over repetitions "
                         f"({failures_text(preset_rows)} at the end)", fontsize=9)
        axes[0][c].legend(fontsize=7, ncol=3)
    fig.suptitle("Error against the number of cumulated frames (VLP-16, K = 1; paper Fig. 5)")
    save(fig, out_dir, "frames.png")


def plot_noise(rows, out_dir):
    presets = sorted({r["preset"] for r in rows})
    settings = sorted({r["setting"] for r in rows})
    ks = sorted({r["noise_k"] for r in rows})
    fig, axes = plt.subplots(2, len(presets), figsize=(7 * len(presets), 7), squeeze=False)
    for c, preset in enumerate(presets):
        cell = [r for r in rows if r["preset"] == preset]
        for m, (key, scale, label) in enumerate(METRICS):
            values = defaultdict(list)
            for r in cell:
                if r["success"]:
                    values[(r["setting"], r["noise_k"])].append(r[key])
            ax = axes[m][c]
            grouped_boxes(ax, settings, ks, values, K_COLORS, [f"K = {k:g}" for k in ks], scale)
            ax.set_xlabel("setting")
            ax.set_ylabel(label)
            ax.set_title(f"{preset} preset ({failures_text(cell)})", fontsize=9)
        axes[0][c].legend(fontsize=7)
    fig.suptitle("Robustness against noise N(0, (K sigma_0)^2) (VLP-16, 30 frames; paper Fig. 6)")
    save(fig, out_dir, "noise.png")


def plot_lidars(rows, out_dir, name, title):
    presets = sorted({r["preset"] for r in rows}, key=lambda p: (p != "paper", p))
    settings = sorted({r["setting"] for r in rows})
    lidars = [l for l in ("vlp16", "hdl32", "hdl64") if any(r["lidar"] == l for r in rows)]
    fig, axes = plt.subplots(2, len(lidars), figsize=(6 * len(lidars), 7), squeeze=False)
    for c, lidar in enumerate(lidars):
        cell = [r for r in rows if r["lidar"] == lidar]
        for m, (key, scale, label) in enumerate(METRICS):
            values = defaultdict(list)
            for r in cell:
                if r["success"]:
                    values[(r["setting"], r["preset"])].append(r[key])
            ax = axes[m][c]
            colors = [PRESET_COLORS.get(p, "tab:gray") for p in presets]
            grouped_boxes(ax, settings, presets, values, colors, presets, scale)
            ax.set_xlabel("setting")
            ax.set_ylabel(label)
            ax.set_title(f"{LIDAR_NAMES.get(lidar, lidar)} ({failures_text(cell)})", fontsize=9)
        axes[0][c].legend(fontsize=7)
    fig.suptitle(title)
    save(fig, out_dir, name)


def median(values):
    v = sorted(values)
    n = len(v)
    if n == 0:
        return float("nan")
    return v[n // 2] if n % 2 else 0.5 * (v[n // 2 - 1] + v[n // 2])


def max_frames(rows):
    return max(r["frames"] for r in rows)


def plot_scenes(rows, out_dir):
    """Randomised scenes have no settings to put on an axis: the share of
    scenes calibrated within an error (failures never reach 100 %)."""
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for ax, (key, scale, label) in zip(axes, METRICS):
        for preset in sorted({r["preset"] for r in rows}):
            runs = [r for r in rows if r["preset"] == preset]
            errors = sorted(r[key] * scale for r in runs if r["success"])
            if not errors:
                continue
            shares = [100.0 * (i + 1) / len(runs) for i in range(len(errors))]
            ax.step(errors, shares, where="post", color=PRESET_COLORS.get(preset),
                    label=f"{preset} ({len(errors)} of {len(runs)} found)")
        ax.set_xscale("log")
        ax.set_xlabel(label)
        ax.set_ylabel("scenes calibrated within [%]")
        ax.set_ylim(0, 100)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(loc="lower right")
    fig.suptitle("Randomised scenes: rigs, lenses, boards, backgrounds, light, lidars and quirks")
    save(fig, out_dir, "scenes.png")


POSE_TITLES = {
    "poses": "Error against the number of board poses (stereo rig, VLP-16, K = 1, 10 frames per pose)",
    "mono": "Mono camera by the board's markers against the number of board poses (VLP-16, K = 1)",
    "lidar-pair": "Lidar to lidar, VLP-16 to HDL-32E, against the number of board poses (K = 1)",
}


def plot_poses(rows, out_dir, experiment):
    """Boxes of the error after P = 1, 2, 3, 5 poses of the same recordings."""
    for r in rows:
        fields = dict(f.split("=", 1) for f in r["scene"].split() if "=" in f)
        r["poses"] = int(fields.get("poses", 0))
    counts = sorted({r["poses"] for r in rows})
    presets = sorted({r["preset"] for r in rows})
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for ax, (key, scale, label) in zip(axes, METRICS):
        values = defaultdict(list)
        for r in rows:
            if r["success"]:
                values[(r["poses"], r["preset"])].append(r[key])
        grouped_boxes(ax, counts, presets, values, [PRESET_COLORS.get(p, "tab:gray") for p in presets],
                      presets, scale)
        failed = sum(1 for r in rows if not r["success"])
        ax.set_xlabel("board poses P" + (f" ({failed} runs failed)" if failed else ""))
        ax.set_ylabel(label)
        ax.set_yscale("log")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.suptitle(POSE_TITLES[experiment])
    save(fig, out_dir, experiment + ".png")


def save(fig, out_dir, name):
    fig.tight_layout()
    path = os.path.join(out_dir, name)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    print(f"plot      {path}")


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__.strip().splitlines()[2])
    out_dir = sys.argv[1]
    rows = read_rows(os.path.join(out_dir, "results.csv"))
    by_experiment = defaultdict(list)
    for r in rows:
        by_experiment[r["experiment"]].append(r)
    if "frames" in by_experiment:
        plot_frames(by_experiment["frames"], out_dir)
    if "noise" in by_experiment:
        plot_noise(by_experiment["noise"], out_dir)
    if "lidars" in by_experiment:
        plot_lidars(by_experiment["lidars"], out_dir, "lidars.png",
                    "Error per lidar model, paper vs default preset (K = 1, 30 frames; paper Fig. 7)")
    if "quick" in by_experiment:
        plot_lidars(by_experiment["quick"], out_dir, "quick.png", "Quick suite (VLP-16, K = 1, 10 frames)")
    if "scenes" in by_experiment:
        plot_scenes(by_experiment["scenes"], out_dir)
    for experiment in POSE_TITLES:
        if experiment in by_experiment:
            plot_poses(by_experiment[experiment], out_dir, experiment)


if __name__ == "__main__":
    main()
