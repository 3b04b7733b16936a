"""lagrange.sweep: a parameter study from Python, on this process or any Executor (docs/sweeps.md).

The cases run on the engine ``lagrange sweep`` uses, so each row holds the numbers
``lagrange simulate --set`` gives for its values alone, wherever it ran.
"""

import hashlib
import itertools
import math
import pickle

_models = {}  # pickled model -> the model loaded from it, once per worker process
MAX_CASES = 1_000_000  # as `lagrange sweep` (lagrange::sweep::kMaxStudyCases, docs/sweeps.md)


def _value(name, value):
    """A parameter's value as a finite float; ValueError naming the parameter otherwise."""
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"sweep: expected a number for '{name}', got {value!r}") from None
    if not math.isfinite(number):
        raise ValueError(f"sweep: expected a finite number for '{name}', got {value!r}")
    return number


def _values(name, values):
    """A grid axis's values: a sequence of numbers (a string is not one, though iterable)."""
    if isinstance(values, (str, bytes)) or not hasattr(values, "__iter__"):
        raise ValueError(f"sweep: expected a sequence of numbers for '{name}', got {values!r}")
    return [_value(name, v) for v in values]


def _cases(grid_or_samples):
    """A dict of value sequences is a grid (every combination, the last name varying fastest);
    a sequence of dicts is a list of cases (random samples, or any other set)."""
    if isinstance(grid_or_samples, dict):
        names = list(grid_or_samples)
        values = [_values(n, grid_or_samples[n]) for n in names]
        if not names or any(len(v) == 0 for v in values):
            raise ValueError("sweep: the grid needs at least one parameter with values")
        size = math.prod(len(v) for v in values)
        if size > MAX_CASES:
            raise ValueError(f"sweep: the grid has {size} cases, more than the {MAX_CASES} a "
                             "study may have (docs/sweeps.md)")
        return [dict(zip(names, combo)) for combo in itertools.product(*values)]
    cases = [{k: _value(k, v) for k, v in case.items()} for case in grid_or_samples]
    if not cases:
        raise ValueError("sweep: no cases")
    return cases


def _metric_specs(metrics):
    if isinstance(metrics, dict):
        return [f"{name}={expr}" for name, expr in metrics.items()]
    return list(metrics)


def _run_chunk(state, cases, metrics, settings):
    """Runs on a worker: the model is unpickled (derived) once per process and pickled state."""
    key = hashlib.sha256(state).digest()
    model = _models.get(key)
    if model is None:
        model = _models[key] = pickle.loads(state)
    return model._run_cases(cases, metrics, **settings)


