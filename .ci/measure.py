"""Run a shell command and print its wall time, CPU time and peak memory: that of the largest
process (RSS) and that of all its processes together (the sum of their RSS, sampled every 0.5 s
from /proc; the test command runs two pytest workers at once).

Usage: python .ci/measure.py LABEL 'shell command'. Exits with the command's status.
"""
import os
import resource
import subprocess
import sys
import threading
import time

SAMPLE_S = 0.5


def _tree_rss_kib(root: int) -> int:
    """Sum of VmRSS over ``root`` and its descendants (0 where /proc cannot be read)."""
    parent, rss = {}, {}
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/status") as f:
                fields = dict(line.split(":", 1) for line in f if ":" in line)
        except OSError:
            continue
        pid = int(entry)
        parent[pid] = int(fields.get("PPid", "0").strip() or 0)
        rss[pid] = int(fields.get("VmRSS", "0 kB").split()[0])
    total, todo = 0, [root]
    children = {}
    for pid, ppid in parent.items():
        children.setdefault(ppid, []).append(pid)
    while todo:
        pid = todo.pop()
        total += rss.get(pid, 0)
        todo.extend(children.get(pid, ()))
    return total


label, command = sys.argv[1], sys.argv[2]
t0 = time.perf_counter()
proc = subprocess.Popen(["bash", "-c", command])
peak_tree = [0]


def _sample() -> None:
    while proc.poll() is None:
        peak_tree[0] = max(peak_tree[0], _tree_rss_kib(proc.pid))
        time.sleep(SAMPLE_S)


sampler = threading.Thread(target=_sample, daemon=True)
sampler.start()
status = proc.wait()
sampler.join()
wall_s = time.perf_counter() - t0
usage = resource.getrusage(resource.RUSAGE_CHILDREN)
cpu_s = usage.ru_utime + usage.ru_stime
peak_gb = usage.ru_maxrss / 1024**2      # ru_maxrss is in KiB on Linux
print(f"== {label}: {wall_s / 60:.1f} min wall, {cpu_s / 60:.1f} min CPU, "
      f"{peak_gb:.2f} GB peak memory (largest process), {peak_tree[0] / 1024**2:.2f} GB (all its processes "
      f"together, sampled), exit status {status}", flush=True)
sys.exit(status)
