"""Runs a command RUNS times and prints the median CPU time (user + system, by getrusage, in
microseconds rather than /usr/bin/time's hundredths) and that run's wall time, in seconds.

A 0.1 s command on a shared virtual machine varies by +-30 % from run to run; the median of a few
runs is what a user sees, where the minimum would flatter it. The command's output is discarded.

Usage: cpu_time.py RUNS COMMAND [ARGS...]  ->  "CPU WALL"
"""
import resource
import subprocess
import sys
import time


def main():
    runs = int(sys.argv[1])
    command = sys.argv[2:]
    samples = []
    for _ in range(runs):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        subprocess.run(command, stdout=subprocess.DEVNULL, check=True)
        wall = time.perf_counter() - start
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        samples.append((cpu, wall))
    samples.sort()
    cpu, wall = samples[len(samples) // 2]
    print("%.4f %.3f" % (cpu, wall))


if __name__ == "__main__":
    main()
