#!/usr/bin/env python3
"""A headless QGIS editing session on a model's axes, as a desktop user would make it.

    QT_QPA_PLATFORM=offscreen /usr/bin/python3 edit_session.py MODEL PROJECT.qgs

The connection comes from PGHOST (socket folder), PGPORT, PGDATABASE and PGUSER. PROJECT.qgs was
written by qgis/make_project.py for MODEL. Through the PostGIS provider the session moves a vertex
of one axis, draws a new axis between two nodes and deletes a third, then commits; the database
must then hold surfaces for exactly the edited axes (streetgen.outdated is empty), QGIS must read
them back, and the commit must reach QGIS and plain clients as NOTIFY qgis, 'MODEL'.
"""
import math
import os
import sys
import time

import psycopg
from qgis.core import (QgsApplication, QgsDataSourceUri, QgsFeatureRequest, QgsGeometry, QgsPointXY, QgsProject,
                       QgsVectorLayer, QgsVectorLayerUtils)

MODEL, PROJECT = sys.argv[1], sys.argv[2]
checks = 0


def check(ok, message):
    global checks
    if not ok:
        sys.exit(f'FAIL: {message}')
    checks += 1


def layer(table, geom, key):
    uri = QgsDataSourceUri()
    uri.setConnection(os.environ['PGHOST'], os.environ['PGPORT'], os.environ['PGDATABASE'], os.environ['PGUSER'], '')
    uri.setDataSource(MODEL, table, geom, '', key)
    result = QgsVectorLayer(uri.uri(False), table, 'postgres')
    check(result.isValid(), f'QGIS cannot open {MODEL}.{table}')
    return result


def wait_for(condition, seconds=10):
    """Lets Qt deliver queued signals (QGIS's notification listener is a thread) until condition()."""
    deadline = time.monotonic() + seconds
    while not condition() and time.monotonic() < deadline:
        QgsApplication.processEvents()
        time.sleep(0.05)
    return condition()


def one(sql, *args):
    row = db.execute(sql, args).fetchone()
    check(row is not None, f'no row from {" ".join(sql.split())[:100]}')
    return row


app = QgsApplication([], False)
app.initQgis()
db = psycopg.connect(autocommit=True)

# The project: every layer opens, and keeps its refresh-on-notification setting.
project = QgsProject.instance()
check(project.read(PROJECT), f'QGIS cannot read {PROJECT}: {project.error()}')
project_layers = {lyr.name(): lyr for lyr in project.mapLayers().values()}
check(len(project_layers) == 7, f'the project has {len(project_layers)} layers, not 7')
for name, lyr in project_layers.items():
    check(lyr.isValid(), f'project layer {name} is not valid')
    check(lyr.isRefreshOnNotifyEnabled() and lyr.refreshOnNotifyMessage() == MODEL,
          f'project layer {name} does not refresh on notification {MODEL!r}')
# Lanes and markings come through the PostGIS provider like the surfaces, every row of them.
for table in ('lane', 'marking'):
    in_db = db.execute(f'SELECT count(*) FROM {MODEL}.{table}').fetchone()[0]
    in_qgis = project_layers[f'{MODEL} {table}'].featureCount()
    check(in_db > 0 and in_qgis == in_db, f'the {table} layer shows {in_qgis} features, the table holds {in_db}')
# The surfaces layer is not edited below: only the notification can make it repaint.
repaints = []
project_layers[f'{MODEL} section'].repaintRequested.connect(lambda *_: repaints.append(time.monotonic()))

# A plain client listening too (psycopg delivers notifications as it reads from the server).
listener = psycopg.connect(autocommit=True)
notes = []
listener.add_notify_handler(lambda n: notes.append((n.channel, n.payload)))
listener.execute('LISTEN qgis')

# What to edit, chosen in SQL so that the three edits lie at least 200 m apart.
# (b) two same-layer nodes 90-110 m apart with no axis within 10 m of the line between them.
node_a, node_b, ax, ay, bx, by = one(f'''
  SELECT a.id, b.id, ST_X(a.geom), ST_Y(a.geom), ST_X(b.geom), ST_Y(b.geom)
    FROM {MODEL}.node a JOIN {MODEL}.node b ON a.id < b.id AND a.layer = b.layer
   WHERE ST_DWithin(a.geom, b.geom, 110) AND ST_Distance(a.geom, b.geom) > 90
     AND NOT EXISTS (SELECT 1 FROM {MODEL}.axis x
                      WHERE ST_DWithin(x.geom, ST_LineSubstring(ST_MakeLine(a.geom, b.geom), 0.1, 0.9), 10))
   ORDER BY a.id, b.id LIMIT 1''')
