#!/usr/bin/python3
"""StreetGAN evaluation as in Hartmann et al. (2017, section 5.2), through the real SQL path:
gan_load_generator -> gan_sample (several seeds) -> raster_to_network -> network_stats, against
  * the example's own graph in the same window, and
  * the example rasterised at the generator's pixel size and road width, then extracted with the
    same raster_to_network parameters (the fair comparison: the same post-processing).
Metrics are taken inside the window shrunk by --margin (network_stats' window: nodes keep their
full degree, so roads cut by the window make no dead ends; the sample's own border does not count).

Writes into --out: metrics.csv (one row per network), table.md (the evaluation table), and
<city>.png (example window, its extraction, raw samples, their extraction, block distributions)
with the ODbL attribution. Needs PG* set to a database with streetgen (bench/gan/eval.sh).

usage: eval.py CITY GENERATOR --window X,Y [--seeds 1 2 3 4] [--side 769] [--road-px 4]
               [--params JSON] [--margin 300] --out DIR
"""
import argparse
import csv
import json
import os

import numpy as np
import psycopg

ATTRIBUTION = "Example data © OpenStreetMap contributors, ODbL 1.0"
SCALARS = ["node_count", "edge_count", "dead_end_share", "connected_node_ratio", "block_count", "total_length",
           "intersection_density", "street_density"]
DISTS = ["block_areas", "block_compactness", "block_aspect_ratios"]


def fetch_stats(cur, edges_query, window_sql, window_args):
    cols = SCALARS + DISTS
    cur.execute(f"SELECT {', '.join('s.' + c for c in cols)} FROM streetgen.network_stats(%s, 0, {window_sql}) s",
                (edges_query, *window_args))
    row = cur.fetchone()
    out = dict(zip(cols, row))
    for d in DISTS:
        out[d] = np.array(out[d] or [], dtype=float)
    return out


def raster_array(wkb):
    """One-band 8BUI PostGIS raster WKB (little-endian) -> uint8 array."""
    wkb = bytes(wkb)
    width, height = np.frombuffer(wkb, "<u2", 2, 57)
    return np.frombuffer(wkb, np.uint8, int(width) * int(height), 62 + 1).reshape(int(height), int(width))


def q(a, p):
    return float(np.percentile(a, p)) if len(a) else float("nan")


