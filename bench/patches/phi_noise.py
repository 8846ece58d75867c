"""The orientation order's sampling noise per example (bench/patches/run.sh).

Reads CSV rows `name,length,bearing,phi` on stdin: one row per street of the example inside the
hull shrunk by 50 m (degree-2 chains merged, length inside the window, bearing in degrees clockwise
from north between the chain's ends), phi the example's orientation order as
streetgen.network_stats computes it. Resamples each example's streets with replacement (as many
as it has, a fixed seed) and prints how far a network drawn from the example's own streets lands
from the example's φ: the spread of the relative difference and the share of resamples past 15 %.
Where that share is large, the realism goal's 15 % bar on φ is within the example's own noise.

The bins and φ follow network_stats (OSMnx's layout: 36 bins of 10 degrees, bin i covering
[10 i - 5, 10 i + 5), each street counted in both directions; φ = 1 - ((H - ln 4) / (ln 36 - ln 4))^2).
The script's φ of the full sample is printed beside network_stats' so a drift between the two shows.
"""
import collections
import csv
import math
import random
import sys

BINS = 36
RESAMPLES = 1000


def orientation_bin(bearing):
    shifted = math.fmod(bearing + 180.0 / BINS, 360.0)
    return min(max(int(math.floor(shifted / (360.0 / BINS))), 0), BINS - 1)


def orientation_order(streets):
    bins = [0.0] * BINS
    for length, bearing in streets:
        bins[orientation_bin(bearing)] += length
        bins[orientation_bin(math.fmod(bearing + 180.0, 360.0))] += length
    weight = sum(bins)
    entropy = -sum(b / weight * math.log(b / weight) for b in bins if b > 0.0)
    return 1.0 - ((entropy - math.log(4)) / (math.log(36) - math.log(4))) ** 2


def main():
    streets = collections.defaultdict(list)
    reported = {}
    for name, length, bearing, phi in csv.reader(sys.stdin):
        streets[name].append((float(length), float(bearing)))
        reported[name] = float(phi)
    rng = random.Random(1)
    print(f"{'name':22s} | {'streets':>7s} | {'phi':>6s} | {'phi_here':>8s} | {'resampled_sd_pct':>16s} | "
          f"{'resamples_past_15_pct':>21s}")
    for name in sorted(streets):
        own = streets[name]
        phi = orientation_order(own)
        differences = []
        for _ in range(RESAMPLES):
            sample = [own[rng.randrange(len(own))] for _ in own]
            differences.append(100.0 * (orientation_order(sample) - phi) / phi)
        mean = sum(differences) / len(differences)
        sd = math.sqrt(sum((d - mean) ** 2 for d in differences) / len(differences))
        past = 100.0 * sum(abs(d) > 15.0 for d in differences) / len(differences)
        print(f"{name:22s} | {len(own):7d} | {reported[name]:6.4f} | {phi:8.4f} | {sd:16.1f} | {past:21.1f}")


if __name__ == "__main__":
    main()
