#!/usr/bin/python3
"""The OSMnx side of bench/metrics: the same statistics on the same GeoJSON edges, timed.

Nodes are the edges' distinct end coordinates (as streetgen's network_stats with tolerance 0),
one undirected street per feature. Prints one line of JSON: counts (to check both saw the same
graph), the entropy, and the seconds spent in graph construction, in OSMnx's statistics
(street counts, basic_stats, bearings and orientation entropy; bearings need an unprojected graph,
so that includes projecting it to WGS84) and in block polygons (OSMnx has none: shapely's
polygonize with areas, perimeters and minimum rotated rectangles)."""
import json
import sys
import time

import geopandas as gpd
import networkx as nx
import osmnx as ox
import shapely.geometry as sg
import shapely.ops as so

# A made-up local CRS for the example's local metres (only the bearings need lon/lat).
LOCAL = "+proj=tmerc +lat_0=48.85 +lon_0=2.35 +k=1 +x_0=0 +y_0=0 +R=6371009 +units=m +no_defs"

with open(sys.argv[1]) as f:
    features = [ft for ft in json.load(f)["features"] if ft["geometry"] and ft["geometry"]["type"] == "LineString"]

t0 = time.perf_counter()
node_id, xs, ys, rows = {}, [], [], []
for ft in features:
    coords = [tuple(c[:2]) for c in ft["geometry"]["coordinates"]]
    ends = []
    for c in (coords[0], coords[-1]):
        if c not in node_id:
            node_id[c] = len(node_id)
            xs.append(c[0])
            ys.append(c[1])
        ends.append(node_id[c])
    line = sg.LineString(coords)
    rows.append((ends[0], ends[1], line, line.length))
nodes = gpd.GeoDataFrame({"x": xs, "y": ys}, geometry=gpd.points_from_xy(xs, ys), crs=LOCAL)
keys, seen = [], {}
for u, v, _, _ in rows:
    k = seen.get((u, v), 0)
    seen[(u, v)] = k + 1
    keys.append(k)
edges = gpd.GeoDataFrame({"u": [r[0] for r in rows], "v": [r[1] for r in rows], "key": keys,
                          "osmid": list(range(len(rows))),  # get_undirected compares osmids
                          "length": [r[3] for r in rows]}, geometry=[r[2] for r in rows], crs=LOCAL)
edges = edges.set_index(["u", "v", "key"])
G = ox.graph_from_gdfs(nodes, edges)
t_graph = time.perf_counter() - t0

t0 = time.perf_counter()
nx.set_node_attributes(G, ox.stats.count_streets_per_node(G), name="street_count")
hull_area = sg.MultiPoint([c for _, _, line, _ in rows for c in line.coords]).convex_hull.area
stats = ox.basic_stats(G, area=hull_area)
Gu = ox.get_undirected(ox.project_graph(G, to_crs="epsg:4326"))
Gu = ox.add_edge_bearings(Gu)
entropy = ox.bearing.orientation_entropy(Gu, num_bins=36, weight="length")
t_stats = time.perf_counter() - t0

t0 = time.perf_counter()
faces = list(so.polygonize([line for _, _, line, _ in rows]))
areas = [p.area for p in faces]
compactness = [4 * 3.141592653589793 * p.area / p.exterior.length ** 2 for p in faces]
aspect = []
for p in faces:
    r = list(p.minimum_rotated_rectangle.exterior.coords)
    a, b = sg.Point(r[0]).distance(sg.Point(r[1])), sg.Point(r[1]).distance(sg.Point(r[2]))
    if min(a, b) > 0:
        aspect.append(max(a, b) / min(a, b))
t_blocks = time.perf_counter() - t0

print(json.dumps({"nodes": stats["n"], "streets": stats["street_segment_count"],
                  "intersections": stats["intersection_count"], "mean_degree": stats["streets_per_node_avg"],
                  "street_density": stats["street_density_km"] / 1000, "circuity": stats["circuity_avg"],
                  "orientation_entropy": entropy, "blocks": len(faces),
                  "t_graph": t_graph, "t_stats": t_stats, "t_blocks": t_blocks}))
