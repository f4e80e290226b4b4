#!/usr/bin/python3
"""The thesis's figures from a runout sweep (SPEC §7), with matplotlib.

    runout plot DIR            (runs this script with Debian's /usr/bin/python3)
    /usr/bin/python3 runout_plot.py DIR [--out FIGDIR]

Reads DIR/points.csv, DIR/results.csv and each case's DIR/cases/NAME/timeseries.csv and writes
PNG and PDF of: fig4_1 (mu against %A_p per D/d, the monodisperse value dashed), fig4_2 (%A_p,m
against D/d with the bracket of its neighbouring shares), fig4_3 (E_k/Ep0 against t*), fig4_14
(H_layer/d against %A_p), fig4_15 (mean heights above the bed of small and large discs against
x_cm) and fig4_16 (basal spin against t*). One colour per D/d in every figure. From the pictures
`runout plot` draws first (DIR/figures/frames, listed in frames.json): fig3_4 (the flow sequence
of one case, thesis: D/d = 8.33, 25 %), a strip per case in figures/strips, and per D/d the
deposit around its centroid with the basal layer highlighted (figs. 4.7-4.10) at the share of
least friction and its neighbours. Restyle freely: this file is installed with runout so that it
can be copied and edited.
"""
import argparse
import csv
import json
import math
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402

# Okabe–Ito, one per size ratio, the same in every figure.
RATIO_COLOURS = {"2": "#0072B2", "3": "#009E73", "4": "#E69F00", "8.33": "#D55E00"}
EXTRA = ["#CC79A7", "#56B4E9", "#F0E442", "#000000"]


def colour(ratio, _seen={}):
    if ratio in RATIO_COLOURS:
        return RATIO_COLOURS[ratio]
    return _seen.setdefault(ratio, EXTRA[len(_seen) % len(EXTRA)])


def number(text):
    try:
        v = float(text)
        return v if math.isfinite(v) else None
    except (TypeError, ValueError):
        return None


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def save(fig, out, name, written):
    for ext in ("png", "pdf"):
        path = os.path.join(out, f"{name}.{ext}")
        tmp = path + ".tmp"
        fig.savefig(tmp, dpi=150, bbox_inches="tight", format=ext)
        os.replace(tmp, path)  # never a half-written figure
        written.append(path)
    plt.close(fig)


def ratio_key(r):
    return float(r) if number(r) is not None else math.inf


