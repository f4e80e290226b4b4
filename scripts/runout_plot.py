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
can be copied and edited, with the two it imports from its own folder: runout_plot_figures.py
(the figures from the tables, the helpers) and runout_plot_frames.py (the figures from the
pictures); copy all three.
"""
import argparse
import os
import sys

# The figure modules sit beside this script, in the source tree, beside the binary in the build
# tree and in share/runout: found from the script's own folder whatever the working directory,
# also under PYTHONSAFEPATH (which leaves that folder off sys.path). No __pycache__ is written
# into those folders (a source tree, an installed share/runout).
sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))
sys.dont_write_bytecode = True
try:
    from runout_plot_figures import number, other_figures, plt, read_csv, study, thesis_figures
    from runout_plot_frames import study_frames
except ModuleNotFoundError as e:
    if e.name not in ("runout_plot_figures", "runout_plot_frames"):
        raise
    sys.exit(f"runout plot: {e.name}.py is not beside {os.path.realpath(__file__)}: copy it with the script")


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
