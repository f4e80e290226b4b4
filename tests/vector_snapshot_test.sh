#!/usr/bin/env bash
# PDF and SVG pictures (--snapshot-format, runout render -o X.pdf/.svg) against the PNG of the
# same state: the PDF rasterised by poppler (pdftoppm), the SVG by librsvg (rsvg-convert), both
# at the PNG's pixel size (one PDF point / SVG unit per pixel) and compared through
# `runout compare`. Only anti-aliasing and glyph rasterisation differ: measured on the quick
# pile at t* = 20 (deposit camera, 640x360), 0.13-0.28 % of the pixels differ by more than
# 64/255 in a channel (edges of discs, walls and glyphs), so the pictures must match at
# --tolerance 64 --max-share 0.006; a picture in another colour mode differs in 4.6-5.1 % and
# must not match. Text must
# stay text (pdftotext reads it; the SVG has <text> elements) and every disc a circle.
# Usage: vector_snapshot_test.sh RUNOUT_BINARY SOURCE_DIR
set -uo pipefail
bin=$1 src=$2
source "$src/tests/lib.sh"
for tool in pdftoppm pdftotext rsvg-convert; do
  command -v $tool >/dev/null || { echo "FAIL: $tool is not installed (poppler-utils, librsvg2-bin)"; exit 1; }
done
if [ ! -e "$(dirname "$bin")/runout_pictures.so" ]; then echo "no picture module: skipped"; exit 77; fi
look=(--size 640x360 --camera deposit --color spin --spokes --outlines)
match=(--tolerance 64 --max-share 0.006)

# A run's snapshot as PDF, and its state drawn as PNG with the same options.
"$bin" run "$src/examples/quick.toml" --out "$work/run" -q --threads 1 --cache-dir "$work/cache" \
  --snapshots 20 --end-at-last-snapshot --states 20 --snapshot-format pdf "${look[@]}" >/dev/null || bad "run"
state=$work/run/states/state_t0020.00.bin
[ -s "$work/run/snapshot_t20.pdf" ] && ok || bad "no snapshot_t20.pdf: $(ls "$work/run")"
"$bin" render "$state" -o "$work/spin.png" "${look[@]}" 2>/dev/null || bad "render png"
pdftoppm -png -r 72 -singlefile "$work/run/snapshot_t20.pdf" "$work/spin_pdf"
"$bin" compare "$work/spin.png" "$work/spin_pdf.png" "${match[@]}" --diff "$work/spin_pdf_diff.png" >"$work/c1" &&
  ok || bad "the PDF snapshot does not match the PNG: $(tr '\n' ' ' <"$work/c1")"
# pdftotext reads the overlays back: the t* stamp and the colour bar's title are text.
text=$(pdftotext "$work/run/snapshot_t20.pdf" -)
grep -q "t\* = 20.0" <<<"$text" && grep -q "ω √(d/g)" <<<"$text" && ok || bad "PDF text: $text"

# SVG (species legend) and PDF (basal layer) of the same state through runout render.
for mode in species layer; do
  for fmt in png pdf svg; do
    "$bin" render "$state" -o "$work/$mode.$fmt" --size 640x360 --camera deposit --color $mode 2>/dev/null ||
      bad "render $mode.$fmt"
  done
  pdftoppm -png -r 72 -singlefile "$work/$mode.pdf" "$work/${mode}_pdf"
  rsvg-convert "$work/$mode.svg" -o "$work/${mode}_svg.png"
  for fmt in pdf svg; do
    "$bin" compare "$work/$mode.png" "$work/${mode}_$fmt.png" "${match[@]}" >"$work/c" &&
      ok || bad "$mode.$fmt does not match $mode.png: $(tr '\n' ' ' <"$work/c")"
  done
done
# The comparison tells pictures apart: another colour mode's PDF does not match.
"$bin" compare "$work/species.png" "$work/spin_pdf.png" "${match[@]}" >/dev/null; rc=$?
[ $rc -eq 1 ] && ok || bad "the spin PDF matched the species PNG (exit $rc)"

# The SVG is XML with a circle per disc and per legend swatch and its labels as <text>.
/usr/bin/python3 - "$work/species.svg" "$work/run/summary.json" <<'PY' && ok || bad "species.svg"
import json, sys, xml.etree.ElementTree as ET
ns = "{http://www.w3.org/2000/svg}"
svg = ET.parse(sys.argv[1]).getroot()
s = json.load(open(sys.argv[2]))
circles = svg.findall(f"{ns}circle")
texts = [t.text for t in svg.findall(f"{ns}text")]
discs = s["n_large"] + s["n_small"]
assert len(circles) == discs + 2, (len(circles), discs)  # + the two legend swatches
assert "t* = 20.0" in texts and "large, D = 1 m" in texts and "small, d = 0.5 m" in texts, texts
assert svg.get("width") == "640" and svg.get("height") == "360", svg.attrib
PY

# The same frame gives the same bytes (no creation date in the PDF).
"$bin" render "$state" -o "$work/again.pdf" --size 640x360 --camera deposit --color layer 2>/dev/null
cmp -s "$work/layer.pdf" "$work/again.pdf" && ok || bad "two renders of one state give different PDFs"

# Bad input: refused with exit 2 before anything is written.
out=$("$bin" render "$state" -o "$work/x.png" --snapshot-format pdf 2>&1); rc=$?
[ $rc -eq 2 ] && grep -q -- "--snapshot-format pdf but -o $work/x.png names a png file" <<<"$out" && [ ! -e "$work/x.png" ] &&
  ok || bad "format against extension: exit $rc: $out"
out=$("$bin" run "$src/examples/quick.toml" --out "$work/bad" -q --snapshots 1 --snapshot-format bmp 2>&1); rc=$?
[ $rc -eq 2 ] && grep -q -- "--snapshot-format: bmp not in {png,pdf,svg}" <<<"$out" && [ ! -e "$work/bad" ] &&
  ok || bad "--snapshot-format bmp: exit $rc: $out"

finish