new_line = (f"ST_SetSRID(ST_MakeLine(ST_MakePoint({ax}, {ay}), ST_MakePoint({bx}, {by})), "
            f"streetgen.model_srid('{MODEL}'))")
# (a) an interior vertex at least 30 m from both ends of its axis, so that it moves a section.
moved, vertex, px, py, qx, qy = one(f'''
  SELECT a.id, v.path[1] - 1, ST_X(ST_PointN(a.geom, v.path[1] - 1)), ST_Y(ST_PointN(a.geom, v.path[1] - 1)),
         ST_X(ST_PointN(a.geom, v.path[1] + 1)), ST_Y(ST_PointN(a.geom, v.path[1] + 1))
    FROM {MODEL}.axis a, ST_DumpPoints(a.geom) v
   WHERE v.path[1] BETWEEN 2 AND ST_NPoints(a.geom) - 1
     AND ST_LineLocatePoint(a.geom, v.geom) * ST_Length(a.geom) BETWEEN 30 AND ST_Length(a.geom) - 30
     AND NOT ST_DWithin(a.geom, {new_line}, 200)
   ORDER BY a.id, v.path[1] LIMIT 1''')
# (c) any axis away from both.
deleted, = one(f'''
  SELECT id FROM {MODEL}.axis
   WHERE NOT ST_DWithin(geom, {new_line}, 200)
     AND NOT ST_DWithin(geom, (SELECT geom FROM {MODEL}.axis WHERE id = %s), 200)
   ORDER BY id LIMIT 1''', moved)
before_sections, = one(f'SELECT ST_Collect(geom)::text FROM {MODEL}.section WHERE axis_id = %s', moved)
check(before_sections is not None, f'axis {moved} has no section surface to compare with')
max_id, = one(f'SELECT max(id) FROM {MODEL}.axis')

# The editing session: everything waits in QGIS's edit buffer until commitChanges.
axes = layer('axis', 'geom', 'id')
request = QgsFeatureRequest().setFilterExpression(f'"id" IN ({moved}, {deleted})')
fid = {f['id']: f.id() for f in axes.getFeatures(request)}
check(len(fid) == 2, f'QGIS does not see axes {moved} and {deleted}')
check(axes.startEditing(), 'cannot start editing')
# (a) 4 m sideways, perpendicular to the chord between the vertex's neighbours.
v = axes.getGeometry(fid[moved]).vertexAt(vertex)
length = math.hypot(qx - px, qy - py)
nx, ny = v.x() - 4 * (qy - py) / length, v.y() + 4 * (qx - px) / length
check(axes.moveVertex(nx, ny, fid[moved], vertex), 'moveVertex refused')
# (b) createFeature, like QGIS's digitizing tools: NOT NULL columns get their database defaults
# (a bare QgsFeature would send explicit NULLs), and the identity id is left to the database.
fields = axes.fields()
new = QgsVectorLayerUtils.createFeature(axes, QgsGeometry.fromPolylineXY([QgsPointXY(ax, ay), QgsPointXY(bx, by)]),
                                        {fields.indexOf('roadway_width'): 7.5, fields.indexOf('speed_kmh'): 30.0})
check(axes.addFeature(new), 'addFeature refused')
# (c)
check(axes.deleteFeature(fid[deleted]), 'deleteFeature refused')
check(not repaints, 'the section layer repainted before the commit')
started = time.monotonic()
committed = axes.commitChanges()
commit_seconds = time.monotonic() - started
check(committed, 'commitChanges failed:\n' + '\n'.join(axes.commitErrors()))

# The notification, to QGIS's own listener and to a plain client.
check(wait_for(lambda: repaints), f'the project\'s section layer did not repaint on NOTIFY qgis, {MODEL!r}')


def notified():
    listener.execute('SELECT 1')  # a round trip reads what the server sent meanwhile
    return ('qgis', MODEL) in notes


