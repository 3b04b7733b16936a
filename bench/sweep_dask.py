"""One study through Dask (docs/sweeps.md, "Speed"): a local cluster of WORKERS processes with one
thread each on the loopback interface, lagrange.sweep with the cluster's executor, and the time
of the sweep call alone (the cluster's start-up printed apart).

    PYTHONPATH=build/python python3 bench/sweep_dask.py MODEL NAME LOW HIGH CASES T_END METRIC [WORKERS=2]
"""
import sys
import time

import lagrange
from distributed import Client, LocalCluster


def main():
    model_path, name, low, high, cases, t_end, metric = sys.argv[1:8]
    workers = int(sys.argv[8]) if len(sys.argv) > 8 else 2
    low, high, cases, t_end = float(low), float(high), int(cases), float(t_end)
    start = time.perf_counter()
    cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                           host="127.0.0.1", dashboard_address=None)
    client = Client(cluster)
    started = time.perf_counter() - start
    model = lagrange.load(model_path)
    values = [low + (high - low) * i / (cases - 1) for i in range(cases)]
    t0 = time.perf_counter()
    frame = lagrange.sweep(model, {name: values}, [metric], client.get_executor(), t_end=t_end)
    took = time.perf_counter() - t0
    failed = int((frame["status"] != "ok").sum())
    print(f"dask {workers} workers: cluster start {started:.2f} s, sweep {took:.3f} s, "
          f"{cases / took:.1f} cases/s, {failed} failed, "
          f"{frame.attrs['model_reads']} model reads")
    client.close()
    cluster.close()


if __name__ == "__main__":
    main()
