#!/usr/bin/env bash
# The screenshots of docs/images/ (docs/tutorials.dox, "What the windows show"): the AprilTag tutorial run with its
# display on in an X server of its own (Xvfb, 24-bit screen) and -c, its windows as it saved them
# (vpDisplay::getImage(): stereo-start.png, stereo-end.png, plot.png), the pictures without their last 60 rows (empty),
# all reduced to a palette of the overlay's colours and 20 greys (Debian's python3-pil) to stay small.
# Usage: scripts/make-doc-screenshots.sh [BUILD_DIR (default build)]
set -euo pipefail
repo="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$repo/build}"
tutorial="$build/tutorials/tutorial-projective-servo-apriltag"
[ -x "$tutorial" ] || { echo "no $tutorial: build the tutorials first" >&2; exit 1; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
xvfb-run -a -s "-screen 0 1600x1200x24" "$tutorial" -c --output "$work" > "$work/out.txt"
tail -n 1 "$work/out.txt"
/usr/bin/python3 - "$work" "$repo/docs/images" <<'PYTHON'
import sys
from PIL import Image
work, images = sys.argv[1], sys.argv[2]
# The overlay's colours exactly (vpColor's yellow, red, green, blue, white, black, the gap's grey and the plot's
# curves), 20 greys for the images.
colours = [(255, 255, 0), (255, 0, 0), (0, 255, 0), (0, 0, 255), (255, 255, 255), (0, 0, 0), (40, 40, 40),
           (0, 255, 255), (255, 165, 0), (128, 0, 128)] + [(g, g, g) for g in range(0, 256, 13)]
palette = Image.new("P", (1, 1))
palette.putpalette([c for rgb in colours for c in rgb] + [0] * (3 * (256 - len(colours))))
for name, box in (("stereo-start", (0, 0, 1290, 420)), ("stereo-end", (0, 0, 1290, 420)), ("plot", None)):
    picture = Image.open(f"{work}/{name}.png").convert("RGB")
    if box is not None:
        picture = picture.crop(box)
    picture.quantize(palette=palette, dither=Image.Dither.NONE).save(f"{images}/apriltag-{name}.png", optimize=True)
    print(f"{images}/apriltag-{name}.png", picture.size)
PYTHON
