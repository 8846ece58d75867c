#!/usr/bin/python3
"""streetgen.network_stats against OSMnx on real OpenStreetMap networks.

For each city: osmium keeps the driveable highway ways, OSMnx builds and simplifies the graph
(graph_from_xml, retain_all) and computes its statistics; the edges of OSMnx's undirected graph
(ox.get_undirected), projected to a local spherical transverse Mercator centred on the city
(R = 6371009 m, OSMnx's great-circle radius, so planar lengths and bearings are OSMnx's great
circle ones to < 1e-6), go into PostgreSQL and through streetgen.network_stats. Counts must be
equal, densities, mean degree, circuity and orientation entropy within 1 %.

Definition alignment (see README, "Network metrics"):
  - the same simplified graph (OSMnx's) goes into both; streetgen's edges are OSMnx's
    undirected streets (street_segment_count), not its directed edges (m);
  - mean_degree is OSMnx's streets_per_node_avg (2 E / N), not k_avg (directed);
  - street_density is km per km²; OSMnx's street_density_km is m per km² (factor 1000);
  - area: the convex hull of the edges' vertices, computed here with shapely and given to
    OSMnx's basic_stats, computed by streetgen itself;
  - exact duplicates (two OSM ways over the same nodes) are one street in streetgen: its
    edge_count + duplicate_edges is OSMnx's street_segment_count;
  - degrees: OSMnx's street_count (count_streets_per_node) merges two one-way edges u->v and
    v->u of different ways into one street although get_undirected keeps both as streets, so its
    streets-per-node sum is not 2 x street_segment_count. streetgen's degree is the undirected
    graph's (networkx Gu.degree() after dropping exact duplicates), which the shares must equal
    exactly; OSMnx's own streets_per_node_avg must be within 1 %;
  - orientation entropy: OSMnx's weight="length" (bearings repeated int(length) times, rounded
    to 0.1°) against streetgen's exact length weights.

Usage: osmnx_reference.py DBNAME WORKDIR [city ...]   (PGHOST/PGPORT/PGUSER from the environment)
"""
import gzip
import bz2
import math
import os
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

import networkx as nx
import osmnx as ox
import psycopg
import pyproj
import shapely.geometry as sg

DATA = os.environ.get("STREETGEN_SHARED_DATA", os.path.join(os.path.dirname(__file__), "../../../shared/data"))
CITIES = {  # name: (file, style)
    "campo-grande": ("campo-grande.osm.gz", "grid"),
    "baltimore": ("baltimore.osm.pbf", "grid"),
    "krems": ("krems.osm.gz", "organic"),
    "paris-11e": ("paris-11e.osm.pbf", "organic"),
    "reisterstown": ("reisterstown.osm.pbf", "suburban"),
}
DRIVE = ("motorway,motorway_link,trunk,trunk_link,primary,primary_link,secondary,secondary_link,"
         "tertiary,tertiary_link,unclassified,residential,living_street,road")
TOLERANCE = 0.01  # relative, for densities, mean degree, circuity and orientation entropy


def prepare_xml(city, workdir):
    """Driveable ways as OSM XML, sorted, with references to nodes missing from the extract
    dropped (the extracts cut ways at their border) and only referenced nodes kept."""
    src = os.path.join(DATA, "osm", CITIES[city][0])
    sorted_pbf = os.path.join(workdir, f"{city}-sorted.osm.pbf")
    filtered = os.path.join(workdir, f"{city}-drive.osm")
    subprocess.run(["osmium", "sort", "-O", "-o", sorted_pbf, src], check=True, capture_output=True)
    subprocess.run(["osmium", "tags-filter", "-O", "-o", filtered, sorted_pbf, f"w/highway={DRIVE}"],
                   check=True, capture_output=True)
    tree = ET.parse(filtered)
    root = tree.getroot()
    present = {n.get("id") for n in root.iter("node")}
    used = set()
    for way in list(root.iter("way")):
        for nd in [nd for nd in way.findall("nd") if nd.get("ref") not in present]:
            way.remove(nd)
        refs = [nd.get("ref") for nd in way.findall("nd")]
        if len(set(refs)) < 2:
            root.remove(way)
        else:
            used.update(refs)
    for node in [n for n in root.findall("node") if n.get("id") not in used]:
        root.remove(node)
    clean = os.path.join(workdir, f"{city}-clean.osm")
    tree.write(clean, encoding="utf-8", xml_declaration=True)
    return clean


