#!/usr/bin/python3
"""The speed-up of each turn of `runout bench --against-threads M --turn-log FILE` against the
host's cache-line round trip read around it (docs/performance.md, issue 11).

On VMs whose vCPUs the host moves, the round trip between two threads swings between a fast and
a slow state, and a two-thread step's speed-up with it. This reads one or more turn logs, prints
the median speed-up of the turns whose round trips before and after both lie under --fast-below
ns, of those whose both lie over --slow-above ns, and of the rest, and with --out draws every turn.
Logs that hold two threads' arithmetic over one's (arithmetic_pair_speedup_*) are also split by it:
two cores' worth (both reads at least --two-cores), one core's (both at most --one-core: the host
has put the two threads on one core's hyperthreads, where nothing can gain ×1.85), and between.

  /usr/bin/python3 scripts/turn_log_plot.py turns_*.csv [--out FIG.png] [--fast-below 250] [--slow-above 400]
      [--two-cores 1.8] [--one-core 1.3]
"""
import argparse
import csv
import math
import signal
import statistics
import sys
from typing import NamedTuple


class Turn(NamedTuple):
    trip_before: float  # ns
    trip_after: float  # ns
    speedup: float  # seconds at M threads over seconds at N
    ms_n: float  # ms per 1,000 steps at N threads (--threads)
    ms_m: float  # ms per 1,000 steps at M threads (--against-threads)
    lockstep: float  # copies alone over in lockstep; NaN without bench --ceiling
    pair_before: float  # two threads' arithmetic over one's; NaN in logs from before it was read
    pair_after: float

    @property
    def trip(self):  # the larger round trip around the turn: what the drawing's x is
        return max(self.trip_before, self.trip_after)

    @property
    def pair(self):  # the smaller arithmetic read around the turn: what the classes and the third panel use
        return min(self.pair_before, self.pair_after)


def read_turns(paths):
    turns = []
    for path in paths:
        with open(path, newline="") as f:
            for line, row in enumerate(csv.DictReader(f), start=2):
                try:
                    if not row["line_round_trip_ns_before"] or not row["line_round_trip_ns_after"]:
                        sys.exit(f"{path}:{line}: no round trip (a run at one thread?)")
                    thousands = float(row["steps"]) / 1000
                    turns.append(Turn(float(row["line_round_trip_ns_before"]), float(row["line_round_trip_ns_after"]),
                                      float(row["speedup"]), float(row["seconds"]) / thousands * 1e3,
                                      float(row["against_seconds"]) / thousands * 1e3,
                                      float(row.get("ceiling_lockstep_speedup") or "nan"),
                                      float(row.get("arithmetic_pair_speedup_before") or "nan"),
                                      float(row.get("arithmetic_pair_speedup_after") or "nan")))
                except (KeyError, TypeError, ValueError, ZeroDivisionError) as e:
                    sys.exit(f"{path}:{line}: not a row of runout bench --turn-log ({type(e).__name__}: {e})")
    return turns


