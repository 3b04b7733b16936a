"""Fly the figure-eight kite FMU with a roll controller written in Python, through ctypes.

The FMU is examples/fmu/figure_eight_roll_input.yaml exported by `lagrange export --fmu`: the
kite's roll angle is its FMI input `roll_cmd`. This script is a minimal FMI 2.0 Co-Simulation
importer using only Python's standard library: it unzips the FMU, reads modelDescription.xml,
loads binaries/linux64/<modelIdentifier>.so with ctypes, instantiates it, and then every 0.05 s
reads the kite's azimuth, elevation and heading (FMI outputs), computes the roll with
examples/figure_eight.yaml's law, sets `roll_cmd` (fmi2SetReal) and advances (fmi2DoStep). The
roll is held between samples (zero-order hold). It prints the orbit it flies and can save the
recorded rows as CSV.

    lagrange export examples/fmu/figure_eight_roll_input.yaml --fmu figure_eight_roll_input.fmu
    python3 examples/fmu/fly_figure_eight.py figure_eight_roll_input.fmu --t-end 60 --csv flight.csv
"""

import argparse
import csv
import ctypes
import math
import pathlib
import re
import sys
import tempfile
import time
import xml.etree.ElementTree as ET
import zipfile

# FMI 2.0 types (fmi2TypesPlatform.h): fmi2Component is a pointer, fmi2Boolean an int,
# fmi2ValueReference an unsigned int, fmi2Status and fmi2Type enums (ints).
fmi2OK, fmi2Warning, fmi2Discard, fmi2Error, fmi2Fatal, fmi2Pending = range(6)
fmi2ModelExchange, fmi2CoSimulation = 0, 1
STATUS = ["OK", "Warning", "Discard", "Error", "Fatal", "Pending"]

# fmi2CallbackLogger is variadic: void logger(env, instanceName, status, category, message, ...).
# ctypes cannot define a variadic callback; a callback taking the fixed arguments is the usual
# workaround. On x86-64 Linux (the only platform binaries/linux64 serves) a variadic caller
# passes its arguments exactly as for a non-variadic function, so three extra pointer-sized
# arguments are declared too: when every conversion of the message is %s (the FMU logs
# "%s", text), the first ones are those strings. Anything else is printed unformatted.
LOGGER = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p,
                          ctypes.c_char_p, ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p)


def _log(env, instance, status, category, message, a1, a2, a3):
    text = (message or b"").decode(errors="replace")
    conversions = re.findall(r"%.", text.replace("%%", ""))
    if conversions and len(conversions) <= 3 and all(c == "%s" for c in conversions):
        args = [ctypes.string_at(p).decode(errors="replace") if p else "(null)"
                for p in (a1, a2, a3)[:len(conversions)]]
        text = text.replace("%%", "\0") % tuple(args)
        text = text.replace("\0", "%")
    status_name = STATUS[status] if 0 <= status < len(STATUS) else str(status)
    print(f"[FMU {status_name}] {(category or b'').decode()}: {text}", file=sys.stderr)


class CallbackFunctions(ctypes.Structure):
    _fields_ = [("logger", LOGGER),
                ("allocateMemory", ctypes.c_void_p),  # void* (*)(size_t, size_t): libc's calloc
                ("freeMemory", ctypes.c_void_p),      # void (*)(void*): libc's free
                ("stepFinished", ctypes.c_void_p),    # NULL: fmi2DoStep is synchronous here
                ("componentEnvironment", ctypes.c_void_p)]


