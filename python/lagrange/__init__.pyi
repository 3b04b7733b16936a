"""Type stubs of the lagrange module (docs/python.md)."""

from concurrent.futures import Executor
from types import SimpleNamespace
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

ArrayLike = npt.ArrayLike
Vector = npt.NDArray[np.float64]

class ModelError(ValueError):
    """A mistake in a model; the message reads 'file:line:column: error: ...'."""

    file: str
    """The model file (or the label given to loads)."""
    line: int
    """1-based line of the mistake (0 when unknown)."""
    column: int
    """1-based column of the mistake (0 when unknown)."""
    detail: str
    """The message without the location."""

class SimulationError(RuntimeError):
    """A numerical failure: singular mass matrix, integrator gave up, NaN."""

    time: float
    """The time at which the run failed."""
    run: Optional["Run"]
    """The trajectory computed up to the failure (None when raised by forward)."""

class AnalysisError(RuntimeError):
    """A numerical failure of linearize or trim: a singular Jacobian, Newton stalled."""

class Equations:
    """Euler-Lagrange equations as `lagrange derive` prints them (Lagrangian form)."""

    @property
    def text(self) -> str:
        """Plain text, as `lagrange derive` prints it."""
    @property
    def latex(self) -> str:
        """LaTeX, as `lagrange derive --format latex` prints it."""
    @property
    def json(self) -> str:
        """A JSON document, as `lagrange derive --format json` prints it."""
    def _repr_latex_(self) -> str: ...

class Run:
    """A simulated trajectory; columns are read-only numpy views of the engine's buffer."""

    @property
    def columns(self) -> List[str]:
        """t, coordinates, velocities (NAME_dot), kinetic, potential, energy, outputs, ..."""
    @property
    def t(self) -> Vector:
        """Sample times (a view)."""
    def __getitem__(self, column: str) -> Vector:
        """The named column (a view); KeyError for an unknown name."""
    def __contains__(self, column: str) -> bool: ...
    def __len__(self) -> int:
        """Number of samples."""
    @property
    def array(self) -> npt.NDArray[np.float64]:
        """All samples, rows x columns, a view without a copy."""
    @property
    def status(self) -> str:
        """'complete', 'failed' or 'interrupted'."""
    @property
    def message(self) -> str:
        """Why the run failed ('' when complete)."""
    @property
    def failure_time(self) -> float:
        """Where a failed run stopped."""
    @property
    def notes(self) -> List[str]:
        """What the engine noted, e.g. how it projected the initial state."""
    @property
    def warnings(self) -> List[str]:
        """Results that may not mean what they seem, e.g. a kite below the ground of its wind."""
    @property
    def stats(self) -> Dict[str, Union[int, float, str]]:
        """steps, rhs_evals, failed_steps, method, rotation_drift."""
    def report(self, path: str) -> None:
        """Write the HTML report (3-D animation, plots, equations, statistics) to path (.html),
        as `lagrange simulate --report` does; a URDF link drawn from its inertia because its
        mesh is missing gives a UserWarning."""
    def _repr_html_(self) -> str:
        """The report inline in a notebook (an iframe)."""
    def to_pandas(self) -> "pandas.DataFrame":  # type: ignore[name-defined]  # noqa: F821
        """A pandas DataFrame of the samples (pandas is imported only here)."""

class Stepper:
    """A controller in the loop: advances the model to t + dt with inputs set between calls,
    keeping the integrator's state (docs/python.md, "A controller in the loop")."""

    @property
    def t(self) -> float:
        """The time of the state."""
    @property
    def state(self) -> Tuple[Vector, Vector]:
        """(q, v) at t, new arrays."""
    @property
    def outputs(self) -> Dict[str, float]:
        """The model's outputs at t by name."""
    @property
    def inputs(self) -> List[str]:
        """Names of the inputs step() may set (declared external in the model)."""
    def step(self, dt: float, inputs: Optional[Mapping[str, float]] = None) -> None:
        """Hold the given external inputs from t on, then advance to t + dt (GIL released).

        Raises SimulationError (with .time and .run, the record up to t) when the integration
        fails; t and state are then unchanged. ValueError for an input that is not external.
        """
    def set_law(self, law: Optional[Callable[[float, Vector, Vector], Sequence[float]]]) -> None:
        """Evaluate law(t, q, v) -> values of the external inputs (in the order of `inputs`)
        at every evaluation of the dynamics instead of held values; None: held values again."""
    def trajectory(self) -> Run:
        """The states so far (t0 and each step's end) as a Run with the model's columns."""

