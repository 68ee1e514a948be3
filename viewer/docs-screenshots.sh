#!/usr/bin/env bash
# Writes the viewer's screenshots in docs/ (docs/view-wave.png, view-die.png,
# view-sequence.png): the views of the iso-scallop program of wave, the die's
# gouge-free lead and the stock-to-part sequence (after its finish), shot in
# headless Chromium and re-encoded with a palette (palette.py, Pillow).
# Usage (from viewer/, after npm ci): ./docs-screenshots.sh [SWARF]
set -euo pipefail
swarf=${1:-../target/debug/swarf}
views=$(mktemp -d)
trap 'rm -rf "$views"' EXIT
"$swarf" view --job ../jobs/wave-iso-scallop.toml --max-vertices 900000 -o "$views/wave" >/dev/null
"$swarf" view --job ../jobs/die-gouge-free.toml -o "$views/die" >/dev/null
"$swarf" view --job ../jobs/fillet-pocket-sequence.toml -o "$views/sequence" >/dev/null
size=1100x700
node screenshot.mjs "$views/wave" ../docs/view-wave.png --size $size --hide cuts,links,rapids,cutter \
  --zoom 0.45 --measure 0.45,0.4,0.8,0.62
node screenshot.mjs "$views/die" ../docs/view-die.png --size $size --hide links,rapids,'tool axes',cutter
node screenshot.mjs "$views/sequence" ../docs/view-sequence.png --size $size --operation 2 --motion 11500 \
  --hide links,rapids,cuts
python3 palette.py ../docs/view-wave.png ../docs/view-die.png ../docs/view-sequence.png
node test/screenshots.mjs ../docs/view-wave.png ../docs/view-die.png ../docs/view-sequence.png