check(wait_for(notified), f'no NOTIFY qgis, {MODEL!r} after the commit (got {notes})')

# The database.
x, y = one(f'SELECT ST_X(ST_PointN(geom, %s)), ST_Y(ST_PointN(geom, %s)) FROM {MODEL}.axis WHERE id = %s',
          vertex + 1, vertex + 1, moved)
check(math.hypot(x - nx, y - ny) < 1e-6, f'axis {moved} vertex {vertex} is at ({x}, {y}), not at ({nx}, {ny})')
shift, = one(f'SELECT ST_HausdorffDistance(%s::geometry, ST_Collect(geom)) FROM {MODEL}.section WHERE axis_id = %s',
             before_sections, moved)
check(shift is not None and shift > 1, f'the sections of moved axis {moved} moved {shift} m, not about 4 m')
# The columns left out took their database defaults.
rows = db.execute(f'''SELECT id FROM {MODEL}.axis WHERE id > %s AND ST_Equals(geom, {new_line})
                        AND roadway_width = 7.5 AND road_class = 'unclassified' AND NOT oneway AND layer = 0
                        AND tags = '{{}}' ''', (max_id,)).fetchall()
check(len(rows) == 1, f'{len(rows)} new axes with the drawn geometry and attributes, not 1')
new_id = rows[0][0]
sections, = one(f'SELECT count(*) FROM {MODEL}.section WHERE axis_id = %s AND geom IS NOT NULL', new_id)
check(sections > 0, f'new axis {new_id} has no section surface')
junctions, = one(f'''SELECT count(*) FROM {MODEL}.node n JOIN {MODEL}.intersection i ON i.node_id = n.id
                     WHERE n.id IN (%s, %s) AND %s = ANY (n.axis_ids) AND %s = ANY (i.axis_ids)''',
                 node_a, node_b, new_id, new_id)
check(junctions == 2, f'{junctions} of the new axis\'s end nodes have an intersection with it, not 2')
left, = one(f'''SELECT (SELECT count(*) FROM {MODEL}.axis WHERE id = %s)
                     + (SELECT count(*) FROM {MODEL}.section WHERE axis_id = %s)
                     + (SELECT count(*) FROM {MODEL}.node WHERE %s = ANY (axis_ids))
                     + (SELECT count(*) FROM {MODEL}.intersection WHERE %s = ANY (axis_ids))''', *[deleted] * 4)
check(left == 0, f'{left} rows still refer to deleted axis {deleted}')
outdated, = one('SELECT count(*) FROM streetgen.outdated(%s)', MODEL)
check(outdated == 0, f'streetgen.outdated({MODEL!r}) lists {outdated} rows after the commit')
for table, column in [('section', 'geom'), ('intersection', 'geom'), ('corner', 'arc_segmentized'), ('node', 'geom')]:
    invalid, = one(f'SELECT count(*) FROM {MODEL}.{table} WHERE {column} IS NOT NULL AND NOT ST_IsValid({column})')
    check(invalid == 0, f'{invalid} invalid {table}.{column}')

# QGIS reads the result back: the moved axis's sections where the database has them.
surfaces = layer('section', 'geom', '"axis_id","part"')
check(surfaces.featureCount() > 0, 'the section layer is empty')
read = QgsGeometry.collectGeometry([f.geometry() for f in surfaces.getFeatures(f'"axis_id" = {moved}')
                                    if f.hasGeometry()])
check(not read.isEmpty(), f'QGIS reads no section surface of axis {moved}')
now, before = one(f'SELECT ST_AsText(ST_Collect(geom)), ST_AsText(%s::geometry) FROM {MODEL}.section '
                  'WHERE axis_id = %s', before_sections, moved)
check(read.hausdorffDistance(QgsGeometry.fromWkt(now)) < 1e-6, f'QGIS reads other sections of axis {moved} than the db')
check(read.hausdorffDistance(QgsGeometry.fromWkt(before)) > 1, f'QGIS still reads the old sections of axis {moved}')

print(f'edit_session: {checks} checks passed; moved a vertex of axis {moved}, added axis {new_id} '
      f'({node_a} - {node_b}), deleted axis {deleted}; {len(notes)} NOTIFY qgis {MODEL!r} at commit; '
      f'commitChanges {commit_seconds:.1f} s')
project.clear()
app.exitQgis()