class Model:
    """A model read, derived, compiled and checked as `lagrange simulate` does."""

    @property
    def name(self) -> str:
        """The model's name."""
    @property
    def path(self) -> str:
        """The file it was read from (or the label given to loads)."""
    @property
    def coordinates(self) -> List[str]:
        """Position coordinates q, in state order."""
    @property
    def velocities(self) -> List[str]:
        """Velocities v in state order (NAME_dot for plain coordinates)."""
    @property
    def constraints(self) -> List[str]:
        """Constraint names (one multiplier each)."""
    @property
    def parameters(self) -> Dict[str, float]:
        """Parameter values by name (with the values given as set=)."""
    @property
    def inputs(self) -> List[str]:
        """Names of the model's inputs."""
    @property
    def columns(self) -> List[str]:
        """The columns a run of this model has."""
    @property
    def initial_state(self) -> Tuple[Vector, Vector]:
        """(q, v) a run starts from, consistent with the constraints."""
    def derive(self) -> Equations:
        """The equations of motion, as `lagrange derive` prints them."""
    def simulate(
        self,
        t_end: Optional[float] = None,
        output_step: Optional[float] = None,
        integrator: Optional[str] = None,
        rtol: Optional[float] = None,
        atol: Optional[float] = None,
        step: Optional[float] = None,
        compile: str = "auto",
        max_order: Optional[int] = None,
    ) -> Run:
        """Simulate from the initial state; unset settings keep the file's simulate: values.

        Releases the GIL while integrating. Raises SimulationError (with .run, the partial
        trajectory) when the integration fails, ValueError for a bad setting. compile="on"
        warns (RuntimeWarning) when machine code cannot be had and the interpreter runs.
        Ctrl-C raises KeyboardInterrupt with .run, the rows so far (status 'interrupted').
        """
    def forward(
        self, q: ArrayLike, v: ArrayLike, t: float = 0.0
    ) -> Union[Vector, Tuple[Vector, Vector]]:
        """Accelerations (q-double-dot for plain coordinates) at (t, q, v); (a, lambda) when
        the model has constraints."""
    def forward_batch(
        self, Q: ArrayLike, V: ArrayLike, t: float = 0.0
    ) -> Union[npt.NDArray[np.float64], Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]]:
        """forward for each row of Q (rows x nq) and V (rows x nv), GIL released."""
    def linearize(
        self,
        q: Optional[ArrayLike] = None,
        v: Optional[ArrayLike] = None,
        inputs: Sequence[str] = (),
        outputs: Sequence[str] = (),
        discrete: Optional[float] = None,
        t: float = 0.0,
        values: Mapping[str, float] = ...,
        at_trim: bool = False,
        free: Sequence[str] = (),
        fix: Sequence[str] = (),
        steady: Sequence[str] = (),
        tol: float = 1e-9,
    ) -> SimpleNamespace:
        """The linear model about (q, v) (default: the initial state) on the constraint
        manifold, as `lagrange linearize`: A, B, C, D (numpy), states, inputs, outputs, modes
        (dicts: eigenvalue, frequency_hz, damping, time_constant, shape), full_states, basis,
        dependent, equilibrium_residual, dt (discrete > 0: the zero-order-hold model), q, v,
        trim. values sets parameters and model inputs at the operating point; at_trim=True
        trims first with free, fix, steady and tol (as `linearize --at-trim`), and trim is
        then a namespace: iterations, residual, tolerance, inputs (found), steady, drift."""
    def trim(
        self,
        q: Optional[ArrayLike] = None,
        free: Sequence[str] = (),
        fix: Sequence[str] = (),
        tol: float = 1e-9,
        max_iterations: int = 100,
        t: float = 0.0,
        steady: Sequence[str] = (),
        v: Optional[ArrayLike] = None,
    ) -> SimpleNamespace:
        """An equilibrium (v = 0, a = 0) from q (default: the initial state) by Levenberg–Marquardt,
        or pseudo-transient continuation when that fails, as `lagrange trim`; steady holds
        those rates at their values in v (default: the initial rates); free may name parameters
        or model inputs too (their values found: inputs): q, v, coordinates, iterations,
        residual, tolerance, not_isolated, inputs, drift, pseudo_transient."""
    def jacobian(
        self,
        q: Optional[ArrayLike] = None,
        v: Optional[ArrayLike] = None,
        inputs: Sequence[str] = (),
        t: float = 0.0,
    ) -> SimpleNamespace:
        """The exact Jacobians at (q, v): a, qdot, lam, a_q, a_v, a_w, qdot_q, qdot_v, G, C_q,
        and the implicit form's K and Phi_x (dense), with d(a, lam)/dx = -K^-1 Phi_x."""
    def optimize(
        self,
        intervals: Optional[int] = None,
        degree: Optional[int] = None,
        ipopt: Mapping[str, object] = {},
        verify: bool = False,
        verbose: bool = False,
        hessian: str = "auto",
    ) -> SimpleNamespace:
        """Solve the file's optimal_control problem as `lagrange optimize` does: optimal, status,
        objective, horizon, controls (intervals x controls), control_names, run (a Run),
        violation, worst_constraint, active_bounds, iterations, setup/solve/function seconds, stages (the
        homotopy's: name, optimal, status, iterations, objective, tracking, seconds), and verify
        (final_gap, largest_gap, message) or None. Ctrl-C raises KeyboardInterrupt with
        .result, this namespace at Ipopt's last iterate."""
    def stepper(
        self,
        t_end: Optional[float] = None,
        integrator: Optional[str] = None,
        rtol: Optional[float] = None,
        atol: Optional[float] = None,
        step: Optional[float] = None,
        compile: str = "auto",
        max_order: Optional[int] = None,
    ) -> "Stepper":
        """A Stepper from the initial state; unset settings keep the file's simulate: values.

        t_end is where dop853 lands its last step, as in simulate (stepping past it is allowed):
        with dop853 and no input set, the states at t0 + k*dt equal simulate(t_end, output_step=dt)
        rows bit for bit.
        """
    def export_c(self, dir: str) -> None:
        """Write lagrange_model.h and lagrange_model.c into dir (as `lagrange export`)."""
    def __reduce__(self) -> object: ...