class CoSimulation:
    """One FMI 2.0 Co-Simulation instance of an FMU file, unpacked into a temporary directory."""

    def __init__(self, fmu_path):
        self._dir = tempfile.TemporaryDirectory(prefix="fmu_")
        root = pathlib.Path(self._dir.name)
        with zipfile.ZipFile(fmu_path) as z:
            z.extractall(root)
        description = ET.parse(root / "modelDescription.xml").getroot()
        self.guid = description.get("guid")
        cs = description.find("CoSimulation")
        if cs is None:
            raise RuntimeError(f"{fmu_path} offers no Co-Simulation")
        identifier = cs.get("modelIdentifier")
        self.variables = {}  # name -> (value reference, causality)
        for v in description.find("ModelVariables").iter("ScalarVariable"):
            self.variables[v.get("name")] = (int(v.get("valueReference")), v.get("causality"))
        self._lib = ctypes.CDLL(str(root / "binaries" / "linux64" / (identifier + ".so")))
        self._declare()
        libc = ctypes.CDLL(None)
        self._logger = LOGGER(_log)  # kept referenced for as long as the instance lives
        self._callbacks = CallbackFunctions(self._logger,
                                            ctypes.cast(libc.calloc, ctypes.c_void_p),
                                            ctypes.cast(libc.free, ctypes.c_void_p), None, None)
        resources = (root / "resources").as_uri()
        self._c = self._lib.fmi2Instantiate(identifier.encode(), fmi2CoSimulation,
                                            self.guid.encode(), resources.encode(),
                                            ctypes.byref(self._callbacks), 0, 0)
        if not self._c:
            raise RuntimeError("fmi2Instantiate failed")

    def _declare(self):
        lib, c, real, integer = self._lib, ctypes.c_void_p, ctypes.c_double, ctypes.c_int
        vrs, reals = ctypes.POINTER(ctypes.c_uint), ctypes.POINTER(ctypes.c_double)
        signatures = {
            "fmi2Instantiate": ([ctypes.c_char_p, integer, ctypes.c_char_p, ctypes.c_char_p,
                                 ctypes.POINTER(CallbackFunctions), integer, integer], c),
            "fmi2SetupExperiment": ([c, integer, real, real, integer, real], integer),
            "fmi2EnterInitializationMode": ([c], integer),
            "fmi2ExitInitializationMode": ([c], integer),
            "fmi2DoStep": ([c, real, real, integer], integer),
            "fmi2GetReal": ([c, vrs, ctypes.c_size_t, reals], integer),
            "fmi2SetReal": ([c, vrs, ctypes.c_size_t, reals], integer),
            "fmi2Terminate": ([c], integer),
            "fmi2FreeInstance": ([c], None),
        }
        for name, (argtypes, restype) in signatures.items():
            f = getattr(lib, name)
            f.argtypes, f.restype = argtypes, restype

    def _check(self, status, what):
        if status != fmi2OK:
            raise RuntimeError(f"{what} returned fmi2{STATUS[status]}")

    def initialize(self, start_time=0.0):
        self._check(self._lib.fmi2SetupExperiment(self._c, 0, 0.0, start_time, 0, 0.0),
                    "fmi2SetupExperiment")
        self._check(self._lib.fmi2EnterInitializationMode(self._c), "fmi2EnterInitializationMode")
        self._check(self._lib.fmi2ExitInitializationMode(self._c), "fmi2ExitInitializationMode")

    def _refs(self, names):
        return (ctypes.c_uint * len(names))(*(self.variables[n][0] for n in names))

    def get(self, names):
        values = (ctypes.c_double * len(names))()
        self._check(self._lib.fmi2GetReal(self._c, self._refs(names), len(names), values),
                    "fmi2GetReal")
        return list(values)

    def set(self, values):
        names = list(values)
        array = (ctypes.c_double * len(names))(*(values[n] for n in names))
        self._check(self._lib.fmi2SetReal(self._c, self._refs(names), len(names), array),
                    "fmi2SetReal")

    def do_step(self, t, h):
        self._check(self._lib.fmi2DoStep(self._c, t, h, 1), f"fmi2DoStep at t = {t:g}")

    def close(self):
        if self._c:
            self._lib.fmi2Terminate(self._c)
            self._lib.fmi2FreeInstance(self._c)
            self._c = None
        self._dir.cleanup()