def study(folder, title):
    """`runout study accuracy`'s plot: wall seconds per t* against |delta mu| to the reference,
    log-log, two standard errors as bars, each variant numbered and named in the legend."""
    rows = [r for r in read_csv(os.path.join(folder, "study.csv")) if number(r.get("seconds_per_t_star"))]
    fig, ax = plt.subplots(figsize=(9.0, 4.8))
    for k, r in enumerate(rows, 1):
        x = number(r["seconds_per_t_star"])
        y = number(r["mu_error"]) or 0.0
        e = number(r["mu_noise_2se"]) or 0.0
        label = "reference" if r["family"] == "reference" else f"{r['family']} {r['setting']}"
        # A zero error (the reference itself) sits on the axis, at the bottom of its bar.
        shown = y if y > 0 else max(e, 1e-4) / 10
        # On a log axis a bar down to zero has no end: it stops at a tenth of the point.
        ax.errorbar([x], [shown], yerr=[[min(e, shown * 0.9)], [e]], fmt="o", ms=6, capsize=3,
                    color="#0072B2" if r["family"] != "reference" else "#D55E00", label=f"{k}  {label}")
        ax.annotate(str(k), (x, shown), textcoords="offset points", xytext=(6, 4), fontsize=8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.xaxis.set_minor_formatter(matplotlib.ticker.LogFormatter(labelOnlyBase=False, minor_thresholds=(2, 0.5)))
    ax.set_xlabel("wall seconds per t* of flow (mean over the piles)")
    ax.set_ylabel("|mean μ − mean μ of the reference|")
    ax.set_title(title)
    ax.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.02, 0.5), title="variant (bars: ±2 SE)",
              title_fontsize=7)
    written = []
    save(fig, folder, "study", written)
    for path in written:
        print(path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dir", help="a runout sweep folder (with points.csv), or a study folder with --study")
    ap.add_argument("--out", help="where the figures go (default DIR/figures)")
    ap.add_argument("--study", action="store_true", help="DIR is a `runout study accuracy` folder: draw study.png/pdf")
    ap.add_argument("--title", default="speed against accuracy")
    a = ap.parse_args()
    plt.rcParams.update({"font.size": 10, "axes.grid": True, "grid.alpha": 0.3})
    if a.study:
        return study(a.dir, a.title)
    points_path = os.path.join(a.dir, "points.csv")
    if not os.path.exists(points_path):
        sys.exit(f"runout plot: {points_path} not found: run `runout sweep SWEEP --out {a.dir}` first")
    out = a.out or os.path.join(a.dir, "figures")
    os.makedirs(out, exist_ok=True)
    points = read_csv(points_path)
    results = read_csv(os.path.join(a.dir, "results.csv"))
    written = []
    plt.rcParams.update({"font.size": 10, "axes.grid": True, "grid.alpha": 0.3, "figure.figsize": (6.0, 4.0)})
    if points and "small_share" in points[0]:
        minima = thesis_figures(a.dir, out, points, results, written)
    else:
        # Not a sweep over %A_p (a polydisperse pile, a knob): mu against its first axis and
        # the segregation class by class; the frames and the report as for the thesis.
        minima = ["ratio,share_min,bracket_low,bracket_high,mu_min_mean,mu_min_2se,at_edge"]
        other_figures(a.dir, out, points, results, written)
    points_axes = list(points[0])[: list(points[0]).index("n")] if points and "n" in points[0] else []
    strips = study_frames(a.dir, out, results, minima, written, points_axes)
    report(a.dir, out, points, results, [w for w in written if w.endswith(".png")], minima, strips)
    for path in written:
        print(path)


def thesis_figures(folder, out, points, results, written):
    """Figs. 4.1, 4.2, 4.3, 4.14, 4.15, 4.16 and DIR/minimum.csv; returns minimum.csv's lines."""
    has_ratio = "ratio" in points[0]
    by_ratio = defaultdict(list)
    for p in points:
        by_ratio[p["ratio"] if has_ratio else "—"].append(p)
    ratios = sorted(by_ratio, key=ratio_key)

    def series(rows, col):
        xs, ys, es = [], [], []
        for p in sorted(rows, key=lambda p: float(p["small_share"])):
            y = number(p.get(col + "_mean"))
            if y is None:
                continue
            xs.append(float(p["small_share"]))
            ys.append(y)
            e = number(p.get(col + "_2se"))
            es.append(e if e is not None else 0.0)
        return xs, ys, es

    # Fig. 4.1: mu = H_cm / L_cm against %A_p.
    fig, ax = plt.subplots()
    mono = [number(p["mu_global_mean"]) for p in points if float(p["small_share"]) in (0.0, 100.0)]
    mono = [m for m in mono if m is not None]
    for r in ratios:
        xs, ys, es = series(by_ratio[r], "mu_global")
        ax.errorbar(xs, ys, yerr=es, marker="o", ms=4, capsize=3, color=colour(r),
                    label=f"D/d = {r}" if has_ratio else "this sweep")
    if mono:
        ax.axhline(sum(mono) / len(mono), ls="--", color="0.4", lw=1, label="monodisperse (mean)")
    ax.set_xlabel("share of small discs %A_p (% of the disc area)")
    ax.set_ylabel("global friction μ = H_cm / L_cm")
    ax.set_title("Fig. 4.1: friction against the share of small discs (±2 SE over seeds)")
    ax.legend(fontsize=8)
    save(fig, out, "fig4_1_mu_vs_share", written)

    # Fig. 4.2: %A_p,m (the share of the lowest mean mu) with its bracket, also as DIR/minimum.csv.
    fig, ax = plt.subplots()
    minima = ["ratio,share_min,bracket_low,bracket_high,mu_min_mean,mu_min_2se,at_edge"]
    for r in ratios:
        xs, ys, es = series(by_ratio[r], "mu_global")
        if len(xs) < 2 or number(r) is None:
            continue
        k = min(range(len(ys)), key=lambda i: ys[i])
        lo = xs[k - 1] if k > 0 else xs[k]
        hi = xs[k + 1] if k + 1 < len(xs) else xs[k]
        # At the first or last share sampled the minimum may lie beyond it: said, not hidden.
        minima.append(f"{r},{xs[k]:g},{lo:g},{hi:g},{ys[k]:.6g},{es[k]:.6g},{int(k in (0, len(xs) - 1))}")
        ax.errorbar([float(r)], [xs[k]], yerr=[[xs[k] - lo], [hi - xs[k]]], marker="s", ms=6, capsize=4,
                    color=colour(r), label=f"D/d = {r}: {xs[k]:g} % ({lo:g}–{hi:g})")
    ax.set_xlabel("size ratio D/d")
    ax.set_ylabel("%A_p,m (share of the lowest μ)")
    ax.set_title("Fig. 4.2: the share of least friction, bracketed by its neighbours")
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=8)
    else:  # no D/d axis: nothing to place against D/d
        ax.text(0.5, 0.5, "no D/d axis in this sweep", transform=ax.transAxes, ha="center", color="0.4")
    save(fig, out, "fig4_2_share_min_vs_ratio", written)
    with open(os.path.join(folder, "minimum.csv.tmp"), "w") as f:
        f.write("\n".join(minima) + "\n")
    os.replace(os.path.join(folder, "minimum.csv.tmp"), os.path.join(folder, "minimum.csv"))
    written.append(os.path.join(folder, "minimum.csv"))

    # Fig. 4.14: basal layer thickness.
    fig, ax = plt.subplots()
    for r in ratios:
        xs, ys, es = series(by_ratio[r], "H_layer_over_d")
        ax.errorbar(xs, ys, yerr=es, marker="o", ms=4, capsize=3, color=colour(r), label=f"D/d = {r}")
    ax.set_xlabel("share of small discs %A_p (%)")
    ax.set_ylabel("basal layer thickness H_layer / d")
    ax.set_title("Fig. 4.14: the basal layer of small discs")
    ax.legend(fontsize=8)
    save(fig, out, "fig4_14_layer_vs_share", written)

    # Time series of one seed per point (the lowest), one panel per D/d.
    cases = defaultdict(list)
    for row in results:
        cases[row.get("ratio", "—")].append(row)

    def first_seed(rows):
        best = {}
        for row in rows:
            s = row["small_share"]
            seed = number(row.get("seed", "0")) or 0
            if s not in best or seed < best[s][0]:
                best[s] = (seed, row)
        return [best[s][1] for s in sorted(best, key=float)]

    def panels(title, name, ycol, ylabel, xcol="t_star", xlabel="t*", logy=False):
        fig, axes = plt.subplots(1, len(ratios), figsize=(4.0 * len(ratios), 3.4), squeeze=False, sharey=True)
        for ax, r in zip(axes[0], ratios):
            rows = first_seed(cases.get(r, []))
            shades = plt.cm.viridis([0.85 * i / max(1, len(rows) - 1) for i in range(len(rows))])
            for row, shade in zip(rows, shades):
                path = os.path.join(folder, "cases", row["case"], "timeseries.csv")
                if not os.path.exists(path):
                    continue
                ts = read_csv(path)
                xs = [number(t.get(xcol)) for t in ts]
                ys = [number(t.get(ycol)) for t in ts]
                pts = [(x, y) for x, y in zip(xs, ys) if x is not None and y is not None and (not logy or y > 0)]
                if pts:
                    ax.plot(*zip(*pts), color=shade, lw=1, label=f"{float(row['small_share']):g} %")
            ax.set_title(f"D/d = {r}", color=colour(r))
            ax.set_xlabel(xlabel)
            if logy:
                ax.set_yscale("log")
                ax.set_ylim(bottom=1e-6)  # the pile at rest before release is 1e-18: not the story
            ax.legend(fontsize=7, title="%A_p", title_fontsize=7)
        axes[0][0].set_ylabel(ylabel)
        fig.suptitle(title, y=1.03)
        save(fig, out, name, written)

    panels("Figs. 4.3–4.6: kinetic energy", "fig4_3_ek_vs_t", "ek_over_ep0", "E_k / Ep0", logy=True)
    panels("Figs. 4.16–4.19: spin of the small discs on the bed", "fig4_16_spin_vs_t", "basal_spin",
           "basal spin ω √(d/g)")

    # Fig. 4.15: mean height above the bed of small and large discs, and their difference.
    fig, axes = plt.subplots(1, len(ratios), figsize=(4.0 * len(ratios), 3.4), squeeze=False, sharey=True)
    for ax, r in zip(axes[0], ratios):
        rows = [row for row in first_seed(cases.get(r, [])) if 0 < float(row["small_share"]) < 100]
        for row in rows[-1:]:  # the largest share with both species
            ts = read_csv(os.path.join(folder, "cases", row["case"], "timeseries.csv"))
            x = [number(t["x_cm"]) for t in ts]
            s = [number(t.get("small_mean_height")) for t in ts]
            l = [number(t.get("large_mean_height")) for t in ts]
            keep = [i for i in range(len(ts)) if None not in (x[i], s[i], l[i])]
            if not keep:
                continue
            xs = [x[i] for i in keep]
            ax.plot(xs, [s[i] for i in keep], color=colour(r), ls="-", label="small")
            ax.plot(xs, [l[i] for i in keep], color=colour(r), ls="--", label="large")
            ax.plot(xs, [l[i] - s[i] for i in keep], color="0.3", ls=":", label="large − small")
            ax.set_title(f"D/d = {r}, %A_p = {float(row['small_share']):g}", color=colour(r))
        ax.set_xlabel("x_cm / d")
        ax.legend(fontsize=7)
    axes[0][0].set_ylabel("mean height above the bed / d")
    fig.suptitle("Fig. 4.15: segregation along the run-out", y=1.03)
    save(fig, out, "fig4_15_heights_vs_xcm", written)

    return minima