def summary(name, s, road_share):
    a, c, r = s["block_areas"], s["block_compactness"], s["block_aspect_ratios"]
    return {"network": name, "road_share": road_share, "dead_end_share": s["dead_end_share"],
            "cnr": s["connected_node_ratio"], "nodes": s["node_count"], "blocks": len(a),
            "length_km": (s["total_length"] or 0) / 1000.0,
            "area_p25": q(a, 25), "area_median": q(a, 50), "area_p75": q(a, 75),
            "compactness_median": q(c, 50), "compactness_iqr": (q(c, 25), q(c, 75)),
            "aspect_median": q(r, 50), "aspect_iqr": (q(r, 25), q(r, 75))}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("city")
    ap.add_argument("generator")
    ap.add_argument("--window", required=True, help="upper-left corner x,y of the example window (m)")
    ap.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3, 4])
    ap.add_argument("--side", type=int, default=769)
    ap.add_argument("--road-px", type=int, default=4, help="road width of the training raster, px")
    ap.add_argument("--params", default='{"erode": 0, "dilate": 1}', help="raster_to_network params")
    ap.add_argument("--margin", type=float, default=300.0)
    ap.add_argument("--srid", type=int, default=3857)
    ap.add_argument("--data", default=os.environ.get("STREETGEN_SHARED_DATA", "/work/shared/data"))
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    x0, y0 = (float(v) for v in args.window.split(","))
    name = "eval_" + args.city.replace("-", "_")

    with psycopg.connect(autocommit=True) as conn, conn.cursor() as cur:
        cur.execute("CREATE TABLE IF NOT EXISTS eval_city (name text, geom geometry(LineString))")
        cur.execute("SELECT count(*) FROM eval_city WHERE name = %s", (args.city,))
        if cur.fetchone()[0] == 0:
            path = os.path.join(args.data, "examples", "cities", args.city + ".geojson")
            # The example cities are in local metres (labelled EPSG:4326 in the file): any metric SRID.
            cur.execute("""INSERT INTO eval_city SELECT %s, ST_SetSRID(ST_GeomFromGeoJSON(f -> 'geometry'), %s)
                             FROM jsonb_array_elements(%s::jsonb -> 'features') AS f""",
                        (args.city, args.srid, open(path).read()))
        cur.execute("SELECT metres_per_pixel, parameter_count, bytes FROM streetgen.gan_load_generator(%s, %s, %s, true)",
                    (name, open(args.generator, "rb").read(), os.path.basename(args.generator)))
        mpp, params_count, size = cur.fetchone()
        ext = args.side * mpp
        window = (x0, y0 - ext, x0 + ext, y0, args.srid)
        wsql = "ST_Buffer(ST_MakeEnvelope(%s, %s, %s, %s, %s), -%s)"
        wargs = (*window, args.margin)
        example_edges = (f"SELECT geom FROM eval_city WHERE name = '{args.city}' "
                         f"AND geom && ST_Expand(ST_MakeEnvelope({x0}, {y0 - ext}, {x0 + ext}, {y0}, {args.srid}), 50)")
        cur.execute("SELECT ST_AsBinary(streetgen.rasterise_network(%s, %s, %s, ST_MakeEnvelope(%s, %s, %s, %s, %s)))",
                    (example_edges, mpp, args.road_px, *window))
        ex_raster = bytes(cur.fetchone()[0])
        cur.execute("CREATE TEMP TABLE IF NOT EXISTS eval_raster (tag text PRIMARY KEY, rast raster)")
        cur.execute("DELETE FROM eval_raster")
        cur.execute("INSERT INTO eval_raster VALUES ('example', ST_RastFromWKB(%s))", (ex_raster,))
        for seed in args.seeds:
            cur.execute("INSERT INTO eval_raster SELECT %s, streetgen.gan_sample(%s, %s, %s, %s, ST_SetSRID(ST_Point(%s, %s), %s))",
                        (f"seed{seed}", name, args.side, args.side, seed, x0, y0, args.srid))
        cur.execute("CREATE TEMP TABLE IF NOT EXISTS eval_edges (tag text, geom geometry)")
        cur.execute("DELETE FROM eval_edges")
        cur.execute("INSERT INTO eval_edges SELECT r.tag, t.geom FROM eval_raster r, streetgen.raster_to_network(r.rast, %s) t",
                    (args.params,))

        rows, pictures = [], {}
        own = fetch_stats(cur, example_edges, wsql, wargs)
        rows.append(summary("example graph", own, float("nan")))
        cur.execute("SELECT tag, ST_AsBinary(rast), (ST_SummaryStats(rast)).mean FROM eval_raster")
        shares = {}
        for tag, wkb, mean in cur.fetchall():
            pictures[tag] = raster_array(wkb)
            shares[tag] = float(mean)
        ex = fetch_stats(cur, "SELECT geom FROM eval_edges WHERE tag = 'example'", wsql, wargs)
        rows.append(summary("example rasterised + extracted", ex, shares["example"]))
        gens = []
        for seed in args.seeds:
            s = fetch_stats(cur, f"SELECT geom FROM eval_edges WHERE tag = 'seed{seed}'", wsql, wargs)
            gens.append(s)
            rows.append(summary(f"generated, seed {seed}", s, shares[f"seed{seed}"]))
        pooled = {d: np.concatenate([g[d] for g in gens]) for d in DISTS}
        nodes = sum(g["node_count"] for g in gens)
        pooled.update({"dead_end_share": float(np.mean([g["dead_end_share"] for g in gens])),
                       "connected_node_ratio": float(np.mean([g["connected_node_ratio"] for g in gens])),
                       "node_count": nodes / len(gens), "total_length": float(np.mean([g["total_length"] for g in gens]))})
        rows.append(summary(f"generated, {len(gens)} seeds (mean, pooled blocks)", pooled,
                            float(np.mean([shares[f"seed{s}"] for s in args.seeds]))))
        rows[-1]["blocks"] = len(pooled["block_areas"]) / len(gens)
        cur.execute("SELECT tag, ST_AsGeoJSON(geom) FROM eval_edges WHERE tag IN ('example', %s)", (f"seed{args.seeds[0]}",))
        lines = {}
        for tag, gj in cur.fetchall():
            lines.setdefault(tag, []).append(np.array(json.loads(gj)["coordinates"]))

    # ---- table --------------------------------------------------------------------------------------
    with open(os.path.join(args.out, f"{args.city}-metrics.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(list(rows[0].keys()))
        for r in rows:
            w.writerow([json.dumps(v) if isinstance(v, tuple) else v for v in r.values()])

    def rel(v, ref):
        return f"{(v - ref) / abs(ref) * 100:+.0f} %" if ref else "n/a"

    lines_md = [f"#### {args.city} ({os.path.basename(args.generator)}: {params_count} parameters, {size} bytes, "
                f"{mpp:g} m/px; window {args.side} px = {ext:.0f} m at ({x0:g}, {y0:g}), metrics inside "
                f"{args.margin:g} m of its border; raster_to_network {args.params})", "",
                "| network | road share | dead-end share | CNR | blocks | block area m² p25 / median / p75 | "
                "compactness median (IQR) | aspect ratio median (IQR) | length km |",
                "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines_md.append(
            f"| {r['network']} | {r['road_share']:.3f} | {r['dead_end_share']:.4f} | {r['cnr']:.3f} | {r['blocks']:.0f} | "
            f"{r['area_p25']:.0f} / {r['area_median']:.0f} / {r['area_p75']:.0f} | "
            f"{r['compactness_median']:.3f} ({r['compactness_iqr'][0]:.2f}–{r['compactness_iqr'][1]:.2f}) | "
            f"{r['aspect_median']:.2f} ({r['aspect_iqr'][0]:.2f}–{r['aspect_iqr'][1]:.2f}) | {r['length_km']:.0f} |")
    g = rows[-1]
    lines_md += ["", f"Generated (mean of seeds) against the example graph / the extracted example: dead-end share "
                 f"{rel(g['dead_end_share'], rows[0]['dead_end_share'])} / {rel(g['dead_end_share'], rows[1]['dead_end_share'])}, "
                 f"CNR {rel(g['cnr'], rows[0]['cnr'])} / {rel(g['cnr'], rows[1]['cnr'])}, median block area "
                 f"{rel(g['area_median'], rows[0]['area_median'])} / {rel(g['area_median'], rows[1]['area_median'])}; "
                 f"per seed dead-end share vs the extracted example: "
                 + ", ".join(rel(r["dead_end_share"], rows[1]["dead_end_share"]) for r in rows[2:-1]), ""]
    with open(os.path.join(args.out, f"{args.city}-table.md"), "w") as f:
        f.write("\n".join(lines_md) + "\n")
    print("\n".join(lines_md), flush=True)

    # ---- picture ------------------------------------------------------------------------------------
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig = plt.figure(figsize=(20, 10.5))
    panels = [("example window (rasterised)", pictures["example"], None),
              ("example extracted (raster_to_network)", None, lines.get("example", [])),
              (f"gan_sample, seed {args.seeds[0]}", pictures[f"seed{args.seeds[0]}"], None),
              (f"sample extracted, seed {args.seeds[0]}", None, lines.get(f"seed{args.seeds[0]}", []))]
    for i, (title, img, segs) in enumerate(panels):
        ax = fig.add_subplot(2, 4, i + 1)
        if img is not None:
            ax.imshow(img, cmap="gray", vmin=0, vmax=1, extent=(x0, x0 + ext, y0 - ext, y0))
        else:
            for s in segs:
                ax.plot(s[:, 0], s[:, 1], "k-", lw=0.5)
            ax.set_xlim(x0, x0 + ext)
            ax.set_ylim(y0 - ext, y0)
        ax.set_aspect("equal")
        ax.set_xticks([])
        ax.set_yticks([])
        ax.set_title(title, fontsize=10)
    hist = [("block area (m², log)", "block_areas", np.logspace(2, 6, 41), True),
            ("block compactness 4πA/P²", "block_compactness", np.linspace(0, 1, 41), False),
            ("block aspect ratio (long/short side)", "block_aspect_ratios", np.linspace(1, 8, 41), False)]
    for i, (title, key, bins, logx) in enumerate(hist):
        ax = fig.add_subplot(2, 4, 5 + i)
        for label, data, style in [("example graph", own[key], "C0"), ("example extracted", ex[key], "C2"),
                                   ("generated (pooled)", pooled[key], "C3")]:
            ax.hist(data, bins=bins, density=True, histtype="step", color=style, label=f"{label} ({len(data)})")
        if logx:
            ax.set_xscale("log")
        ax.set_title(title, fontsize=10)
        ax.legend(fontsize=8)
    ax = fig.add_subplot(2, 4, 8)
    ax.axis("off")
    ax.text(0, 0.95, "\n".join(f"{r['network']}: dead ends {r['dead_end_share']:.3f}, CNR {r['cnr']:.3f}, "
                                f"road {r['road_share']:.2f}" for r in rows), fontsize=8, va="top", family="monospace",
            wrap=True)
    fig.suptitle(f"StreetGAN {args.city}: {os.path.basename(args.generator)}", fontsize=12)
    fig.text(0.01, 0.005, ATTRIBUTION, fontsize=9)
    fig.tight_layout(rect=(0, 0.02, 1, 0.97))
    path = os.path.join(args.out, f"{args.city}.png")
    fig.savefig(path, dpi=90)
    print(f"picture: {path}")


if __name__ == "__main__":
    main()
