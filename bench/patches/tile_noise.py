"""The realism goal as the example itself would score it, by tiles (bench/patches/run.sh).

The goal asks, for each grown network (one seed), a per-pair median of the eight headline
metrics' relative differences of 5 % or less and no metric past 15 %. sampling_noise.py resamples
three metrics part by part; this script asks the whole question at once, of a network drawn from
the example's own streets. It cuts the window (the hull shrunk by 50 m) into square tiles and draws
as many tiles as there are, with replacement, 1,000 times (a fixed seed per example and tile
size): the drawn tiles' streets, nodes and blocks make one resampled network. That keeps the streets of a tile together
(neighbouring blocks and junctions are alike), so it is a block bootstrap at the tile's scale; a
larger tile keeps more together and spreads more.

Each resample is scored as compare_networks scores a growth: the relative difference of each
headline metric from the example's own (all tiles once), the per-pair median of their absolute
values (each capped at 100 %; where the example's value is 0, a metric counts as 0 when the
resample's is 0 too and is left out otherwise, as in compare_networks), and the values past 15 %.
The goal also asks that the example's junction mix be kept: the 4-way and dead-end shares within 5
percentage points of the example's. A resample misses that when either share is farther off. The
share of resamples (and of growths) that meet all three is printed too.

Reads CSV rows on stdin:
  tile,name,size,id,area,length,degrees,histogram
      a tile: its area and street length inside the window (m², m), its nodes' degrees (space
      separated; network_stats' degrees inside the tile, with their full degree) and its
      orientation histogram (36 shares, network_stats' orientation_histogram of the tile)
  block,name,size,id,area,,,
      a block of the window (network_stats' blocks), in the tile holding its point on surface
  reported,name,,metric,value,,,
      the window's own value as network_stats computes it (printed beside the script's own)
  grown,name,,seed,per_pair_median,,metrics,mix_differences
      a growth as compare_networks scored it, printed beside the resamples: its per-pair median (a
      share); the metrics whose relative difference is past 15 % (space separated; the headline ones
      count); its 4-way and dead-end shares' differences from the example's (shares, signed, space
      separated)
"""
import collections
import csv
import random
import statistics
import sys

from sampling_noise import BINS, order_of_histogram  # (beside this script)

RESAMPLES = 1000
MIX_GAP = 0.05  # the junction mix kept: the 4-way and dead-end shares within 5 percentage points
MIX = ("degree4_share", "dead_end_share")
HEADLINE = ["street_density", "intersection_density", "mean_degree", "dead_end_share", "degree4_share",
            "connected_node_ratio", "orientation_order", "block_area_median"]
SHORT = {"street_density": "street", "intersection_density": "junct", "mean_degree": "degree",
         "dead_end_share": "dead", "degree4_share": "4way", "connected_node_ratio": "cnr",
         "orientation_order": "phi", "block_area_median": "blocks"}


class Tile:
    def __init__(self, area, length, degrees, histogram):
        self.area = area
        self.length = length
        self.degrees = degrees
        # network_stats' histogram holds shares of the tile's street length: back to metres, so
        # that tiles add up
        self.histogram = [length * share for share in histogram] if histogram else [0.0] * BINS
        self.blocks = []


def metrics(tiles):
    """The eight headline metrics of the network the tiles make together (network_stats' definitions)."""
    area = sum(t.area for t in tiles)
    length = sum(t.length for t in tiles)
    degrees = [d for t in tiles for d in t.degrees]
    nodes = len(degrees)
    histogram = [sum(t.histogram[i] for t in tiles) for i in range(BINS)]
    blocks = [b for t in tiles for b in t.blocks]
    dead = sum(d == 1 for d in degrees)
    return {
        "street_density": length / area * 1000.0,           # km per km²
        "intersection_density": sum(d >= 3 for d in degrees) / area * 1e6,
        "mean_degree": sum(degrees) / nodes if nodes else 0.0,
        "dead_end_share": dead / nodes if nodes else 0.0,
        "degree4_share": sum(d == 4 for d in degrees) / nodes if nodes else 0.0,
        "connected_node_ratio": (nodes - dead) / nodes if nodes else 0.0,
        "orientation_order": order_of_histogram(histogram),
        "block_area_median": statistics.median(blocks) if blocks else 0.0,
    }


def score(values, own):
    """compare_networks' per-pair median and the values past 15 % of one resample."""
    differences = {}
    for metric in HEADLINE:
        if own[metric] != 0.0:
            differences[metric] = min(abs(values[metric] - own[metric]) / abs(own[metric]), 1.0)
        elif values[metric] == 0.0:
            differences[metric] = 0.0  # both 0: equal (compare_networks' relative_difference)
    return statistics.median(differences.values()), differences


def mix_gap(differences):
    """The larger of the 4-way and dead-end shares' differences from the example's (a share)."""
    return max(abs(d) for d in differences)


def goal_met(median, past15, gap):
    """The whole goal on one network: per-pair median 5 % or less, no headline value past 15 %, the
    junction mix within 5 percentage points."""
    return median <= 0.05 and past15 == 0 and gap <= MIX_GAP


def spread(differences):
    """Mean and standard deviation of differences in shares, in percentage points."""
    if len(differences) < 2:
        return "-"
    return f"{100.0 * statistics.mean(differences):+.1f} ± {100.0 * statistics.stdev(differences):.1f}"


