#!/usr/bin/python3
"""The cost model of docs/SCALING.md: a sweep or table of C independent cases on P MPI ranks with
railcontact's dynamic load balancing, simulated case by case (standard library only).

Each case costs a time drawn log-uniformly between t_min and spread * t_min, scaled so that the
mean is the measured mean (a 10x spread by default, the issue's assumption; the measured spread is
smaller). Rank 0 hands out the cases one request at a time: a request waits until rank 0 is free,
takes it `service` seconds (receive, file the result, append it to the journal, send the next
index; measured), and the answer reaches the rank after a message latency; rank 0 polls with
0.2 ms sleeps, so a request also waits 0.1 ms on average. Every rank computes (rank 0 on its own
thread). Before the cases: the start (mpirun, MPI_Init, reading the profiles and the file); after
them: rank 0 writes the CSV and the journal (bytes per case, disk speed).

Efficiency E(P) = (C * mean) / (P * T(P)), T(P) the simulated wall time.

Usage: scaling_model.py [--cases 100000] [--mean 0.206] [--spread 10] [--service-us 32]
                        [--latency-us 50] [--start-s 10] [--bytes-per-case 544] [--disk-MBps 100]
                        [--ranks 64,128,256,512,1024]
"""
import argparse
import heapq
import math
import random


def simulate(cases, ranks, mean, spread, service, latency, start, write):
    rng = random.Random(1)
    # log-uniform on [a, spread a] with mean `mean`: mean = a (spread - 1) / ln(spread)
    a = mean * math.log(spread) / (spread - 1) if spread > 1 else mean
    costs = [a * math.exp(rng.random() * math.log(spread)) if spread > 1 else mean for _ in range(cases)]
    free = [(start, r) for r in range(ranks)]  # each rank asks for its first case after the start
    heapq.heapify(free)
    server = start
    end = start
    for cost in costs:
        t, r = heapq.heappop(free)
        begin = max(t + 0.5 * latency + 1e-4, server)  # the request arrives, waits for rank 0's poll and turn
        server = begin + service
        done = server + 0.5 * latency + cost
        end = max(end, done)
        heapq.heappush(free, (done, r))
    return end + write, costs


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--cases", type=int, default=100000)
    p.add_argument("--mean", type=float, default=0.206, help="mean time per case on one core (s)")
    p.add_argument("--spread", type=float, default=10.0, help="largest / smallest case time")
    p.add_argument("--service-us", type=float, default=32.0, help="rank 0's time per case (us)")
    p.add_argument("--latency-us", type=float, default=50.0, help="message round trip (us)")
    p.add_argument("--start-s", type=float, default=10.0, help="start-up before the first case (s)")
    p.add_argument("--bytes-per-case", type=float, default=544.0)
    p.add_argument("--disk-MBps", type=float, default=100.0)
    p.add_argument("--ranks", default="64,128,256,512,1024")
    a = p.parse_args()
    write = 2 * a.cases * a.bytes_per_case / (a.disk_MBps * 1e6)  # journal and CSV
    print(f"{a.cases} cases, mean {a.mean:g} s, spread {a.spread:g}x, rank 0 {a.service_us:g} us per case, "
          f"round trip {a.latency_us:g} us, start {a.start_s:g} s, output {a.cases * a.bytes_per_case / 1e6:.1f} MB "
          f"(written in {write:.1f} s)")
    print("| ranks | serial work (s) | wall time (s) | of which start + write (s) | rank 0 busy | efficiency |")
    print("|---:|---:|---:|---:|---:|---:|")
    for ranks in (int(r) for r in a.ranks.split(",")):
        wall, costs = simulate(a.cases, ranks, a.mean, a.spread, a.service_us * 1e-6, a.latency_us * 1e-6,
                               a.start_s, write)
        work = sum(costs)
        busy = a.cases * a.service_us * 1e-6 / (wall - a.start_s - write)
        print(f"| {ranks} | {work:.0f} | {wall:.1f} | {a.start_s + write:.1f} | {100 * busy:.1f} % | "
              f"{100 * work / (ranks * wall):.1f} % |")


if __name__ == "__main__":
    main()
