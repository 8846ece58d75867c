#!/usr/bin/python3
"""Prints the LineString features of a GeoJSON file as COPY text: id, EWKT with SRID 0 (the
example graphs are in local metres with no CRS). Usage: geojson_edges.py FILE | psql -c "COPY t FROM STDIN"."""
import json
import sys

with open(sys.argv[1]) as f:
    data = json.load(f)
out = sys.stdout
for i, feature in enumerate(data["features"], 1):
    g = feature.get("geometry")
    if not g or g["type"] != "LineString":
        continue
    coords = ",".join(f"{x!r} {y!r}" for x, y in g["coordinates"])
    out.write(f"{i}\tSRID=0;LINESTRING({coords})\n")
