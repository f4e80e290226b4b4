"""The figures of `runout plot` drawn from the sweep's tables (figs. 4.1, 4.2, 4.3, 4.14, 4.15,
4.16, a sweep not over %A_p, the accuracy study), and the helpers every figure uses: runout_plot.py
imports them. Restyle freely, as runout_plot.py says."""
import csv
import math
import os
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
