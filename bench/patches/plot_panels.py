#!/usr/bin/python3
"""Draws networks side by side as one PNG (used by bench/patches/pictures.sh).

  plot_panels.py DSN OUT.png TITLE "PANEL TITLE|QUERY" ["PANEL TITLE|QUERY" ...]

Each query returns rows (geom geometry, kind text); kind picks the style: a (first example or
style), b (second), parametric (statistical fallback), guide, point, bridge. Needs Debian's
python3-psycopg and python3-matplotlib. Every picture carries the line
"© OpenStreetMap contributors, ODbL" (the examples are crops of OpenStreetMap).
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import psycopg  # noqa: E402

STYLE = {
    "a": dict(color="#202020", lw=0.6),
    "b": dict(color="#1f5fbf", lw=0.6),
    "parametric": dict(color="#e08020", lw=0.6),
    "bridge": dict(color="#8040a0", lw=1.2),
    "guide": dict(color="#d02020", lw=1.6, alpha=0.6, ls="--"),
}


def draw(cur, ax, title, query):
    cur.execute(f"SELECT ST_AsText((ST_Dump(q.geom)).geom), q.kind FROM ({query}) AS q")
    for wkt, kind in cur.fetchall():
        if wkt.startswith("POINT"):
            x, y = map(float, wkt[wkt.index("(") + 1:wkt.index(")")].split())
            ax.plot([x], [y], marker="o", color="#d02020", ms=7)
            continue
        if not wkt.startswith("LINESTRING"):
            continue
        pts = [tuple(map(float, p.split())) for p in wkt[wkt.index("(") + 1:wkt.rindex(")")].split(",")]
        xs, ys = zip(*pts)
        ax.plot(xs, ys, **STYLE.get(kind, STYLE["a"]))
    ax.set_aspect("equal")
    ax.set_title(title, fontsize=9)
    ax.set_xticks([])
    ax.set_yticks([])


def main():
    dsn, out, title = sys.argv[1:4]
    panels = [p.split("|", 1) for p in sys.argv[4:]]
    with psycopg.connect(dsn) as conn:
        cur = conn.cursor()
        fig, axes = plt.subplots(1, len(panels), figsize=(5.5 * len(panels), 6))
        for ax, (t, q) in zip(axes, panels):
            draw(cur, ax, t, q)
    fig.suptitle(title, fontsize=10)
    fig.text(0.01, 0.01, "© OpenStreetMap contributors, ODbL (example patches of Nishida et al. 2016); "
             "grown by streetgen.grow_patches", fontsize=7)
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main()
