#!/usr/bin/env python3
"""Writes examples/thesis_<D/d>_<%A_p>.toml, one scene per row of the thesis's table 3.1
(SPEC §5). Run from the repository root: python3 scripts/make_thesis_scenes.py"""

ROWS = [  # (label, small diameter d in metres, %A_p) with D = 1 m
    ("8_33", 0.12, 0), ("8_33", 0.12, 10), ("8_33", 0.12, 25), ("8_33", 0.12, 50),
    ("4", 0.25, 10), ("4", 0.25, 40), ("4", 0.25, 100),
    ("3", 1.0 / 3.0, 10), ("3", 1.0 / 3.0, 60), ("3", 1.0 / 3.0, 100),
    ("2", 0.5, 10), ("2", 0.5, 50), ("2", 0.5, 90),
]

TEMPLATE = """# Thesis scene (SPEC §5, table 3.1): D/d = {ratio}, %A_p = {pct}.
# Total disc area = 500 large discs (392.7 m^2); 30 degree incline, 50 D from gate to foot.
# Run it: runout run examples/{name}.toml --out out/{name}
name = "{name}"

[species.large]
diameter = 1.0
spread = 0.1
area_share = {large_share}

[species.small]
diameter = {d!r}
spread = 0.1
area_share = {small_share}

[avalanche]
incline_angle = 30.0
incline_length = 50.0
pile_width = 20.0
floor_length = 250.0
wall_height = 60.0
reference_large_count = 500

[preparation]
seed = 1

[rest]
ek_threshold = 1e-5
hold = 5.0
max_time = 2000.0
"""

for label, d, pct in ROWS:
    name = f"thesis_{label}_{pct}"
    text = TEMPLATE.format(ratio=label.replace("_", "."), pct=pct, name=name, d=d,
                           large_share=round(1 - pct / 100, 10), small_share=pct / 100)
    with open(f"examples/{name}.toml", "w") as f:
        f.write(text)
    print("wrote", f"examples/{name}.toml")