def other_figures(folder, out, points, results, written):
    axes = list(points[0].keys())[: list(points[0].keys()).index("n")] if points else []
    if axes:
        key = axes[0]
        fig, ax = plt.subplots()
        rows = sorted((p for p in points if number(p[key]) is not None), key=lambda p: float(p[key]))
        ax.errorbar([float(p[key]) for p in rows], [number(p["mu_global_mean"]) for p in rows],
                    yerr=[number(p.get("mu_global_2se")) or 0.0 for p in rows], marker="o", ms=4, capsize=3,
                    color="#0072B2")
        ax.set_xlabel(key)
        ax.set_ylabel("global friction μ = H_cm / L_cm")
        ax.set_title(f"friction against {key} (±2 SE over seeds)")
        save(fig, out, "mu_vs_" + key.replace(".", "_"), written)
    # Segregation per class: the deposit's mean height above the bed of each species against its
    # nominal diameter (summary.json's diameters), one line per case.
    prefix = "mean_height_over_d."
    if results and sum(c.startswith(prefix) for c in results[0]) >= 3:
        fig, ax = plt.subplots()
        shades = plt.cm.viridis([0.85 * i / max(1, len(results) - 1) for i in range(len(results))])
        for row, shade in zip(results, shades):
            sizes = {c[len("diameters."):]: number(v) for c, v in row.items() if c.startswith("diameters.")}
            pts = sorted((sizes[c[len(prefix):]], number(v)) for c, v in row.items()
                         if c.startswith(prefix) and number(v) is not None and c[len(prefix):] in sizes)
            if pts:
                ax.plot(*zip(*pts), marker="o", ms=4, color=shade, label=row["case"])
        ax.set_xscale("log")
        ax.set_xlabel("nominal diameter of the class (m)")
        ax.set_ylabel("mean height above the bed / d")
        ax.set_title("Segregation class by class in the deposit")
        ax.legend(fontsize=7)
        save(fig, out, "segregation_by_class", written)


