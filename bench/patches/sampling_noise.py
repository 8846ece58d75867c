"""Sampling noise of three headline metrics per example (bench/patches/run.sh).

The realism goal asks every metric within 15 % of the example's. Where an example has few of
what a metric counts, a network drawn from the example's own parts misses that bar by chance.
This script measures how often: it resamples each example's parts with replacement (as many as it
has, 1,000 times, a fixed seed), recomputes the metric and prints the spread of its relative
difference from the example's value and the share of resamples past 15 %.

Reads CSV rows `metric,name,a,b,reported` on stdin, one per part of the example inside the hull
shrunk by 50 m:
  phi,name,length,bearing,phi           a street (degree-2 chains merged; length inside the window,
                                        bearing in degrees clockwise from north between its ends)
  block_median,name,area,,median        a block (network_stats' block_areas)
  four_way,name,degree,,share           a node (network_stats' degrees; its degree4_share is the
                                        4-way nodes' share of them)
`reported` is the example's value as network_stats computes it; the script's own value of the full
sample is printed beside it, so a drift between the two shows.

φ follows network_stats (OSMnx's layout: 36 bins of 10 degrees, bin i covering [10 i - 5, 10 i + 5),
each street counted in both directions; φ = 1 - ((H - ln 4) / (ln 36 - ln 4))^2). A resample is an
upper bound on the noise, not a proof: a generator that copies the example's parts may miss less.
"""
import collections
import csv
import math
import random
import statistics
import sys

BINS = 36
RESAMPLES = 1000


def orientation_bin(bearing):
    shifted = math.fmod(bearing + 180.0 / BINS, 360.0)
    return min(max(int(math.floor(shifted / (360.0 / BINS))), 0), BINS - 1)


def order_of_histogram(bins):
    """φ of a length-weighted orientation histogram of BINS bins (each street counted both ways); 0 when empty."""
    weight = sum(bins)
    if weight <= 0.0:
        return 0.0
    entropy = -sum(b / weight * math.log(b / weight) for b in bins if b > 0.0)
    return 1.0 - ((entropy - math.log(4)) / (math.log(36) - math.log(4))) ** 2


def orientation_order(streets):
    bins = [0.0] * BINS
    for length, bearing in streets:
        bins[orientation_bin(bearing)] += length
        bins[orientation_bin(math.fmod(bearing + 180.0, 360.0))] += length
    return order_of_histogram(bins)


# metric -> (the part a row holds, the statistic of a list of parts)
METRICS = {
    "phi": (lambda a, b: (float(a), float(b)), orientation_order),
    "block_median": (lambda a, b: float(a), statistics.median),
    "four_way": (lambda a, b: int(a) == 4, lambda nodes: sum(nodes) / len(nodes)),
}


def main():
    parts = collections.defaultdict(list)
    reported = {}
    for metric, name, a, b, value in csv.reader(sys.stdin):
        parts[(metric, name)].append(METRICS[metric][0](a, b))
        reported[(metric, name)] = float(value)
    rng = random.Random(1)
    print(f"{'metric':12s} | {'name':22s} | {'parts':>6s} | {'value':>10s} | {'value_here':>10s} | "
          f"{'resampled_sd_pct':>16s} | {'resamples_past_15_pct':>21s}")
    for key in sorted(parts, key=lambda k: (list(METRICS).index(k[0]), k[1])):
        metric, name = key
        own = parts[key]
        statistic = METRICS[metric][1]
        value = statistic(own)
        if value == 0.0:  # nothing to be relative to (an example without 4-way nodes)
            print(f"{metric:12s} | {name:22s} | {len(own):6d} | {reported[key]:10.4g} | {value:10.4g} | {'':>16s} | {'':>21s}")
            continue
        differences = []
        for _ in range(RESAMPLES):
            sample = [own[rng.randrange(len(own))] for _ in own]
            differences.append(100.0 * (statistic(sample) - value) / value)
        mean = sum(differences) / len(differences)
        sd = math.sqrt(sum((d - mean) ** 2 for d in differences) / len(differences))
        past = 100.0 * sum(abs(d) > 15.0 for d in differences) / len(differences)
        print(f"{metric:12s} | {name:22s} | {len(own):6d} | {reported[key]:10.4g} | {value:10.4g} | {sd:16.1f} | {past:21.1f}")


if __name__ == "__main__":
    main()
