"""Re-encodes PNG files in place with a 256-colour palette (Pillow's fast octree,
no dithering), so that the viewer's screenshots in docs/ stay under 400 KB: a heat
map of scallops at full colour depth does not compress.

Usage: python3 palette.py PNG...
"""

import sys

from PIL import Image

for path in sys.argv[1:]:
    image = Image.open(path).convert("RGB")
    image.quantize(colors=256, method=Image.Quantize.FASTOCTREE, dither=Image.Dither.NONE).save(
        path, optimize=True
    )
    print(f"palette: {path}")
