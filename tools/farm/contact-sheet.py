#!/usr/bin/env python3
"""Contact sheet of rendered frames for docs/farm.md: the frames in a grid, each labelled
with its number, as one JPEG. Needs Pillow (pip install pillow).

Usage: tools/farm/contact-sheet.py OUT.jpg COLUMNS FRAME.png...   (frames named NAME-0001.png)
"""
import re
import sys

from PIL import Image, ImageDraw


def main() -> None:
    out, columns, frames = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
    images = [Image.open(f).convert("RGB") for f in frames]
    w, h = images[0].size
    gap = 4
    rows = -(-len(images) // columns)
    sheet = Image.new("RGB", (columns * (w + gap) + gap, rows * (h + gap) + gap), (24, 24, 24))
    draw = ImageDraw.Draw(sheet)
    for k, (name, image) in enumerate(zip(frames, images)):
        x, y = gap + (k % columns) * (w + gap), gap + (k // columns) * (h + gap)
        sheet.paste(image, (x, y))
        number = re.search(r"-(\d+)\.png$", name)
        label = f"frame {int(number.group(1))}" if number else name
        draw.text((x + 5, y + 4), label, fill=(0, 0, 0))
        draw.text((x + 4, y + 3), label, fill=(255, 255, 255))
    sheet.save(out, quality=88)


if __name__ == "__main__":
    main()