def roll_law(p, azimuth, elevation, heading):
    """examples/figure_eight.yaml's law: loops beyond |azimuth| > a0, heading control between."""
    turn = (1 + math.tanh((abs(azimuth) - p["a0"]) / 0.02)) / 2
    loop = p["K_loop"] * math.tanh(azimuth / 0.02)
    descent = math.pi / 2 + p["gamma0"] + p["k_e"] * (elevation - p["el0"])
    aim = math.tanh(heading / 0.05) * descent
    return turn * loop + (1 - turn) * p["K_h"] * (heading - aim)


def upward_crossings(t, x):
    """Times where x crosses 0 from below, linearly interpolated between samples."""
    return [t[i - 1] + (t[i] - t[i - 1]) * -x[i - 1] / (x[i] - x[i - 1])
            for i in range(1, len(x)) if x[i - 1] < 0 <= x[i]]


COLUMNS = ["t", "roll_cmd", "wing.roll", "wing.azimuth", "wing.elevation", "wing.heading",
           "wing.height", "wing.airspeed", "main.segment1", "drum.power", "x", "y", "z"]


def fly(fmu_path, t_end, step):
    """Rows of COLUMNS every `step` s up to t_end, the roll computed and set before each step."""
    fmu = CoSimulation(fmu_path)
    try:
        causality = {name: fmu.variables.get(name, (0, None))[1]
                     for name in ["roll_cmd"] + COLUMNS[2:]}
        if causality.pop("roll_cmd") != "input" or set(causality.values()) != {"output"}:
            raise RuntimeError(f"{fmu_path}: roll_cmd must be an FMI input and the kite's "
                               f"columns outputs (export figure_eight_roll_input.yaml)")
        fmu.initialize()
        gains = ["a0", "K_loop", "K_h", "gamma0", "k_e", "el0"]
        p = dict(zip(gains, fmu.get(gains)))  # the law's parameters, as the model file gives them
        sensors = ["wing.azimuth", "wing.elevation", "wing.heading"]
        recorded = COLUMNS[2:]
        rows = []
        steps = round(t_end / step)
        for k in range(steps + 1):
            t = k * step
            roll = roll_law(p, *fmu.get(sensors))  # sample, compute, hold until the next sample
            fmu.set({"roll_cmd": roll})
            rows.append([t, roll] + fmu.get(recorded))
            if k < steps:
                fmu.do_step(t, step)
        return rows
    finally:
        fmu.close()


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("fmu", help="figure_eight_roll_input.fmu (lagrange export --fmu)")
    parser.add_argument("--t-end", type=float, default=60.0, help="seconds of flight (60)")
    parser.add_argument("--step", type=float, default=0.05,
                        help="controller sample time and communication step, s (0.05)")
    parser.add_argument("--csv", help="write the recorded rows here")
    args = parser.parse_args()

    start = time.process_time()
    rows = fly(args.fmu, args.t_end, args.step)
    cpu = time.process_time() - start
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            writer = csv.writer(f)
            writer.writerow(COLUMNS)
            writer.writerows([f"{x:.17g}" for x in row] for row in rows)

    column = {name: [row[j] for row in rows] for j, name in enumerate(COLUMNS)}
    t, azimuth, elevation = column["t"], column["wing.azimuth"], column["wing.elevation"]
    print(f"{len(rows) - 1} steps of {args.step:g} s: {t[-1]:g} s flown in {cpu:.2f} s CPU")
    print(f"azimuth {min(azimuth):.3f} .. {max(azimuth):.3f} rad, "
          f"elevation {min(elevation):.3f} .. {max(elevation):.3f} rad, "
          f"height {min(column['wing.height']):.1f} .. {max(column['wing.height']):.1f} m")
    crossings = upward_crossings(t, azimuth)
    if len(crossings) >= 2:
        periods = [b - a for a, b in zip(crossings, crossings[1:])]
        print(f"figure eights: azimuth crosses 0 upwards at t = "
              f"{', '.join(f'{c:.2f}' for c in crossings)} s; orbit period "
              f"{', '.join(f'{p:.3f}' for p in periods)} s")
    else:
        print("figure eights: fewer than two upward crossings of azimuth 0, no orbit period")
    if args.csv:
        print(f"wrote {args.csv}")


if __name__ == "__main__":
    main()