def load(
    path: str,
    *,
    set: Mapping[str, float] = ...,
    initial: Mapping[str, float] = ...,
    dynamics: str = "auto",
) -> Model:
    """Read, derive, compile and check a model file; `set` replaces parameter values, `initial`
    the initial values of coordinates and velocities (NAME_dot), as --set and --initial do.

    Raises ModelError (with .file, .line, .column) for a mistake in the file and ValueError
    for a `set` name the model does not have or a value it rejects.
    """

def loads(
    text: str,
    *,
    set: Mapping[str, float] = ...,
    initial: Mapping[str, float] = ...,
    dynamics: str = "auto",
    label: str = "<string>",
) -> Model:
    """As load, for YAML text; `label` names it in error messages."""

def sweep(
    model: Model,
    grid_or_samples: Union[Mapping[str, Sequence[float]], Sequence[Mapping[str, float]]],
    metrics: Union[Mapping[str, str], Sequence[str]],
    executor: Optional[Executor] = None,
    *,
    chunk: Optional[int] = None,
    t_end: Optional[float] = None,
    output_step: Optional[float] = None,
    integrator: Optional[str] = None,
    rtol: Optional[float] = None,
    atol: Optional[float] = None,
    step: Optional[float] = None,
    max_order: Optional[int] = None,
    optimize: bool = False,
    intervals: Optional[int] = None,
    degree: Optional[int] = None,
    ipopt: Optional[Mapping[str, Any]] = None,
    hessian: str = "auto",
) -> Any:
    """Every case of a grid ({name: values}) or list of cases ([{name: value}]) run on model as
    `lagrange sweep` runs it, here or on an Executor: a pandas DataFrame, one row per case
    (values, status, reason, failure_time, metrics, wall_s). optimize=True: each case solves the
    optimal_control problem, started from the nearest solved case and then re-solved from its
    neighbours' optima, as `lagrange sweep --optimize` (objective, horizon, iterations, violation,
    warm_start, solve_s). docs/sweeps.md.
    Ctrl-C raises KeyboardInterrupt with .frame, the finished cases' rows."""