def sweep(model, grid_or_samples, metrics, executor=None, *, chunk=None, t_end=None,
          output_step=None, integrator=None, rtol=None, atol=None, step=None, max_order=None,
          optimize=False, intervals=None, degree=None, ipopt=None, hessian="auto"):
    """Run every case of a study on ``model`` and return a pandas DataFrame, one row per case:
    the parameter values, ``status`` ("ok" or "failed"), ``reason``, ``failure_time``, the
    metrics and ``wall_s``.

    ``grid_or_samples``: a dict ``{name: values}`` (the grid of every combination) or a list of
    dicts ``{name: value}``. ``metrics``: ``{name: "max(abs(theta1))"}`` or a list of
    ``"NAME=AGG(COLUMN[, t > T])"`` as for ``lagrange sweep --metric``. ``executor``: None runs
    here; any ``concurrent.futures.Executor`` (a ProcessPoolExecutor, Dask's
    ``distributed.Client(...).get_executor()``) runs chunks of ``chunk`` cases as tasks, each
    worker process loading the model once. An unknown parameter or metric raises ValueError
    before any case runs.

    As for ``lagrange sweep``, the cases' inputs come from one read of the model file per
    process when it can give them (docs/sweeps.md); ``frame.attrs["model_reads"]`` counts the
    reads of every process.

    ``optimize=True``: every case solves the model's optimal_control problem, as ``lagrange
    sweep --optimize`` does (docs/sweeps.md, "Optimal control: a power curve"), here and one
    after another, each started from the nearest case solved before it, then every case again
    from its neighbours' solutions, keeping a better optimum; ``intervals``,
    ``degree``, ``ipopt`` ({key: value}) and ``hessian`` are those of ``Model.optimize``, the
    simulation settings and ``executor`` do not apply. Columns: the parameters, ``status``,
    ``reason``, ``objective``, ``horizon``, ``iterations``, ``violation``, ``warm_start`` (the
    case started from, or None), the metrics (over the collocated trajectory), ``solve_s`` and
    ``wall_s``.

    Ctrl-C raises ``KeyboardInterrupt`` with ``.frame``: the table of the cases finished so far
    (indexed by their case numbers; the others have no row), as ``lagrange sweep`` keeps them.
    """
    import pandas

    if optimize:
        given = [name for name, value in dict(executor=executor, chunk=chunk, t_end=t_end,
                                              output_step=output_step, integrator=integrator,
                                              rtol=rtol, atol=atol, step=step,
                                              max_order=max_order).items() if value is not None]
        if given:
            raise ValueError(f"sweep(optimize=True): {', '.join(given)} do not apply (each case "
                             "is solved by collocation, one after another here)")
        rows = model._optimize_cases(_cases(grid_or_samples), _metric_specs(metrics),
                                     intervals=intervals, degree=degree, ipopt=ipopt or {},
                                     hessian=hessian)
        frame = pandas.DataFrame(rows)
        frame.index.name = "case"
        return frame
    if intervals is not None or degree is not None or ipopt is not None or hessian != "auto":
        raise ValueError("sweep: intervals, degree, ipopt and hessian apply to optimize=True")

    if chunk is not None and (isinstance(chunk, bool) or not isinstance(chunk, int) or chunk < 1):
        raise ValueError(f"sweep: chunk must be a whole number of cases, 1 or more, got {chunk!r}")
    cases = _cases(grid_or_samples)
    specs = _metric_specs(metrics)
    settings = dict(t_end=t_end, output_step=output_step, integrator=integrator, rtol=rtol,
                    atol=atol, step=step, max_order=max_order)
    model._run_cases(cases, specs, check_only=True, **settings)
    if executor is None:
        try:
            rows, reads = model._run_cases(cases, specs, **settings)
        except KeyboardInterrupt as e:
            e.frame = _frame(pandas, e.rows, e.reads, e.cases)
            raise
    else:
        size = chunk if chunk is not None else max(1, len(cases) // 32)
        state = pickle.dumps(model)
        starts = range(0, len(cases), size)
        futures = [executor.submit(_run_chunk, state, cases[i:i + size], specs, settings)
                   for i in starts]
        try:
            chunks = [f.result() for f in futures]
        except KeyboardInterrupt as e:
            # The chunks finished so far are kept; those not started are cancelled.
            for f in futures:
                f.cancel()
            done = [(i, f.result()) for i, f in zip(starts, futures)
                    if f.done() and not f.cancelled() and f.exception() is None]
            e.frame = _frame(pandas, [row for _, (chunk_rows, _) in done for row in chunk_rows],
                             sum(chunk_reads for _, (_, chunk_reads) in done),
                             [i + k for i, (chunk_rows, _) in done for k in range(len(chunk_rows))])
            raise
        rows = [row for chunk_rows, _ in chunks for row in chunk_rows]
        reads = sum(chunk_reads for _, chunk_reads in chunks)
    return _frame(pandas, rows, reads)


def _frame(pandas, rows, reads, cases=None):
    """The study's table; ``cases``: the case numbers of the rows when some cases have none."""
    frame = pandas.DataFrame(rows, index=cases)
    frame.index.name = "case"
    frame.attrs["model_reads"] = reads
    return frame
