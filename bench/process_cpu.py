#!/usr/bin/python3
"""CPU and wall time of whole `shudder` processes, two binaries alternated run by run.

    /usr/bin/python3 bench/process_cpu.py 21 OLD/shudder NEW/shudder run scenarios/paper_g_case1_25kN.toml -o /tmp/x.h5

CPU = user + sys of the child (wait4's rusage), so the figure is comparable on a shared machine,
where wall times are inflated by the other jobs. Alternating the binaries spreads the load's
drift over both. The child's figures include its fork/exec from this Python (≈ 0.5–1 ms here):
compare binaries with each other, not with `perf stat`. docs/performance.md names the figures.
"""
import os
import statistics
import sys
import time


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    n, bins, args = int(sys.argv[1]), sys.argv[2:4], sys.argv[4:]
    cpu = {b: [] for b in bins}
    wall = {b: [] for b in bins}
    for _ in range(n):
        for b in bins:
            t0 = time.perf_counter()
            pid = os.fork()
            if pid == 0:
                fd = os.open(os.devnull, os.O_WRONLY)
                os.dup2(fd, 1)
                os.execv(b, [b] + args)
            _, status, ru = os.wait4(pid, 0)
            wall[b].append((time.perf_counter() - t0) * 1e3)
            if status != 0:
                sys.exit(f"{b} exited with status {os.waitstatus_to_exitcode(status)}")
            cpu[b].append((ru.ru_utime + ru.ru_stime) * 1e3)
    for b in bins:
        print(f"{b}: CPU median {statistics.median(cpu[b]):.2f} min {min(cpu[b]):.2f} ms | "
              f"wall median {statistics.median(wall[b]):.2f} min {min(wall[b]):.2f} ms ({n} runs)")


if __name__ == "__main__":
    main()
