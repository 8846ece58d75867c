#!/usr/bin/python3
"""The peer of bench/raster/run.sh: the same image steps with scikit-image (python3-skimage) on
the same WKB raster file: threshold, one erosion and five dilations with the 3 x 3 cross, and
skeletonize (Zhang-Suen for 2-D images, the method of the paper and of streetgen). scikit-image
has no skeleton -> graph step, so only these steps are timed. Prints one JSON object: median
seconds per step and the skeleton's pixel count.

    skimage_peer.py FILE [RUNS]
"""
import json
import struct
import sys
import time

import numpy as np
from skimage.morphology import binary_dilation, binary_erosion, diamond, skeletonize


def read_wkb_raster(path):
    data = open(path, "rb").read()
    endian = "<" if data[0] == 1 else ">"
    (_, bands, *_geo, _srid, width, height) = struct.unpack(endian + "HH6diHH", data[1:61])
    assert bands == 1, "one band"
    pixtype = data[61] & 0x0F
    dtype = {4: np.uint8, 10: np.float32, 11: np.float64}[pixtype]
    size = np.dtype(dtype).itemsize
    values = np.frombuffer(data, dtype=np.dtype(dtype).newbyteorder(endian), count=width * height, offset=62 + size)
    return values.reshape(height, width)


def main():
    path = sys.argv[1]
    runs = int(sys.argv[2]) if len(sys.argv) > 2 else 5
    values = read_wkb_raster(path)
    cross = diamond(1)
    t_morph, t_thin = [], []
    for _ in range(runs):
        t0 = time.perf_counter()
        mask = values > 0.5
        mask = binary_erosion(mask, cross)
        for _ in range(5):
            mask = binary_dilation(mask, cross)
        t1 = time.perf_counter()
        skeleton = skeletonize(mask)
        t2 = time.perf_counter()
        t_morph.append(t1 - t0)
        t_thin.append(t2 - t1)
    print(json.dumps({"morphology": float(np.median(t_morph)), "thinning": float(np.median(t_thin)),
                      "cleaned_pixels": int(mask.sum()), "skeleton_pixels": int(skeleton.sum())}))


if __name__ == "__main__":
    main()
