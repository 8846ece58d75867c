#!/usr/bin/python3
"""Draws an example network, its road raster and the network traced back from the raster, side
by side, as PNG (used by bench/raster/run.sh). Dead ends of both networks are marked.
Usage: plot.py DSN EXAMPLE_QUERY RASTER_QUERY TRACED_QUERY TITLE OUT.png
EXAMPLE_QUERY and TRACED_QUERY return a geometry column geom; RASTER_QUERY one raster rast."""
import struct
import sys
from collections import Counter

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import psycopg

dsn, example_q, raster_q, traced_q, title, out = sys.argv[1:7]
conn = psycopg.connect(dsn)


def lines(query):
    rows = conn.execute(f"SELECT ST_AsBinary((ST_Dump(q.geom)).geom) FROM ({query}) AS q").fetchall()
    result = []
    for (wkb,) in rows:
        wkb = bytes(wkb)
        endian = "<" if wkb[0] == 1 else ">"
        n = struct.unpack(endian + "I", wkb[5:9])[0]
        result.append(np.frombuffer(wkb, dtype=np.dtype("f8").newbyteorder(endian), count=2 * n, offset=9).reshape(n, 2))
    return result


def draw(ax, query, label):
    parts = lines(query)
    ends = Counter()
    for xy in parts:
        ax.plot(xy[:, 0], xy[:, 1], color="#303030", lw=0.6)
        ends[tuple(np.round(xy[0], 3))] += 1
        ends[tuple(np.round(xy[-1], 3))] += 1
    dead = np.array([p for p, c in ends.items() if c == 1])
    if len(dead):
        ax.plot(dead[:, 0], dead[:, 1], "o", color="#c03030", ms=2.5)
    ax.set_title(f"{label}: {len(parts)} edges, {len(dead)} dead ends (red)", fontsize=9)
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    return ax.get_xlim(), ax.get_ylim()


fig, axes = plt.subplots(1, 3, figsize=(18, 6.5))
xlim, ylim = draw(axes[0], example_q, "example")
wkb, = conn.execute(f"SELECT ST_AsBinary(q.rast) FROM ({raster_q}) AS q").fetchone()
wkb = bytes(wkb)
endian = "<" if wkb[0] == 1 else ">"
_, _, sx, sy, ipx, ipy, _, _, _, w, h = struct.unpack(endian + "HHdddddd" + "iHH", wkb[1:61])
img = np.frombuffer(wkb, dtype=np.uint8, count=w * h, offset=63).reshape(h, w)
axes[1].imshow(img, cmap="Greys", extent=(ipx, ipx + w * sx, ipy + h * sy, ipy), interpolation="nearest")
axes[1].set_title(f"road raster: {w} x {h} px of {sx:g} m (streetgen.rasterise_network)", fontsize=9)
axes[1].set_xticks([])
axes[1].set_yticks([])
draw(axes[2], traced_q, "traced (streetgen.raster_to_network)")
for ax in axes:
    ax.set_xlim(xlim)
    ax.set_ylim(ylim)
fig.suptitle(title, fontsize=10)
fig.text(0.01, 0.01, "Road data: © OpenStreetMap contributors, ODbL 1.0 (examples of Nishida et al. 2016)", fontsize=7)
fig.tight_layout(rect=(0, 0.03, 1, 0.97))
fig.savefig(out, dpi=110)
