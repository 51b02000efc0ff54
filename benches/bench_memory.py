"""Peak memory of a feature computation in a fresh process (docs/RELIABILITY.md).

    .venv/bin/python benches/bench_memory.py [--faces 1M,5M,10M] [--resolutions 1024] [--quadrature surfels]

Each cell builds a lat-long torus of about that many faces in a new Python process and calls
``uvfeat.compute(mesh, ["mean_curvature", "gaussian_curvature"], "2%")`` with the defaults (its
own UVs, 512² computation texture, 256 samples) and the given buffer resolution. It reports the
process's peak resident set size (the whole process: interpreter, NumPy, the mesh arrays and
uvfeat's tables and buffers) and the seconds the call took.
"""

from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys
import time

CHILD = """
import json, resource, sys, time
import uvfeat
n_u, n_v, resolution = map(int, sys.argv[1:4])
quadrature = sys.argv[4]
shape = uvfeat.shapes.torus(2.0, 0.5, n_u, n_v)
mesh = uvfeat.Mesh(shape.positions, shape.faces, uvs=shape.uvs, uv_faces=shape.uv_faces)
del shape
started = time.perf_counter()
values = uvfeat.compute(mesh, ["mean_curvature", "gaussian_curvature"], "2%", resolution=resolution,
                        quadrature=quadrature)
print(json.dumps({"faces": mesh.n_faces, "peak_mib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
                  "seconds": time.perf_counter() - started}))
"""


def count(text: str) -> int:
    return int(float(text[:-1]) * 1_000_000) if text.endswith("M") else int(text)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--faces", default="1M,5M,10M")
    parser.add_argument("--resolutions", default="1024")
    parser.add_argument("--quadrature", default="pattern", choices=("pattern", "surfels"))
    args = parser.parse_args()
    print("| faces | buffers | peak RSS MiB | seconds of the call |")
    print("|---|---|---|---|")
    for faces in map(count, args.faces.split(",")):
        n_v = max(3, round(math.sqrt(faces / 4)))  # 2 n_u n_v faces with n_u = 2 n_v
        for resolution in args.resolutions.split(","):
            run = subprocess.run([sys.executable, "-c", CHILD, str(2 * n_v), str(n_v), resolution, args.quadrature],
                                 capture_output=True, text=True)
            if run.returncode != 0:
                print(f"| {faces:,} | {resolution}² | failed: {run.stderr.strip().splitlines()[-1]} | |", flush=True)
                continue
            cell = json.loads(run.stdout.strip().splitlines()[-1])
            print(f"| {cell['faces']:,} | {resolution}² | {cell['peak_mib']:,.0f} | {cell['seconds']:.1f} |", flush=True)


if __name__ == "__main__":
    main()