def local_crs(G):
    xs = [d["x"] for _, d in G.nodes(data=True)]
    ys = [d["y"] for _, d in G.nodes(data=True)]
    lon0, lat0 = (min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2
    return f"+proj=tmerc +lat_0={lat0} +lon_0={lon0} +k=1 +x_0=0 +y_0=0 +R=6371009 +units=m +no_defs"


def osmnx_side(xml_path):
    t0 = time.perf_counter()
    G = ox.graph_from_xml(xml_path, simplify=True, retain_all=True)
    # graph_from_xml does not set street_count (graph_from_place etc. do): the same function they use.
    nx.set_node_attributes(G, ox.stats.count_streets_per_node(G), name="street_count")
    Gu = ox.get_undirected(G)
    t_graph = time.perf_counter() - t0

    to_local = pyproj.Transformer.from_crs("EPSG:4326", local_crs(G), always_xy=True)
    xy = {n: to_local.transform(d["x"], d["y"]) for n, d in G.nodes(data=True)}
    edges = []
    for u, v, k, d in Gu.edges(keys=True, data=True):
        if "geometry" in d:
            coords = list(d["geometry"].coords)
            # orient like (u, v); the geometry's ends are exactly the nodes' coordinates
            if (coords[0][0], coords[0][1]) != (G.nodes[u]["x"], G.nodes[u]["y"]):
                coords.reverse()
            pts = [xy[u]] + [to_local.transform(x, y) for x, y in coords[1:-1]] + [xy[v]]
        else:
            pts = [xy[u], xy[v]]
        edges.append(pts)
    # Undirected degrees of Gu without exact duplicates (same end nodes, same course).
    seen, degree, duplicates = set(), {n: 0 for n in G.nodes}, 0
    for (u, v, k, d), pts in zip(Gu.edges(keys=True, data=True), edges):
        key = (min(u, v), max(u, v), tuple(pts) if u <= v else tuple(reversed(pts)))
        if u == v:
            key = (u, u, min(tuple(pts), tuple(reversed(pts))))
        if key in seen:
            duplicates += 1
            continue
        seen.add(key)
        degree[u] += 1
        degree[v] += 1
    n = len(degree)
    share = lambda pred: sum(1 for x in degree.values() if pred(x)) / n
    hull_area = sg.MultiPoint([p for pts in edges for p in pts]).convex_hull.area

    t0 = time.perf_counter()
    stats = ox.basic_stats(G, area=hull_area)
    Gb = ox.add_edge_bearings(Gu)
    entropy = ox.bearing.orientation_entropy(Gb, num_bins=36, weight="length")
    t_stats = time.perf_counter() - t0
    entropy_unweighted = ox.bearing.orientation_entropy(Gb, num_bins=36)
    spnp = stats["streets_per_node_proportions"]
    ref = {
        "node_count": stats["n"],
        "edge_count": stats["street_segment_count"],  # compared with edge_count + duplicate_edges
        "intersection_count": stats["intersection_count"],
        "total_length": stats["street_length_total"],
        "area": hull_area,
        "node_density": stats["node_density_km"],
        "intersection_density": stats["intersection_density_km"],
        "street_density": stats["street_density_km"] / 1000.0,  # m/km² -> km/km²
        "mean_degree": stats["streets_per_node_avg"],
        "dead_end_share": share(lambda x: x == 1),
        "degree3_share": share(lambda x: x == 3),
        "degree4_share": share(lambda x: x == 4),
        "degree5plus_share": share(lambda x: x >= 5),
        "osmnx_street_count_degree4_share": spnp.get(4, 0.0),
        "duplicate_edges": duplicates,
        "circuity": stats["circuity_avg"],
        "orientation_entropy": entropy,
        "orientation_order": 1 - ((entropy - math.log(4)) / (math.log(36) - math.log(4))) ** 2,
        "component_count": nx.number_connected_components(nx.Graph(Gu)),
    }
    info = {"directed_edges": stats["m"], "entropy_unweighted": entropy_unweighted,
            "t_graph": t_graph, "t_stats": t_stats}
    return ref, edges, info


EXACT = ["node_count", "edge_count", "duplicate_edges", "intersection_count", "component_count"]
RELATIVE = ["street_density", "intersection_density", "node_density", "mean_degree", "circuity",
            "orientation_entropy", "total_length", "area"]
ABSOLUTE = ["dead_end_share", "degree3_share", "degree4_share", "degree5plus_share"]  # shares of the same nodes: exact up to float


def streetgen_side(conn, city, edges):
    table = "osmnx_" + city.replace("-", "_")
    with conn.cursor() as cur:
        cur.execute(f"DROP TABLE IF EXISTS {table}")
        cur.execute(f"CREATE TABLE {table} (id integer, geom geometry(LineString, 0))")
        with cur.copy(f"COPY {table} (id, geom) FROM STDIN") as copy:
            for i, pts in enumerate(edges, 1):
                wkt = "LINESTRING(" + ",".join(f"{x!r} {y!r}" for x, y in pts) + ")"
                copy.write_row((i, wkt))
        t0 = time.perf_counter()
        cur.execute(f"SELECT to_jsonb(s) FROM streetgen.network_stats('SELECT geom FROM {table}') s")
        ours = cur.fetchone()[0]
        t_ours = time.perf_counter() - t0
    conn.commit()
    return ours, t_ours


def main():
    db, workdir = sys.argv[1], sys.argv[2]
    cities = sys.argv[3:] or list(CITIES)
    os.makedirs(workdir, exist_ok=True)
    failures = []
    with psycopg.connect(dbname=db) as conn:
        for city in cities:
            xml_path = prepare_xml(city, workdir)
            ref, edges, info = osmnx_side(xml_path)
            ours, t_ours = streetgen_side(conn, city, edges)
            ours["edge_count"] += ours["duplicate_edges"]
            print(f"\n== {city} ({CITIES[city][1]}): {ref['node_count']} nodes, {ref['edge_count']} streets "
                  f"({info['directed_edges']} directed edges); OSMnx graph {info['t_graph']:.2f} s, "
                  f"stats {info['t_stats']:.2f} s; streetgen {t_ours:.2f} s")
            print(f"   {'metric':<22} {'OSMnx':>16} {'streetgen':>16} {'rel. diff':>10}")
            for m in EXACT + RELATIVE + ABSOLUTE + ["orientation_order"]:
                a, b = ref[m], ours[m]
                rd = (b - a) / abs(a) if a else (0.0 if b == a else float("inf"))
                ok = True
                if m in EXACT:
                    ok = a == b
                elif m in RELATIVE:
                    ok = abs(rd) <= TOLERANCE
                elif m in ABSOLUTE:
                    ok = abs(b - a) <= 1e-9
                flag = "" if ok else "  FAIL"
                print(f"   {m:<22} {a:>16.6g} {b:>16.6g} {rd:>+10.2e}{flag}")
                if not ok:
                    failures.append(f"{city}: {m} OSMnx {a} streetgen {b}")
            print(f"   (edge_count above is streetgen's edge_count + duplicate_edges; OSMnx street_count based: "
                  f"degree4_share {ref['osmnx_street_count_degree4_share']:.6g}; unweighted OSMnx orientation "
                  f"entropy {info['entropy_unweighted']:.4f}; collapsed edges {ours['collapsed_edges']})")
    if failures:
        print("\nFAIL:\n  " + "\n  ".join(failures), file=sys.stderr)
        return 1
    print(f"\nOK: {len(cities)} cities agree with OSMnx (counts exact, the rest within {TOLERANCE:.0%})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
