#!/usr/bin/python3
"""Renders part of a generated model to PNG: axes, sections, intersections (coloured by status),
corner arcs. A development aid for looking at what generate() made.

  PGHOST=... PGPORT=... /usr/bin/python3 tools/plot_model.py DB MODEL OUT.png [--node ID | --bbox x0 y0 x1 y1] [--radius M]

Needs Debian's python3-psycopg, python3-shapely and python3-matplotlib.
Road data in the pictures: (c) OpenStreetMap contributors, ODbL 1.0.
"""
import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import psycopg  # noqa: E402
from shapely import wkb  # noqa: E402

STATUS_COLOURS = {"ok": "#9ecae1", "transition": "#a1d99b", "narrowed": "#fdae6b", "fallback": "#fb6a4a",
                  "repaired": "#fcbba1"}


def draw_polygon(ax, geom, **kw):
    polys = getattr(geom, "geoms", [geom])
    for p in polys:
        x, y = p.exterior.xy
        ax.fill(x, y, **kw)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("db")
    ap.add_argument("model")
    ap.add_argument("out")
    ap.add_argument("--node", type=int)
    ap.add_argument("--bbox", type=float, nargs=4)
    ap.add_argument("--radius", type=float, default=80.0)
    a = ap.parse_args()
    with psycopg.connect(dbname=a.db) as conn:
        cur = conn.cursor()
        m = a.model
        if a.node is not None:
            cur.execute(f"SELECT ST_Expand(geom, %s) FROM {m}.node WHERE id = %s", (a.radius, a.node))
        elif a.bbox:
            cur.execute(f"SELECT ST_SetSRID(ST_MakeEnvelope(%s, %s, %s, %s), ST_SRID(geom)) FROM {m}.axis LIMIT 1", a.bbox)
        else:
            cur.execute(f"SELECT ST_Extent(geom)::geometry FROM {m}.axis")
        box = cur.fetchone()[0]
        fig, ax = plt.subplots(figsize=(12, 12))
        cur.execute(f"SELECT ST_AsBinary(geom) FROM {m}.section WHERE geom && %s::geometry", (box,))
        for (g,) in cur.fetchall():
            draw_polygon(ax, wkb.loads(g), facecolor="#d9d9d9", edgecolor="#636363", linewidth=0.4)
        cur.execute(f"SELECT status, ST_AsBinary(geom) FROM {m}.intersection WHERE geom && %s::geometry", (box,))
        for status, g in cur.fetchall():
            draw_polygon(ax, wkb.loads(g), facecolor=STATUS_COLOURS.get(status, "#756bb1"), edgecolor="#08519c", linewidth=0.5)
        cur.execute(f"SELECT ST_AsBinary(arc_segmentized) FROM {m}.corner WHERE arc_segmentized && %s::geometry", (box,))
        for (g,) in cur.fetchall():
            x, y = wkb.loads(g).xy
            ax.plot(x, y, color="#e6550d", linewidth=1.2)
        cur.execute(f"SELECT ST_AsBinary(geom) FROM {m}.axis WHERE geom && %s::geometry", (box,))
        for (g,) in cur.fetchall():
            x, y = wkb.loads(g).xy
            ax.plot(x, y, color="black", linewidth=0.5, linestyle="--")
        xmin, ymin, xmax, ymax = wkb.loads(cur.execute("SELECT ST_AsBinary(%s::geometry)", (box,)).fetchone()[0]).bounds
        ax.set_xlim(xmin, xmax)
        ax.set_ylim(ymin, ymax)
        ax.set_aspect("equal")
        ax.set_title(f"{m}: sections (grey), intersections by status, arcs (orange)  -  (c) OpenStreetMap contributors")
        fig.savefig(a.out, dpi=110, bbox_inches="tight")


if __name__ == "__main__":
    main()
