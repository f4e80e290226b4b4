"""The figures of `runout plot` laid out from the study's pictures (fig. 3.4, a strip per case, the
deposit figures 4.7-4.10), which `runout plot` draws first into FIGDIR/frames: runout_plot.py
imports them. Restyle freely, as runout_plot.py says."""
import json
import os
from collections import defaultdict

from runout_plot_figures import number, plt, ratio_key, save


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