# The thesis's numbers for the deposit figures of each size ratio.
DEPOSIT_FIGURES = {"8.33": "4_7", "4": "4_8", "3": "4_9", "2": "4_10"}


def study_frames(folder, out, results, minima, written, points_axes=()):
    """Fig. 3.4, a strip per case and the deposit figures, from the pictures in out/frames.
    Returns the per-case strips (path, case) for the report."""
    import matplotlib.image as mpimg
    import matplotlib.patches as mpatches

    path = os.path.join(out, "frames", "frames.json")
    if not os.path.exists(path):
        return []
    with open(path) as f:
        frames = {c["case"]: c for c in json.load(f)["cases"]}
    frame_dir = os.path.join(out, "frames")

    def picture(entry):
        base = os.path.join(frame_dir, entry["png"])
        with open(base[:-4] + ".json") as f:
            return mpimg.imread(base), json.load(f)

    def legend(fig, info, **kw):
        handles = [mpatches.Patch(color=e["color"], label=e["label"]) for e in info["legend"]]
        fig.legend(handles=handles, fontsize=8, frameon=False, **kw)

    def strip(case, title, name):
        c = frames[case]
        D = c["large_diameter"]
        pics = [picture(e) for e in c["strip"]]
        aspect = pics[0][0].shape[0] / pics[0][0].shape[1]
        fig, axes = plt.subplots(len(pics), 1, figsize=(8.0, 0.4 + len(pics) * (8.0 * aspect + 0.45)),
                                 squeeze=False, sharex=True)
        for k, (ax, (img, info)) in enumerate(zip(axes[:, 0], pics)):
            x0, x1, y0, y1 = (v / D for v in info["extent"])
            ax.imshow(img, extent=(x0, x1, y0, y1), interpolation="lanczos")
            ax.grid(False)
            when = f"at rest, t* = {info['t_star']:.0f}" if c["strip"][k]["at_rest"] else f"t* = {info['t_star']:.0f}"
            ax.set_title(f"{chr(ord('a') + k)}) {when}", loc="left", fontsize=9)
            ax.set_ylabel("y / D", fontsize=8)
            ax.tick_params(labelsize=7)
        axes[-1, 0].set_xlabel("x / D (0 at the foot of the incline)")
        legend(fig, pics[0][1], loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=min(3, len(pics[0][1]["legend"])))
        fig.suptitle(title, x=0.02, ha="left", fontsize=10)
        fig.tight_layout()
        return fig

    rows = {r["case"]: r for r in results}

    # The sweep's axes, as results.csv gives them: its columns between "case" and the first
    # number of the summaries (points.csv's before "n", and the seed).
    axes = [k for k in (list(results[0])[1:] if results else []) if k in ("ratio", "small_share", "seed") or
            (k in points_axes)]

    def label(case):
        r = rows.get(case, {})
        parts = []
        for k in axes:
            if k == "ratio":
                parts.append(f"D/d = {r[k]}")
            elif k == "small_share":
                parts.append(f"%A_p = {float(r[k]):g}")
            elif k == "seed":
                parts.append(f"seed {r[k]}")
            else:
                parts.append(f"{k} = {r[k]}")
        return ", ".join(parts) or case

    strips = []
    with_strip = [c for c in sorted(frames) if frames[c].get("strip")]
    strip_dir = os.path.join(out, "strips")
    for case in with_strip:
        os.makedirs(strip_dir, exist_ok=True)
        fig = strip(case, f"Flow sequence: {label(case)}", case)
        target = os.path.join(strip_dir, f"strip_{case}.png")
        fig.savefig(target + ".tmp", dpi=150, bbox_inches="tight", format="png")
        plt.close(fig)
        os.replace(target + ".tmp", target)
        strips.append((target, case))

    # Fig. 3.4 is the thesis's D/d = 8.33, 25 % case: the nearest one of this sweep.
    def distance(case):
        r = rows.get(case, {})
        ratio, share = number(r.get("ratio")), number(r.get("small_share"))
        return (abs(ratio - 8.33) if ratio is not None else 0, abs(share - 25) if share is not None else 0, case)

    if with_strip:
        best = min(with_strip, key=distance)
        fig = strip(best, f"Fig. 3.4: the avalanche down the incline, {label(best)}", best)
        save(fig, out, "fig3_4_flow_sequence", written)

    # Figs. 4.7-4.10: per D/d, the deposit at %A_p,m and at its neighbouring shares (the thesis
    # shows below, at and above the minimum), first seed, around the centroid (*).
    share_min = {row.split(",")[0]: number(row.split(",")[1]) for row in minima[1:]}
    by_ratio = defaultdict(dict)
    for case, c in frames.items():
        r = rows.get(case)
        if not r or "deposit" not in c or "small_share" not in r:
            continue
        share = float(r["small_share"])
        if not 0 < share < 100:
            continue  # one species: no basal layer to show
        seed = number(r.get("seed", "0")) or 0
        key = r.get("ratio", "—")
        if share not in by_ratio[key] or seed < by_ratio[key][share][0]:
            by_ratio[key][share] = (seed, case)
    def deposits(panels, title, name):
        """One panel per (title, case): the deposit around its centroid (*), the layer shaded."""
        pics = [(t, picture(frames[case]["deposit"]), frames[case]) for t, case in panels]
        heights = [p[1][0].shape[0] / p[1][0].shape[1] for p in pics]
        fig, axes_ = plt.subplots(len(pics), 1, figsize=(8.0, 0.6 + sum(8.0 * h + 0.5 for h in heights)),
                                  squeeze=False, gridspec_kw={"height_ratios": heights})
        for j, (ax, (t, (img, info), c)) in enumerate(zip(axes_[:, 0], pics)):
            D = c["large_diameter"]
            cx, cy = c["deposit"]["centroid"]
            x0, x1, y0, y1 = info["extent"]
            ax.imshow(img, extent=((x0 - cx) / D, (x1 - cx) / D, y0 / D, y1 / D), interpolation="lanczos")
            ax.plot([0], [cy / D], marker="*", ms=14, color="black", mec="white", mew=0.8, ls="none")
            ax.grid(False)
            ax.set_title(f"({chr(ord('a') + j)}) {t}", loc="left", fontsize=9)
            ax.set_ylabel("y / D", fontsize=8)
            ax.tick_params(labelsize=7)
        axes_[-1, 0].set_xlabel("(x − x_c) / D, from the deposit's centroid (*)")
        legend(fig, pics[0][1][1], loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=3)
        fig.suptitle(title, x=0.02, ha="left", fontsize=10)
        fig.tight_layout()
        save(fig, out, name, written)

    for ratio, cases in sorted(by_ratio.items(), key=lambda kv: ratio_key(kv[0])):
        shares = sorted(cases)
        m = share_min.get(ratio)
        k = shares.index(m) if m in shares else len(shares) // 2
        lo = max(0, min(k - 1, len(shares) - 3))
        panels = [(f"%A_p = {sh:g}" + (" = %A_p,m" if m is not None and sh == m else ""), cases[sh][1])
                  for sh in shares[lo:lo + 3]]
        number_ = DEPOSIT_FIGURES.get(ratio)
        head = f"Fig. {number_.replace('_', '.')}: " if number_ else ""
        which = f" for D/d = {ratio}" if number(ratio) is not None else ""
        clean = str(ratio).replace(".", "_")
        deposits(panels, f"{head}the deposit{which}, its basal layer of small discs highlighted",
                 f"fig{number_}_deposit_Dd{clean}" if number_ else
                 f"deposit_Dd{clean}" if number(ratio) is not None else "deposit")

    # A sweep not over %A_p: the deposits of the first seed along its first axis (up to four).
    if not by_ratio and points_axes:
        key = points_axes[0]
        first = {}
        for case, c in frames.items():
            r = rows.get(case)
            if not r or "deposit" not in c or number(r.get(key)) is None:
                continue
            seed = number(r.get("seed", "0")) or 0
            v = float(r[key])
            if v not in first or seed < first[v][0]:
                first[v] = (seed, case)
        chosen = sorted(first)[:4]
        if chosen:
            deposits([(f"{key} = {v:g}", first[v][1]) for v in chosen],
                     "The deposits around their centroids, the basal layer (smallest class) highlighted", "deposits")
    return strips


