"""Run a shell command and print its wall time, CPU time and peak memory (the largest process's RSS).

Usage: python .ci/measure.py LABEL 'shell command'. Exits with the command's status.
"""
import resource
import subprocess
import sys
import time

label, command = sys.argv[1], sys.argv[2]
t0 = time.perf_counter()
status = subprocess.call(["bash", "-c", command])
wall_s = time.perf_counter() - t0
usage = resource.getrusage(resource.RUSAGE_CHILDREN)
cpu_s = usage.ru_utime + usage.ru_stime
peak_gb = usage.ru_maxrss / 1024**2      # ru_maxrss is in KiB on Linux
print(f"== {label}: {wall_s / 60:.1f} min wall, {cpu_s / 60:.1f} min CPU, "
      f"{peak_gb:.2f} GB peak memory (largest process), exit status {status}", flush=True)
sys.exit(status)
