#!/usr/bin/env bash
# Metrics layer: streetgen.network_stats against OSMnx (Debian python3-osmnx) on real OSM
# networks of ../shared/data/osm: a grid, an organic old town and a suburb at least (see
# tests/metrics/osmnx_reference.py for the cities and the definitions aligned).
source "$(dirname "$0")/lib.sh"
mark=$(log_mark)
fresh_db streetgen_metrics streetgen
work=$(mktemp -d /tmp/streetgen-metrics.XXXXXX)
trap 'rm -rf "$work"' EXIT
status=0
STREETGEN_SHARED_DATA="${STREETGEN_SHARED_DATA:?}" /usr/bin/python3 "$SRC"/tests/metrics/osmnx_reference.py \
  streetgen_metrics "$work" || status=$?
assert_no_crash_since "$mark" || status=1
exit $status