def report(folder, figures, points, results, pngs, minima, strips=()):
    """DIR/report.html: one page, readable offline (no fetches), with the table of points, every
    figure, and links to each case's files. Its script puts "images: LOADED/TOTAL" in the title
    once the page has loaded, which the test reads from headless Chromium."""
    import html

    rel = os.path.relpath(figures, folder)
    cols = [c for c in ("ratio", "small_share", "n", "mu_global_mean", "mu_global_2se", "peak_ek_over_ep0_mean",
                        "H_layer_over_d_mean", "final_basal_spin_mean") if points and c in points[0]]

    def fmt(v):
        x = number(v)
        return "" if x is None else (f"{x:.4g}" if not float(x).is_integer() else f"{x:g}")

    rows = "".join("<tr>" + "".join(f"<td>{html.escape(fmt(p[c]))}</td>" for c in cols) + "</tr>\n" for p in points)
    cases = "".join(
        f'<li><a href="cases/{html.escape(r["case"])}/summary.json">{html.escape(r["case"])}</a> '
        f'(<a href="cases/{html.escape(r["case"])}/timeseries.csv">time series</a>, '
        f'<a href="cases/{html.escape(r["case"])}/scene.resolved.toml">scene</a>): mu = {html.escape(fmt(r.get("mu_global")))}</li>\n'
        for r in results)
    strip_links = ("<p>The flow sequence of every case that kept its states: " + ", ".join(
        f'<a href="{html.escape(os.path.relpath(p, folder))}">{html.escape(c)}</a>' for p, c in strips) + ".</p>\n"
        if strips else "")
    images = "".join(f'<figure><img src="{html.escape(os.path.join(rel, os.path.basename(p)))}" alt="{html.escape(os.path.basename(p))}">'
                     f'<figcaption><a href="{html.escape(os.path.join(rel, os.path.basename(p)[:-4]))}.pdf">PDF</a></figcaption></figure>\n'
                     for p in pngs)
    head, *body = [line.split(",") for line in minima]
    minimum = ("<h2>Share of least friction %A_p,m</h2><div class=\"wide\"><table><tr>" +
               "".join(f"<th>{html.escape(c)}</th>" for c in head) + "</tr>" +
               "".join("<tr>" + "".join(f"<td>{html.escape(c)}</td>" for c in row) + "</tr>" for row in body) +
               "</table></div><p>at_edge = 1: the lowest mu is at the first or last share sampled, so the "
               "minimum may lie beyond it.</p>") if body else ""
    page = f"""<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>runout sweep</title>
<style>body{{font-family:sans-serif;max-width:1100px;margin:2em auto;color:#222}}
.wide{{overflow-x:auto}}table{{border-collapse:collapse;font-size:13px}}
td,th{{border:1px solid #ccc;padding:2px 8px;text-align:right}}
img{{max-width:100%}}figure{{margin:1em 0}}</style></head><body>
<h1>runout sweep: {html.escape(os.path.basename(os.path.abspath(folder)))}</h1>
<p>{len(results)} cases; points are cases that differ only in seed (mean, ±2 standard errors). Files:
<a href="results.csv">results.csv</a>, <a href="points.csv">points.csv</a>, <a href="timings.csv">timings.csv</a>,
<a href="sweep.toml">sweep.toml</a>, <a href="minimum.csv">minimum.csv</a>.</p>
<div class="wide"><table><tr>{"".join(f"<th>{html.escape(c)}</th>" for c in cols)}</tr>
{rows}</table></div>
{minimum}
<h2>Figures</h2>
{images}{strip_links}<h2>Cases</h2><ul>
{cases}</ul>
<script>
window.addEventListener("load", function () {{
  var all = document.images, ok = 0;
  for (var i = 0; i < all.length; i++) if (all[i].complete && all[i].naturalWidth > 0) ok++;
  document.title = "images: " + ok + "/" + all.length;
}});
</script>
</body></html>
"""
    path = os.path.join(folder, "report.html")
    with open(path + ".tmp", "w") as f:
        f.write(page)
    os.replace(path + ".tmp", path)
    print(path)


if __name__ == "__main__":
    main()
