"""Print versions of the peer packages, numpy's BLAS and thread counts (for README.md)."""
import os, platform
from importlib.metadata import version
import numpy as np, threadpoolctl

print("python", platform.python_version(), "| cpus", os.cpu_count(), "|", platform.machine())
for p in ["numpy", "scipy", "tamaas", "contactmechanics", "SurfaceTopography", "muGrid",
          "quadprog", "clarabel", "osqp", "threadpoolctl"]:
    print(f"{p} {version(p)}")
for lib in threadpoolctl.threadpool_info():
    print(f"threadpool: {lib['user_api']} {lib['internal_api']} {lib['version']} "
          f"threads={lib['num_threads']} arch={lib.get('architecture')} ({os.path.basename(lib['filepath'])})")
cfg = np.show_config(mode="dicts")["Build Dependencies"]
print("numpy blas:", cfg["blas"]["name"], cfg["blas"].get("version"), "| lapack:", cfg["lapack"]["name"])
print("OMP_NUM_THREADS =", os.environ.get("OMP_NUM_THREADS"), "| OPENBLAS_NUM_THREADS =", os.environ.get("OPENBLAS_NUM_THREADS"))
