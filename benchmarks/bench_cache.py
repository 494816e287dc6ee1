"""The disk cache's cost per write in a full folder (model/runs/cache.py).

    python benchmarks/bench_cache.py [--entries 10000] [--writes 200]

Fills a temporary cache folder with ``--entries`` entries (copies of one valid entry
under other names, so the fill is quick), then times ``--writes`` puts of new keys two
ways in the same run: the cache as it is (a folder scan only when its count of entries
passes a bound) and the same put followed by a full scan (``_evict``, one ``stat`` per
entry), which is what every write cost before. Reports median [min-max] in ms per write.
"""
from __future__ import annotations

import argparse
import shutil
import sys
import tempfile
import time

import numpy as np


from spread import cell, spread
from model.runs.cache import DiskCache


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--entries", type=int, default=10_000)
    parser.add_argument("--writes", type=int, default=200)
    args = parser.parse_args(argv)
    row = {name: np.array(1.0) for name in ("FTx", "Dy_over_Dx", "beta", "Nc", "error")}
    with tempfile.TemporaryDirectory() as tmp:
        cache = DiskCache(tmp, max_entries=args.entries + 10 * args.writes)
        cache.put({"seed": -1}, row)
        seed = cache.file_for({"seed": -1})
        for i in range(args.entries):
            shutil.copyfile(seed, seed.with_name(f"{i:064x}.npz"))
        times = {"indexed": [], "scan every write": []}
        for i in range(args.writes):
            for policy, samples in times.items():
                start = time.perf_counter()
                cache.put({"policy": policy, "i": i}, row)
                if policy == "scan every write":
                    cache._evict()
                samples.append(1e3 * (time.perf_counter() - start))
    print(f"{args.entries} entries, {args.writes} writes each (ms per write, median [min-max]):")
    for policy, samples in times.items():
        s = spread(samples)
        print(f"  {policy:18s} {cell(s['median'], s['min'], s['max'])}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
