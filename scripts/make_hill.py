#!/usr/bin/env python3
"""Writes samples/terrain/hill.asc: a synthetic ESRI ASCII grid made by the project (two
hills, a saddle and a valley, 800 m a side at 5 m cells, heights in metres), small enough
that trees of real size show their brushwork in samples/scenes/grove.json."""
import math
import pathlib

N, CELL = 160, 5.0


def height(i, j):
    u, v = i / N, j / N
    z = 120.0 * math.exp(-((u - 0.35) ** 2 / 0.03 + (v - 0.6) ** 2 / 0.08))
    z += 90.0 * math.exp(-((u - 0.75) ** 2 / 0.02 + (v - 0.4) ** 2 / 0.05))
    z += 25.0 * math.sin(u * 11.0 + 1.3) * math.sin(v * 9.0 + 0.4)
    return z + 40.0 * v


def main():
    out = pathlib.Path(__file__).resolve().parent.parent / "samples" / "terrain" / "hill.asc"
    rows = [f"ncols {N}", f"nrows {N}", "xllcorner 0", "yllcorner 0", f"cellsize {CELL}", "NODATA_value -9999"]
    for j in range(N):  # the first row is the northernmost
        rows.append(" ".join("%.1f" % height(i, N - 1 - j) for i in range(N)))
    out.write_text("\n".join(rows) + "\n")
    print(out)


if __name__ == "__main__":
    main()