def main():
    tiles = collections.defaultdict(dict)  # (name, size) -> id -> Tile
    reported = {}
    grown = collections.defaultdict(list)  # name -> (per-pair median, values past 15 %, their metrics, mix gap) per seed
    grown_mix = collections.defaultdict(list)  # name -> (4-way, dead-end share differences) per seed
    for row in csv.reader(sys.stdin):
        if row[0] == "tile":
            _, name, size, tile_id, area, length, degrees, histogram = row
            tiles[(name, float(size))][tile_id] = Tile(float(area), float(length),
                                                       [int(d) for d in degrees.split()],
                                                       [float(h) for h in histogram.split()])
        elif row[0] == "block":
            _, name, size, tile_id, area = row[:5]
            tiles[(name, float(size))][tile_id].blocks.append(float(area))
        elif row[0] == "reported":
            _, name, _, metric, value = row[:5]
            reported[(name, metric)] = float(value)
        elif row[0] == "grown":
            _, name, _, _, median, _, past_metrics, mix = row[:8]
            past = [m for m in past_metrics.split() if m in HEADLINE]
            mix = tuple(float(d) for d in mix.split())
            grown[name].append((float(median), len(past), past, mix_gap(mix)))
            grown_mix[name].append(mix)
    print(f"{'name':22s} | {'tile_m':>6s} | {'tiles':>5s} | {'pairs_over_5_pct':>16s} | {'past_15_per_pair':>16s} | "
          f"{'grown_over_5_pct':>16s} | {'grown_past_15':>13s} | {'mix_off_5pp_pct':>15s} | {'grown_mix_off_pct':>17s} | "
          f"{'goal_met_pct':>12s} | {'grown_goal_met_pct':>18s} | past 15 % by metric, resamples / growths (%)")
    checks = []
    mix_rows = []
    for key in sorted(tiles):
        name, size = key
        own_tiles = list(tiles[key].values())
        rng = random.Random(f"{name} {size:g}")  # each example's own draws, whichever others run
        own = metrics(own_tiles)
        checks.append((name, size, own))
        over5 = 0
        past15 = 0
        mix_off = 0
        met = 0
        mix_differences = []
        past_by_metric = collections.Counter()
        for _ in range(RESAMPLES):
            sample = [own_tiles[rng.randrange(len(own_tiles))] for _ in own_tiles]
            values = metrics(sample)
            median, differences = score(values, own)
            over5 += median > 0.05
            mix = tuple(values[m] - own[m] for m in MIX)
            gap = mix_gap(mix)
            mix_off += gap > MIX_GAP
            mix_differences.append(mix)
            past = [metric for metric, difference in differences.items() if difference > 0.15]
            past15 += len(past)
            past_by_metric.update(past)
            met += goal_met(median, len(past), gap)
        seeds = grown.get(name, [])

        def growths_past(metric):
            return f"/{100.0 * sum(metric in past for _, _, past, _ in seeds) / len(seeds):.0f}" if seeds else ""

        by_metric = " ".join(f"{SHORT[m]} {100.0 * past_by_metric[m] / RESAMPLES:.1f}{growths_past(m)}" for m in HEADLINE)
        grown_over5 = f"{100.0 * sum(m > 0.05 for m, _, _, _ in seeds) / len(seeds):16.1f}" if seeds else f"{'':>16s}"
        grown_past15 = f"{sum(p for _, p, _, _ in seeds) / len(seeds):13.2f}" if seeds else f"{'':>13s}"
        grown_mix_off = f"{100.0 * sum(g > MIX_GAP for _, _, _, g in seeds) / len(seeds):17.1f}" if seeds else f"{'':>17s}"
        grown_met = (f"{100.0 * sum(goal_met(m, p, g) for m, p, _, g in seeds) / len(seeds):18.1f}" if seeds
                     else f"{'':>18s}")
        print(f"{name:22s} | {size:6.0f} | {len(own_tiles):5d} | {100.0 * over5 / RESAMPLES:16.1f} | "
              f"{past15 / RESAMPLES:16.2f} | {grown_over5} | {grown_past15} | {100.0 * mix_off / RESAMPLES:15.1f} | "
              f"{grown_mix_off} | {100.0 * met / RESAMPLES:12.1f} | {grown_met} | {by_metric}")
        mix_rows.append((name, size, mix_differences))
    # The script's own values of all tiles once against network_stats' of the window: nodes on a
    # tile's edge count in both tiles, and the histogram is weighted by each tile's length, so they
    # are near equal, not equal.
    print()
    print("the junction mix, percentage points from the example's (mean ± sd): the draws' beside the growths'")
    for name, size, draws in mix_rows:
        seeds = grown_mix.get(name, [])
        cells = " | ".join(f"{SHORT[m]} {spread([d[i] for d in draws])} / {spread([d[i] for d in seeds])}"
                           for i, m in enumerate(MIX))
        print(f"  {name:22s} {size:4.0f} m: {cells}")
    print()
    print("the script's own values (all tiles once) / network_stats' of the window:")
    for name, size, own in checks:
        pairs = " ".join(f"{SHORT[m]} {own[m]:.4g}/{reported.get((name, m), float('nan')):.4g}" for m in HEADLINE)
        print(f"  {name:22s} {size:4.0f} m: {pairs}")


if __name__ == "__main__":
    main()
