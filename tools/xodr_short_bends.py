#!/usr/bin/env python3
"""Counts the short bends in an OpenDRIVE file's connecting roads: elevation pieces shorter than
0.5 m whose grade turns by more than 5 % (and 2 %) over the piece, a sub-metre kink a vehicle
feels as a jolt. Prints the counts and the five worst (grade turned, road, junction, s, length).

    python3 tools/xodr_short_bends.py out/NAME.xodr
"""
import re
import sys


def main(path):
    text = open(path, encoding="utf-8").read()
    bends = []
    road = re.compile(r'<road name="connection[^"]*" length="([\d.]+)" id="(\d+)" junction="(\d+)">')
    piece = re.compile(r'<elevation s="([\d.e+-]+)" a="[^"]+" b="([^"]+)" c="([^"]+)" d="([^"]+)"')
    for m in road.finditer(text):
        end = text.index("</road>", m.end())
        pieces = piece.findall(text[m.end():end])
        length = float(m.group(1))
        for k, (s, _b, c, d) in enumerate(pieces):
            s, c, d = float(s), float(c), float(d)
            h = (float(pieces[k + 1][0]) if k + 1 < len(pieces) else length) - s
            if h < 0.5:
                bends.append((abs(2 * c * h + 3 * d * h * h), m.group(2), m.group(3), s, h))
    bends.sort(reverse=True)
    print(f"{path}: connecting-road elevation pieces under 0.5 m turning the grade by more than 5 %: "
          f"{sum(1 for b in bends if b[0] > 0.05)}, by more than 2 %: {sum(1 for b in bends if b[0] > 0.02)}")
    for g, r, j, s, h in bends[:5]:
        print(f"  {100 * g:.1f} % on road {r} (junction {j}) at s = {s:.3f} m over {h:.4f} m")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: xodr_short_bends.py FILE.xodr")
    main(sys.argv[1])
