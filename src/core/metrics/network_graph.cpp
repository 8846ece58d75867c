#include "core/metrics/network_graph.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <string>
#include <unordered_map>

#include "core/error.hpp"
#include "core/interrupts.hpp"
#include "core/streets/topology.hpp"
#include "core/union_find.hpp"

namespace streetgen::core {
namespace {


std::uint64_t cell_key(std::int64_t cx, std::int64_t cy) {
  return (static_cast<std::uint64_t>(cx) * 0x9E3779B97F4A7C15ULL) ^ static_cast<std::uint64_t>(cy);
}

// Endpoints within `tol` of each other (single linkage) get one node id; 0: equal points only.
std::vector<std::size_t> cluster_points(const std::vector<Point>& pts, double tol, std::size_t& cluster_count) {
  UnionFind uf(pts.size());
  InterruptPoller poller;
  if (tol == 0.0) {
    auto bits = [](double v) {
      v = v == 0.0 ? 0.0 : v;  // -0 and +0 are one place
      std::uint64_t b;
      std::memcpy(&b, &v, sizeof b);
      return b;
    };
    std::unordered_map<std::uint64_t, std::vector<std::size_t>> seen;
    seen.reserve(pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) {
      poller.tick();
      auto& bucket =
          seen[cell_key(static_cast<std::int64_t>(bits(pts[i].x)), static_cast<std::int64_t>(bits(pts[i].y)))];
      for (std::size_t j : bucket) {
        if (pts[j].x == pts[i].x && pts[j].y == pts[i].y) {
          uf.unite(i, j);
          break;
        }
      }
      bucket.push_back(i);
    }
  } else {
    std::unordered_map<std::uint64_t, std::vector<std::size_t>> grid;
    grid.reserve(pts.size());
    auto cell = [tol](double v) { return static_cast<std::int64_t>(std::floor(v / tol)); };
    for (std::size_t i = 0; i < pts.size(); ++i) {
      poller.tick();
      std::int64_t cx = cell(pts[i].x), cy = cell(pts[i].y);
      for (std::int64_t dx = -1; dx <= 1; ++dx) {
        for (std::int64_t dy = -1; dy <= 1; ++dy) {
          auto it = grid.find(cell_key(cx + dx, cy + dy));
          if (it == grid.end()) continue;
          for (std::size_t j : it->second) {
            if (distance(pts[i], pts[j]) <= tol) uf.unite(i, j);
          }
        }
      }
      grid[cell_key(cx, cy)].push_back(i);
    }
  }
  // Dense ids in order of first appearance: the same input gives the same node numbering.
  std::vector<std::size_t> id(pts.size());
  std::vector<std::size_t> root_id(pts.size(), SIZE_MAX);
  cluster_count = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    std::size_t r = uf.find(i);
    if (root_id[r] == SIZE_MAX) root_id[r] = cluster_count++;
    id[i] = root_id[r];
  }
  return id;
}

bool same_course(const Polyline& p, const Polyline& q) {
  if (p.size() != q.size()) return false;
  bool forward = true, backward = true;
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n && (forward || backward); ++i) {
    forward = forward && p[i].x == q[i].x && p[i].y == q[i].y;
    backward = backward && p[i].x == q[n - 1 - i].x && p[i].y == q[n - 1 - i].y;
  }
  return forward || backward;
}

void compute_degrees(NetworkGraph& g) {
  g.degree.assign(g.nodes.size(), 0);
  for (const NetworkEdge& e : g.edges) {
    ++g.degree[e.a];
    ++g.degree[e.b];
  }
}

// OSMnx-style simplification: every chain of edges through nodes with exactly two edge ends
// (and no self-loop) becomes one edge between the chain's end nodes. Rings made only of such
// nodes are left as they are, as OSMnx leaves them.
void simplify_graph(NetworkGraph& g) {
  const std::size_t n = g.nodes.size();
  std::vector<std::vector<std::size_t>> incident(n);
  for (std::size_t e = 0; e < g.edges.size(); ++e) {
    incident[g.edges[e].a].push_back(e);
    if (g.edges[e].b != g.edges[e].a) incident[g.edges[e].b].push_back(e);
  }
  auto interstitial = [&](std::size_t v) {
    return g.degree[v] == 2 && incident[v].size() == 2 && incident[v][0] != incident[v][1];
  };
  std::vector<bool> used(g.edges.size(), false);
  std::vector<NetworkEdge> out;
  out.reserve(g.edges.size());
  InterruptPoller poller;
  for (std::size_t start = 0; start < n; ++start) {
    if (interstitial(start)) continue;
    for (std::size_t first : incident[start]) {
      if (used[first]) continue;
      NetworkEdge chain;
      chain.a = start;
      std::size_t at = start, e = first;
      for (;;) {
        poller.tick();
        used[e] = true;
        const NetworkEdge& edge = g.edges[e];
        Polyline part = edge.line;
        std::size_t next = edge.a == at ? edge.b : edge.a;
        if (edge.a != at) std::reverse(part.begin(), part.end());
        chain.line.insert(chain.line.end(), chain.line.empty() ? part.begin() : part.begin() + 1, part.end());
        chain.length += edge.length;
        at = next;
        if (!interstitial(at)) break;
        e = incident[at][0] == e ? incident[at][1] : incident[at][0];
        if (used[e]) break;
      }
      chain.b = at;
      out.push_back(std::move(chain));
    }
  }
  for (std::size_t e = 0; e < g.edges.size(); ++e) {
    if (!used[e]) out.push_back(g.edges[e]);  // rings of degree-2 nodes
  }
  // Drop the nodes no edge uses any more, renumbering in the old order.
  std::vector<std::size_t> new_id(n, SIZE_MAX);
  std::vector<Point> nodes;
  auto keep = [&](std::size_t v) {
    if (new_id[v] == SIZE_MAX) {
      new_id[v] = 0;  // mark; numbered below
    }
  };
  for (const NetworkEdge& e : out) {
    keep(e.a);
    keep(e.b);
  }
  std::size_t next = 0;
  for (std::size_t v = 0; v < n; ++v) {
    if (new_id[v] != SIZE_MAX) {
      new_id[v] = next++;
      nodes.push_back(g.nodes[v]);
    }
  }
  for (NetworkEdge& e : out) {
    e.a = new_id[e.a];
    e.b = new_id[e.b];
  }
  g.merged_nodes += n - nodes.size();
  g.nodes = std::move(nodes);
  g.edges = std::move(out);
  compute_degrees(g);
}

}  // namespace

