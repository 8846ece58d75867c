#include "core/streets/topology.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <unordered_map>
#include <unordered_set>

#include "core/interrupts.hpp"
#include "core/streets/box_pairs.hpp"
#include "core/union_find.hpp"

namespace streetgen::core {
namespace {

// A place where an axis must be cut: its ends, and every point where another axis of the same
// layer crosses or touches it.
struct Event {
  std::size_t axis;
  double abscissa;
  Point point;
  bool axis_end;
  int layer;
};

struct Segment {
  std::size_t axis;
  std::size_t index;  // segment i joins vertices i and i+1
  double start_abscissa;
};


std::uint64_t mix(std::uint64_t h) {  // splitmix64 finaliser
  h += 0x9e3779b97f4a7c15ULL;
  h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ULL;
  h = (h ^ (h >> 27)) * 0x94d049bb133111ebULL;
  return h ^ (h >> 31);
}

// Closest point of segment [a, b] to p, as parameter t in [0, 1].
double segment_parameter(Point a, Point b, Point p) {
  Point d = b - a;
  double len2 = dot(d, d);
  return len2 > 0.0 ? std::clamp(dot(p - a, d) / len2, 0.0, 1.0) : 0.0;
}

}  // namespace

std::int64_t node_id_for(Point position, int layer) {
  auto mm = [](double v) { return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::llround(v * 1000.0))); };
  std::uint64_t h = mix(mix(mix(mm(position.x)) ^ mm(position.y)) ^ static_cast<std::uint64_t>(layer + 16));
  return static_cast<std::int64_t>(h & 0x7fffffffffffffffULL);
}

