"""Where a grown network's orientation order φ comes from (bench/patches/run.sh).

φ (network_stats' orientation_order) weighs each street (degree-2 chains merged) by its length
at the bearing of its chord. A grown street (grow_patches returns one row per segment) is one
patch's street as its example drew it (its segments all from one patch; two placements of one
patch side by side count as one), patch streets
joined at seams (segments of two patches or more: a connector meeting another patch's connector
mid-street, a dead end slid onto a patch's vertex), a chain of patch and statistical segments
(joins and fallback streets continuing a patch street), or statistical segments alone. This script splits each grown network's streets by that kind and prints,
per example: the example's φ, the grown networks' (mean over the seeds), and over all seeds
together each kind's share of the length inside the window and the φ of that kind's streets alone. A kind whose φ alone is far under the example's is
where the network loses its order.

Reads CSV rows `source,name,seed,patch,ax,ay,bx,by,length` on stdin, one per edge (all of them, so
that the degrees are right): source example or grown, patch the id of the patch that made the edge
(its origin's; empty: statistical or a join), (ax, ay) and (bx, by) its ends, length its length
inside the window (the region shrunk by 50 m; 0 outside).
Chains are merged through nodes of degree 2 (ends equal to the millimetre), as network_stats'
simplification does; a chain's bearing is between its two ends.
"""
import collections
import csv
import math
import sys

from sampling_noise import orientation_order  # (this folder: the script's own is on sys.path)

KINDS = ("one patch's street", "patch streets at seams", "patch and statistical", "statistical")


def phi(streets):
    """φ of (length, bearing) pairs as network_stats computes it (sampling_noise's); NaN for none."""
    return orientation_order(streets) if streets else float("nan")


def key(x, y):
    return (round(x * 1000.0), round(y * 1000.0))


def streets(edges):
    """(kind, length inside the window, bearing) of each chain of edges through nodes of degree 2."""
    at = collections.defaultdict(list)
    for i, (a, b, _, _) in enumerate(edges):
        at[a].append(i)
        at[b].append(i)
    used = [False] * len(edges)
    out = []

    def walk(start, i):
        ends, cur, length, patches = [start], start, 0.0, []
        while True:
            used[i] = True
            a, b, inside, patch = edges[i]
            cur = b if a == cur else a
            length += inside
            patches.append(patch)
            ends.append(cur)
            nxt = [j for j in at[cur] if not used[j]]
            if len(at[cur]) != 2 or not nxt:
                break
            i = nxt[0]
        if all(patches):
            kind = KINDS[0] if len(set(patches)) == 1 else KINDS[1]
        else:
            kind = KINDS[2] if any(patches) else KINDS[3]
        return kind, length, ends[0], ends[-1]

    for node, incident in at.items():
        if len(incident) != 2:
            for i in incident:
                if not used[i]:
                    out.append(walk(node, i))
    for i in range(len(edges)):  # rings of degree-2 nodes
        if not used[i]:
            out.append(walk(edges[i][0], i))
    result = []
    for kind, length, a, b in out:
        if a == b or length <= 0.0:
            continue  # a loop has no bearing (network_stats skips it too)
        bearing = math.fmod(math.degrees(math.atan2(b[0] - a[0], b[1] - a[1])) + 360.0, 360.0)
        result.append((kind, length, bearing))
    return result


def main():
    edges = collections.defaultdict(list)  # (source, name, seed) -> [(a, b, inside, patch id or "")]
    for source, name, seed, patch, ax, ay, bx, by, length in csv.reader(sys.stdin):
        edges[(source, name, seed)].append((key(float(ax), float(ay)), key(float(bx), float(by)), float(length),
                                            patch))
    names = sorted({name for (_, name, _) in edges})
    print(f"{'name':22s} {'phi example':>11s} {'phi grown':>9s}  {'streets':22s} {'share':>7s} {'phi alone':>9s}")
    for name in names:
        example = [(length, bearing) for _, length, bearing in streets(edges[("example", name, "0")])]
        grown = collections.defaultdict(list)
        per_seed = []
        length_total = 0.0
        for (source, n, seed), rows in sorted(edges.items()):
            if source != "grown" or n != name:
                continue
            s = streets(rows)
            per_seed.append(phi([(length, bearing) for _, length, bearing in s]))
            for kind, length, bearing in s:
                grown[kind].append((length, bearing))
                length_total += length
        if not per_seed:
            continue
        first = f"{name:22s} {phi(example):11.3f} {sum(per_seed) / len(per_seed):9.3f}"
        for kind in KINDS:
            share = sum(length for length, _ in grown[kind]) / length_total if length_total > 0 else 0.0
            label = first if kind == KINDS[0] else ""
            print(f"{label:44s}  {kind:22s} {100.0 * share:5.1f} % {phi(grown[kind]):9.3f}")


if __name__ == "__main__":
    main()
