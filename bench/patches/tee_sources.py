"""Where a grown network's T-junctions come from (bench/patches/run.sh).

The 4-way share is crossings over junctions. A T can become a crossing only by a street going on
across it: to a T facing it (two T's become crossings, no junction more) or to the street ahead
(a junction more, and a new T at the far end unless that street ends in a node). So where the T's
are, and what lies at the far end of each T's lone street, says what a rule could still gain.

For each example and each grown network, inside the window (the region shrunk by 50 m), every
node of degree 3 whose two other streets run on within 30 degrees of each other (a T; the others
are counted as skew) is classed by its lone street: statistical (a fallback street or a join,
`grow_parametric` origin) or a patch's, main or local, and by what that street reaches at its far
end once degree-2 nodes are passed: a crossing, a T, a dead end or another junction. Printed per
example: the example's junctions, crossings and T's, and the same as a mean per grown network;
then the T's by class (the example's, and the mean per grown network), with the T's the example's
4-way share would leave at the grown networks' junctions. Then the junctions split by level: those
on a main street (one of their streets main) and the local ones, each with its share of crossings,
and the share of crossings the growths would have with the example's split at their own shares per
level. Junctions on main streets are crossings more often than local ones in most examples, so a
growth with fewer main streets has fewer crossings even where each level's share is the example's.

Reads CSV rows `source,name,seed,kind,level,inside_a,inside_b,coords` on stdin, one per edge:
source example or grown; kind patch or statistical; level main or local; inside_a / inside_b 1
when the edge's first / last point lies in the window; coords the edge's points as
`x y;x y;...`. Nodes are ends equal to the centimetre.
"""
import collections
import csv
import math
import sys

TEE_WINDOW = math.radians(30.0)


def key(p):
    return (round(p[0] * 100.0), round(p[1] * 100.0))


def wrap(a):
    return (a + math.pi) % (2.0 * math.pi) - math.pi


def tees(edges):
    """(junctions, crossings, Counter of T classes, Counter of junctions by (on a main street, crossing))
    of one network's edges, inside the window."""
    arms = collections.defaultdict(list)  # node -> [(edge, other end node, bearing)]
    inside = {}
    for i, e in enumerate(edges):
        pts = e["pts"]
        a, b = key(pts[0]), key(pts[-1])
        inside[a] = e["inside_a"]
        inside[b] = e["inside_b"]
        arms[a].append((i, b, math.atan2(pts[1][1] - pts[0][1], pts[1][0] - pts[0][0])))
        arms[b].append((i, a, math.atan2(pts[-2][1] - pts[-1][1], pts[-2][0] - pts[-1][0])))
    junctions = crossings = 0
    classes = collections.Counter()
    by_level = collections.Counter()  # (on a main street, crossing) -> junctions
    for node, at in arms.items():
        if not inside[node] or len(at) < 3:
            continue
        junctions += 1
        crossings += len(at) >= 4
        by_level[(any(edges[i]["level"] == "main" for i, _, _ in at), len(at) >= 4)] += 1
        if len(at) != 3:
            continue
        best, lone = math.inf, None
        for k in range(3):
            others = [at[j][2] for j in range(3) if j != k]
            off = math.pi - abs(wrap(others[0] - others[1]))
            if off < best:
                best, lone = off, k
        if best > TEE_WINDOW:
            classes[("skew", "", "")] += 1
            continue
        edge, cur, _ = at[lone]
        e = edges[edge]
        steps = 0
        while len(arms[cur]) == 2 and steps < 1000:  # on through degree-2 nodes
            edge, cur = next((i, other) for i, other, _ in arms[cur] if i != edge)
            steps += 1
        far = {1: "a dead end", 3: "a T", 4: "a crossing"}.get(len(arms[cur]), "another junction")
        classes[(e["kind"], e["level"], far)] += 1
    assert sum(by_level.values()) == junctions and by_level[(True, True)] + by_level[(False, True)] == crossings
    return junctions, crossings, classes, by_level


def level_split(by_level, count=1):
    """Junctions on a main street and local ones (means over `count` networks), each level's share of crossings."""
    split = {}
    for main in (True, False):
        n = (by_level[(main, True)] + by_level[(main, False)]) / count
        split[main] = (n, by_level[(main, True)] / count / n if n else 0.0)
    return split


def main():
    networks = collections.defaultdict(list)
    for source, name, seed, kind, level, inside_a, inside_b, coords in csv.reader(sys.stdin):
        pts = [tuple(map(float, p.split())) for p in coords.split(";")]
        networks[(name, source, int(seed))].append(
            {"kind": kind, "level": level, "inside_a": inside_a == "1", "inside_b": inside_b == "1", "pts": pts})
    names = sorted({n for n, _, _ in networks})
    print(f"{'name':22} {'':8} {'junctions':>9} {'crossings':>9} {'Ts':>6} {'4-way':>6}")
    for name in names:
        ex = tees(networks[(name, "example", 0)])
        grown = [tees(edges) for (n, source, _), edges in sorted(networks.items()) if n == name and source == "grown"]
        if not grown:
            continue
        count = len(grown)
        jg = sum(g[0] for g in grown) / count
        xg = sum(g[1] for g in grown) / count
        tg = sum(sum(v for k, v in g[2].items() if k[0] != "skew") for g in grown) / count
        te = sum(v for k, v in ex[2].items() if k[0] != "skew")
        share = ex[1] / ex[0] if ex[0] else float("nan")
        print(f"{name:22} {'example':8} {ex[0]:9d} {ex[1]:9d} {te:6d} {share:6.3f}")
        print(f"{'':22} {'grown':8} {jg:9.1f} {xg:9.1f} {tg:6.1f} {xg / jg if jg else float('nan'):6.3f}"
              f"   (at the example's share these junctions would hold {jg * (1 - share):.1f} T's and other junctions)")
        total = collections.Counter()
        for g in grown:
            total.update(g[2])
        print(f"{'':22} {'':8} {'example':>9} {'grown':>9}  T's by their lone street (the example's are all a patch's)")
        for cls in sorted(set(total) | set(ex[2]), key=lambda c: -total[c]):
            if total[cls] / count >= 0.5 or ex[2][cls] > 0:
                kind, level, far = cls
                label = "skew (no lone street)" if kind == "skew" else f"{kind}, {level}, its far end {far}"
                print(f"{'':22} {'':8} {ex[2][cls]:9d} {total[cls] / count:9.1f}  {label}")
        levels = collections.Counter()
        for g in grown:
            levels.update(g[3])
        ex_split, grown_split = level_split(ex[3]), level_split(levels, count)
        on_example_split = sum(ex_split[m][0] * grown_split[m][1] for m in (True, False)) / ex[0] if ex[0] else float("nan")
        print(f"{'':22} {'':8} by level: on a main street {ex_split[True][0]:.0f} ({ex_split[True][1]:.3f} crossings) / "
              f"{grown_split[True][0]:.1f} ({grown_split[True][1]:.3f}), local {ex_split[False][0]:.0f} "
              f"({ex_split[False][1]:.3f}) / {grown_split[False][0]:.1f} ({grown_split[False][1]:.3f}), example / grown; "
              f"with the example's split the growths' 4-way share would be {on_example_split:.3f}")


if __name__ == "__main__":
    main()
