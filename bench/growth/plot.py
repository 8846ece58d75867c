#!/usr/bin/python3
"""Draws an example patch beside a network grown from it, as PNG (used by bench/growth/run.sh).
Usage: plot.py DSN EXAMPLE_QUERY GROWN_QUERY TITLE OUT.png
Each query returns rows (geom_wkt text, road_class text)."""
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import psycopg2

dsn, example_q, grown_q, title, out = sys.argv[1:6]
conn = psycopg2.connect(dsn)


def draw(ax, query, label):
    cur = conn.cursor()
    cur.execute(f"SELECT ST_AsText(q.geom), q.road_class FROM ({query}) AS q")
    for wkt, cls in cur.fetchall():
        for part in wkt.replace("MULTILINESTRING", "").replace("LINESTRING", "").strip("() ").split("),("):
            pts = [tuple(map(float, p.split())) for p in part.strip("()").split(",")]
            xs, ys = zip(*pts)
            ax.plot(xs, ys, color="#b03030" if cls == "avenue" else "#303030", lw=1.2 if cls == "avenue" else 0.5)
    ax.set_aspect("equal")
    ax.set_title(label, fontsize=9)
    ax.set_xticks([])
    ax.set_yticks([])


fig, axes = plt.subplots(1, 2, figsize=(12, 6))
draw(axes[0], example_q, "example")
draw(axes[1], grown_q, "grown (streetgen.grow_example)")
fig.suptitle(title, fontsize=10)
fig.text(0.01, 0.01, "Road data: © OpenStreetMap contributors, ODbL 1.0 (examples of Nishida et al. 2016)", fontsize=7)
fig.savefig(out, dpi=110)