NetworkGraph build_network_graph(const std::vector<Polyline>& input, const NetworkGraphOptions& options,
                                 const std::vector<int>& layers) {
  const double tol = options.node_tolerance;
  if (!std::isfinite(tol) || tol < 0.0) {
    throw_invalid_argument("node_tolerance must be a finite number >= 0", "It is " + std::to_string(tol) + ".");
  }
  NetworkGraph g;
  std::vector<Polyline> lines;
  if (options.split_at_crossings) {
    std::vector<TopologyAxis> axes(input.size());
    for (std::size_t i = 0; i < input.size(); ++i) {
      axes[i].id = static_cast<std::int64_t>(i);
      axes[i].line = input[i];
      axes[i].layer = i < layers.size() ? layers[i] : 0;
    }
    Topology topo = build_topology(axes, tol);
    for (const TopologyIssue& issue : topo.issues) {
      if (issue.kind == "degenerate_axis" || issue.kind == "loop_dropped") ++g.collapsed_edges;
    }
    for (TopologyEdge& e : topo.edges) {
      if (e.duplicate) {
        ++g.duplicate_edges;
      } else {
        lines.push_back(std::move(e.line));
      }
    }
  } else {
    lines.reserve(input.size());
    for (const Polyline& l : input) lines.push_back(without_repeated_points(l, 0.0));
  }
  const double merge_tol = options.split_at_crossings ? 0.0 : tol;  // the topology merged already

  std::vector<Point> ends;
  ends.reserve(2 * lines.size());
  for (const Polyline& l : lines) {
    if (l.size() < 2) {
      ends.push_back(l.empty() ? Point{} : l.front());
      ends.push_back(l.empty() ? Point{} : l.front());
    } else {
      ends.push_back(l.front());
      ends.push_back(l.back());
    }
  }
  std::size_t node_count = 0;
  std::vector<std::size_t> node_of = cluster_points(ends, merge_tol, node_count);
  // A node sits at the mean of its endpoints, summed in input order (deterministic).
  std::vector<Point> sum(node_count);
  std::vector<std::size_t> members(node_count, 0), first(node_count, SIZE_MAX);
  for (std::size_t i = 0; i < ends.size(); ++i) {
    sum[node_of[i]] = sum[node_of[i]] + ends[i];
    ++members[node_of[i]];
    if (first[node_of[i]] == SIZE_MAX) first[node_of[i]] = i;
  }
  std::vector<Point> position(node_count);
  for (std::size_t v = 0; v < node_count; ++v) {
    // Unmerged nodes keep their exact coordinates (no rounding from the mean).
    position[v] =
        members[v] == 1 || merge_tol == 0.0 ? ends[first[v]] : (1.0 / static_cast<double>(members[v])) * sum[v];
  }

  // Edges with snapped ends; collapsed ones and exact duplicates dropped.
  std::vector<std::size_t> used_id(node_count, SIZE_MAX);
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> by_pair;
  InterruptPoller poller;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    poller.tick();
    Polyline& l = lines[i];
    if (l.size() < 2) {
      ++g.collapsed_edges;
      continue;
    }
    std::size_t a = node_of[2 * i], b = node_of[2 * i + 1];
    l.front() = position[a];
    l.back() = position[b];
    l = without_repeated_points(l, 0.0);
    double len = l.size() < 2 ? 0.0 : length(l);
    if (a == b && (len <= 2.0 * merge_tol || l.size() < 3)) {
      ++g.collapsed_edges;
      continue;
    }
    auto& bucket =
        by_pair[cell_key(static_cast<std::int64_t>(std::min(a, b)), static_cast<std::int64_t>(std::max(a, b)))];
    bool duplicate = false;
    for (std::size_t k : bucket) {
      const NetworkEdge& o = g.edges[k];
      if (std::min(o.a, o.b) == std::min(a, b) && std::max(o.a, o.b) == std::max(a, b) && same_course(o.line, l)) {
        duplicate = true;
        break;
      }
    }
    if (duplicate) {
      ++g.duplicate_edges;
      continue;
    }
    for (std::size_t v : {a, b}) {
      if (used_id[v] == SIZE_MAX) {
        used_id[v] = g.nodes.size();
        g.nodes.push_back(position[v]);
      }
    }
    bucket.push_back(g.edges.size());
    g.edges.push_back({used_id[a], used_id[b], std::move(l), len});
  }
  compute_degrees(g);
  if (options.simplify) simplify_graph(g);
  return g;
}

}  // namespace streetgen::core