Topology build_topology(const std::vector<TopologyAxis>& axes, double snap_tolerance) {
  const double tol = std::max(snap_tolerance, 1e-9);
  Topology topo;

  std::vector<Polyline> lines(axes.size());
  std::vector<double> lengths(axes.size(), 0.0);
  std::vector<bool> usable(axes.size(), false);
  for (std::size_t i = 0; i < axes.size(); ++i) {
    lines[i] = without_repeated_points(axes[i].line, 1e-9);
    lengths[i] = length(lines[i]);
    usable[i] = lines[i].size() >= 2 && lengths[i] > tol;
    if (!usable[i]) {
      topo.issues.push_back({axes[i].id, "degenerate_axis", "shorter than the snap tolerance; no surface", std::nullopt});
    }
  }

  std::vector<Event> events;
  std::vector<Segment> segments;
  std::vector<Box> boxes;
  for (std::size_t a = 0; a < axes.size(); ++a) {
    if (!usable[a]) continue;
    const Polyline& l = lines[a];
    events.push_back({a, 0.0, l.front(), true, axes[a].layer});
    events.push_back({a, lengths[a], l.back(), true, axes[a].layer});
    double s = 0.0;
    for (std::size_t i = 0; i + 1 < l.size(); ++i) {
      segments.push_back({a, i, s});
      boxes.push_back({std::min(l[i].x, l[i + 1].x) - tol, std::min(l[i].y, l[i + 1].y) - tol,
                       std::max(l[i].x, l[i + 1].x) + tol, std::max(l[i].y, l[i + 1].y) + tol});
      s += distance(l[i], l[i + 1]);
    }
  }

  // Segment pairs of the same layer that come within the tolerance: cut both where they cross,
  // and where a vertex of one lies within the tolerance of the other.
  auto add_event_on = [&](const Segment& seg, Point p) {
    const Polyline& l = lines[seg.axis];
    double t = segment_parameter(l[seg.index], l[seg.index + 1], p);
    double abscissa = seg.start_abscissa + t * distance(l[seg.index], l[seg.index + 1]);
    events.push_back({seg.axis, abscissa, l[seg.index] + t * (l[seg.index + 1] - l[seg.index]), false,
                      axes[seg.axis].layer});
  };
  for_each_overlapping_pair(boxes, [&](std::size_t i, std::size_t j) {
    const Segment& s1 = segments[i];
    const Segment& s2 = segments[j];
    if (axes[s1.axis].layer != axes[s2.axis].layer) return;
    if (s1.axis == s2.axis && (s1.index + 1 == s2.index || s2.index + 1 == s1.index)) return;  // neighbours
    const Polyline& l1 = lines[s1.axis];
    const Polyline& l2 = lines[s2.axis];
    Point a0 = l1[s1.index], a1 = l1[s1.index + 1], b0 = l2[s2.index], b1 = l2[s2.index + 1];
    for (Point v : {a0, a1}) {
      double t = segment_parameter(b0, b1, v);
      if (distance(v, b0 + t * (b1 - b0)) <= tol) {
        add_event_on(s1, v);
        add_event_on(s2, v);
      }
    }
    for (Point v : {b0, b1}) {
      double t = segment_parameter(a0, a1, v);
      if (distance(v, a0 + t * (a1 - a0)) <= tol) {
        add_event_on(s2, v);
        add_event_on(s1, v);
      }
    }
    // Proper crossing of the interiors.
    Point r = a1 - a0, s = b1 - b0;
    double denom = cross(r, s);
    if (denom != 0.0) {
      double t = cross(b0 - a0, s) / denom;
      double u = cross(b0 - a0, r) / denom;
      if (t > 0.0 && t < 1.0 && u > 0.0 && u < 1.0) {
        Point x = a0 + t * r;
        add_event_on(s1, x);
        add_event_on(s2, x);
      }
    }
  });

  // Cluster events into nodes: within the tolerance, and on the same layer unless both are axis
  // ends (a bridge's end meets the street below it at ground level).
  UnionFind clusters(events.size());
  {
    std::unordered_map<std::int64_t, std::vector<std::size_t>> grid;
    auto cell = [&](double v) { return static_cast<std::int64_t>(std::floor(v / tol)); };
    auto key = [](std::int64_t cx, std::int64_t cy) { return cx * 73856093LL ^ cy * 19349663LL; };
    InterruptPoller poller(4096);
    for (std::size_t e = 0; e < events.size(); ++e) {
      poller.tick();
      std::int64_t cx = cell(events[e].point.x), cy = cell(events[e].point.y);
      for (std::int64_t dx = -1; dx <= 1; ++dx) {
        for (std::int64_t dy = -1; dy <= 1; ++dy) {
          auto it = grid.find(key(cx + dx, cy + dy));
          if (it == grid.end()) continue;
          for (std::size_t o : it->second) {
            const Event& a = events[e];
            const Event& b = events[o];
            if (distance(a.point, b.point) > tol) continue;
            if (a.layer != b.layer && !(a.axis_end && b.axis_end)) continue;
            clusters.unite(e, o);
          }
        }
      }
      grid[key(cx, cy)].push_back(e);
    }
  }

  // Nodes at the mean position of their events. The points are summed in sorted order, so a
  // node's position (and id) does not depend on the order axes came in: a recompute of a few
  // axes finds the same node as a run on the whole model.
  std::vector<std::size_t> node_of_event(events.size());
  std::map<std::size_t, std::size_t> node_of_root;
  std::vector<std::vector<Point>> members;
  std::vector<int> layers;
  for (std::size_t e = 0; e < events.size(); ++e) {
    std::size_t root = clusters.find(e);
    auto [it, inserted] = node_of_root.emplace(root, members.size());
    if (inserted) {
      members.emplace_back();
      layers.push_back(events[e].layer);
    }
    std::size_t n = it->second;
    node_of_event[e] = n;
    members[n].push_back(events[e].point);
    layers[n] = std::min(layers[n], events[e].layer);
  }
  std::vector<std::vector<std::int64_t>> axes_of_node(members.size());
  for (std::size_t e = 0; e < events.size(); ++e) axes_of_node[node_of_event[e]].push_back(axes[events[e].axis].id);
  for (auto& ids : axes_of_node) {
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  }
  std::unordered_set<std::int64_t> used_ids;
  for (std::size_t n = 0; n < members.size(); ++n) {
    std::sort(members[n].begin(), members[n].end(),
              [](Point a, Point b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    Point sum{0.0, 0.0};
    for (const Point& p : members[n]) sum = sum + p;
    Point position = (1.0 / static_cast<double>(members[n].size())) * sum;
    std::int64_t id = node_id_for(position, layers[n]);
    while (!used_ids.insert(id).second) id = static_cast<std::int64_t>(mix(static_cast<std::uint64_t>(id)) & 0x7fffffffffffffffULL);
    topo.nodes.push_back({id, position, layers[n], std::move(axes_of_node[n])});
  }

  // Cut every axis at its events; each piece between two nodes is an edge.
  std::vector<std::vector<std::size_t>> events_of_axis(axes.size());
  for (std::size_t e = 0; e < events.size(); ++e) events_of_axis[events[e].axis].push_back(e);
  for (std::size_t a = 0; a < axes.size(); ++a) {
    if (!usable[a]) continue;
    auto& ev = events_of_axis[a];
    std::sort(ev.begin(), ev.end(), [&](std::size_t x, std::size_t y) {
      return events[x].abscissa < events[y].abscissa || (events[x].abscissa == events[y].abscissa && x < y);
    });
    // Consecutive cuts at the same node collapse into one.
    std::vector<std::pair<double, std::size_t>> cuts;
    for (std::size_t e : ev) {
      std::size_t n = node_of_event[e];
      if (!cuts.empty() && cuts.back().second == n && events[e].abscissa - cuts.back().first <= 2 * tol) continue;
      cuts.push_back({events[e].abscissa, n});
    }
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
      auto [s0, n0] = cuts[k];
      auto [s1, n1] = cuts[k + 1];
      Polyline piece = substring(lines[a], s0, s1);
      piece.front() = topo.nodes[n0].position;
      piece.back() = topo.nodes[n1].position;
      piece = without_repeated_points(piece, 1e-9);
      double len = length(piece);
      if (piece.size() < 2 || len <= 1e-9 || (n0 == n1 && len <= 2 * tol)) {
        if (n0 == n1 && len > 1e-9) {
          topo.issues.push_back({axes[a].id, "loop_dropped", "a loop shorter than twice the snap tolerance",
                                 std::llround(s0 * 1000.0), topo.nodes[n0].id});
        }
        continue;
      }
      topo.edges.push_back({a, axes[a].id, std::llround(s0 * 1000.0), n0, n1, std::move(piece), false});
    }
  }

  // Duplicates: same pair of nodes and every vertex of one within the tolerance of the other.
  std::map<std::pair<std::size_t, std::size_t>, std::vector<std::size_t>> by_nodes;
  for (std::size_t e = 0; e < topo.edges.size(); ++e) {
    const TopologyEdge& edge = topo.edges[e];
    auto key = std::minmax(edge.from_node, edge.to_node);
    auto& same = by_nodes[{key.first, key.second}];
    for (std::size_t other : same) {
      const TopologyEdge& o = topo.edges[other];
      if (o.duplicate) continue;
      bool close = std::all_of(edge.line.begin(), edge.line.end(), [&](Point p) { return project(o.line, p).distance <= tol; }) &&
                   std::all_of(o.line.begin(), o.line.end(), [&](Point p) { return project(edge.line, p).distance <= tol; });
      if (close) {
        topo.edges[e].duplicate = true;
        topo.issues.push_back({edge.axis_id, "duplicate_axis", "it runs along axis " + std::to_string(o.axis_id), edge.part,
                               topo.nodes[edge.from_node].id});
        break;
      }
    }
    same.push_back(e);
  }
  return topo;
}

}  // namespace streetgen::core