# The host's line round trip, in ns, under which a turn met its fast state and over which its
# slow one (docs/performance.md, "Two threads"); scripts/thread_scaling.sh splits its rounds by
# the same edges.
FAST_BELOW_NS = 250
SLOW_ABOVE_NS = 400


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("logs", nargs="+", help="CSV files written by runout bench --turn-log")
    ap.add_argument("--out", help="draw the turns to this PNG, PDF or SVG")
    ap.add_argument("--fast-below", type=float, default=FAST_BELOW_NS, help=f"ns (default {FAST_BELOW_NS})")
    ap.add_argument("--slow-above", type=float, default=SLOW_ABOVE_NS, help=f"ns (default {SLOW_ABOVE_NS})")
    ap.add_argument("--two-cores", type=float, default=1.8, help="arithmetic pair speed-up (default 1.8)")
    ap.add_argument("--one-core", type=float, default=1.3, help="arithmetic pair speed-up (default 1.3)")
    ap.add_argument("--target", type=float, default=1.85, help="speed-up line to draw (default 1.85)")
    a = ap.parse_args()
    if not a.fast_below < a.slow_above:
        sys.exit("--fast-below must be under --slow-above")
    if not a.one_core < a.two_cores:
        sys.exit("--one-core must be under --two-cores")
    turns = read_turns(a.logs)
    if not turns:
        sys.exit("no turns in " + ", ".join(a.logs))
    fast, slow = f"fast (both < {a.fast_below:g} ns)", f"slow (both > {a.slow_above:g} ns)"

    def trip_class(t):
        return fast if t.trip < a.fast_below else slow if min(t.trip_before, t.trip_after) > a.slow_above else "between"

    classes = {fast: [], slow: [], "between": []}
    for t in turns:
        classes[trip_class(t)].append(t)
    # A turn whose M-thread side the host slowed has a speed-up lifted by it, not earned: the
    # same medians again over the turns whose M-thread side ran at full speed.
    m_side = [t.ms_m for t in turns]
    full = 1.1 * (statistics.quantiles(m_side, n=10)[0] if len(m_side) > 1 else m_side[0])

    def summary(ts):
        s = [t.speedup for t in ts]
        if len(s) < 2:
            return f"{len(s)} turn(s)" + (f", speed-up {s[0]:.3f}" if s else "")
        q = statistics.quantiles(s, n=4)
        copies = [t for t in ts if not math.isnan(t.lockstep)]
        return (f"{len(s)} turns, speed-up median {statistics.median(s):.3f}, quartiles {q[0]:.3f}–{q[2]:.3f}, "
                f"{sum(v >= a.target for v in s) / len(s):.0%} ≥ {a.target:g}"
                + (f"; copies in lockstep median {statistics.median(t.lockstep for t in copies):.3f}, "
                   f"the step over them turn by turn {statistics.median(t.speedup / t.lockstep for t in copies):.3f}"
                   if copies else ""))

    print(f"turns: {len(turns)}")
    for name, ts in classes.items():
        print(f"{name}: {summary(ts)}")
    print(f"with the M-thread side at full speed (at most {full:.1f} ms per 1,000 steps: 1.1 × its 10th percentile):")
    for name, ts in classes.items():
        print(f"  {name}: {summary([t for t in ts if t.ms_m <= full])}")
    paired = [t for t in turns if not math.isnan(t.pair_before) and not math.isnan(t.pair_after)]
    two_cores, one_core = f"two cores' worth (both ≥ {a.two_cores:g})", f"one core's (both ≤ {a.one_core:g})"

    def pair_class(t):
        return two_cores if t.pair >= a.two_cores else one_core if max(t.pair_before, t.pair_after) <= a.one_core else "between"

    if paired:
        print("by two threads' arithmetic over one's, read before and after the turn:")
        for name in (two_cores, one_core, "between"):
            print(f"  {name}: {summary([t for t in paired if pair_class(t) == name])}")
        # Where the host gave two cores, what the round trip still costs.
        for name in classes:
            ts = [t for t in paired if pair_class(t) == two_cores and trip_class(t) == name]
            print(f"  {two_cores}, round trip {name}: {summary(ts)}")
    if a.out:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        import matplotlib.ticker
        fig, axes = plt.subplots(1, 3 if paired else 2, figsize=(18 if paired else 12, 4.8), dpi=150)
        ax, bx = axes[0], axes[1]
        colours = dict(zip(classes, ["tab:blue", "tab:red", "tab:gray"]))
        for name, ts in classes.items():
            if ts:
                ax.scatter([t.trip for t in ts], [t.speedup for t in ts], s=9, alpha=0.5, color=colours[name],
                           label=f"{name}: {len(ts)} turns, median {statistics.median(t.speedup for t in ts):.2f}")
                bx.scatter([t.ms_m for t in ts], [t.ms_n for t in ts], s=9, alpha=0.5, color=colours[name], label=name)
        ax.axhline(a.target, color="black", lw=0.8, ls="--", label=f"target ×{a.target:g}")
        ax.set_xscale("log")
        trips = [t.trip for t in turns]
        wide = math.log10(max(trips) / min(trips)) > 2  # a host stall of a millisecond stretches the axis
        ax.xaxis.set_major_locator(matplotlib.ticker.LogLocator(subs=(1,) if wide else (1, 2, 5)))
        ax.xaxis.set_major_formatter(matplotlib.ticker.StrMethodFormatter("{x:,.0f}"))
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.set_xlabel("line round trip, the larger of before and after the turn (ns)")
        ax.set_ylabel("turn's speed-up (seconds at M threads / at N)")
        ax.set_title("Speed-up of each turn against the host's round trip", fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7, loc="lower left")
        # Right: each turn's two sides, so a speed-up lifted by a slow M-thread side shows as such.
        xs, ys = [t.ms_m for t in turns], [t.ms_n for t in turns]
        # The middle 99 % of turns: a turn the host stopped for seconds would squash the rest.
        def span(v):
            q = statistics.quantiles(v, n=200) if len(v) > 1 else [v[0], v[0]]
            return q[0] * 0.97, q[-1] * 1.03
        (xlo, xhi), (ylo, yhi) = span(xs), span(ys)
        for ratio, style in ((a.target, "--"), (2.0, "-.")):
            bx.plot([xlo, xhi], [xlo / ratio, xhi / ratio], color="black", lw=0.8, ls=style, label=f"speed-up ×{ratio:g}")
        bx.set_xlim(xlo, xhi)
        bx.set_ylim(ylo, yhi)
        bx.set_xlabel("ms per 1,000 steps at M threads (--against-threads)")
        bx.set_ylabel("ms per 1,000 steps at N threads (--threads)")
        bx.set_title("Each turn's two sides (below a line: faster than its speed-up)", fontsize=10)
        bx.grid(True, which="both", alpha=0.3)
        bx.legend(fontsize=7, loc="upper left")
        if paired:
            # Third: each turn against what the host gave two threads' arithmetic around it.
            cx = axes[2]
            for name in classes:
                ts = [t for t in paired if trip_class(t) == name]
                if ts:
                    cx.scatter([t.pair for t in ts], [t.speedup for t in ts], s=9,
                               alpha=0.5, color=colours[name], label=name)
            cx.axhline(a.target, color="black", lw=0.8, ls="--", label=f"target ×{a.target:g}")
            for edge in (a.one_core, a.two_cores):
                cx.axvline(edge, color="black", lw=0.6, ls=":")
            cx.set_xlabel("two threads' arithmetic over one's, the smaller of before and after")
            cx.set_ylabel("turn's speed-up (seconds at M threads / at N)")
            cx.set_title("Speed-up against what the host gave two threads", fontsize=10)
            cx.grid(True, alpha=0.3)
            cx.legend(fontsize=7, loc="upper left")
        fig.suptitle("runout bench --turn-log: " + ", ".join(a.logs) if len(a.logs) < 3 else
                     f"runout bench --turn-log: {len(a.logs)} runs, {len(turns)} turns", fontsize=11)
        fig.tight_layout()
        fig.savefig(a.out)
        print(f"drawn: {a.out}")


if __name__ == "__main__":
    # Piped into head, end quietly as other commands do, not with a BrokenPipeError.
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)
    main()
