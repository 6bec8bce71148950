"""A suspended wheelset on straight track, coupled in closed loop to the WheelRailContact FMU.

The host is this Python master: it steps the packed FMU with FMPy once per communication step and
integrates the wheelset's motion itself. The wheelset (mass m, yaw inertia Iz, spin inertia Iy)
has three degrees of freedom — lateral shift y, yaw ψ and its spin ω about the axle — and hangs on
primary springs (lateral ky, yaw kψ) from a frame that moves along the track at constant speed V.
Each step the host sets the FMU's inputs from its states (y, yaw, vy = ẏ, yawRate = ψ̇, omega = ω,
vx = V, the wheel loads Q), calls fmi2DoStep, reads the wheels' wrenches at the wheelset centre
(left/right Fy, Mz, My, in track axes) and advances

    m ẍ_y  = Fy_left + Fy_right − ky y,
    Iz ψ̈  = Mz_left + Mz_right − kψ ψ,
    Iy ω̇   = −(My_left + My_right)        (ω positive rolling forward, My about +y),

explicitly (symplectic Euler: velocities from the forces at the step's start, then positions), or
linearly implicitly in the velocities with the FMU's directional derivatives J = ∂(F, Mz, −My)/∂
(vy, yawRate, omega): (M − h J) Δv = h f. The creep forces act as a damper of rate ~2 f22/V per
wheelset, i.e. a time constant m V/(2 f22) ≈ 0.1–1 ms at 1–10 m/s: the explicit coupling is stable
only for h below twice that and chatters at low speed; the implicit one is not limited by it.

What it shows (docs/vehicle.md has the numbers, figures and how to reproduce them):

1. Klingel: the free wheelset (no springs) at 10 m/s runs the kinematic oscillation; its
   wavelength is compared with 2π √(r0 e0/λ(A)) with the element's own λ(A) (Klingel
   integration at the run's amplitude, ``railcontact conicity``).
2. The critical speed by bisection on the closed loop (does a 3 mm oscillation grow or decay?)
   against the linear Wickens model built from the element's own linear creep coefficients
   (FMU evaluated at small prescribed creepages), its gravitational stiffness and its conicity
   λ(3 mm), both harmonically linearised at the same amplitude; for communication steps of 0.25,
   0.5 and 1 ms, and for the normal models Hertz (1) and ANALYN (6).
3. Low-speed chatter of the explicit coupling at 1 ms, removed by the implicit treatment with the
   directional derivatives.
4. Figures of y(t) below and above the critical speed (SVG, written without plotting packages).

Run: ``.venv/bin/python examples/wheelset_hunting.py [--full] [--out DIR]`` after
``cargo run --release -p fmu-pack`` (the FMU is taken from $RAILCONTACT_FMU_DIR, else
$CARGO_TARGET_DIR/fmu, else target/fmu). ``--full`` runs every step size and model (a few
minutes); without it the short form (about a minute) that CI runs through
tests/python/test_vehicle_example.py.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

REPO_ROOT = Path(__file__).resolve().parents[1]

# ------------------------------------------------------------------------------------------------
# The vehicle


@dataclass(frozen=True)
class Wheelset:
    """A wheelset on primary springs to a frame moving at constant speed (SI units)."""

    mass: float = 1500.0  # kg
    yaw_inertia: float = 700.0  # kg m²
    spin_inertia: float = 120.0  # kg m²
    wheel_load: float = 60_000.0  # N per wheel
    lateral_stiffness: float = 2.0e6  # N/m (both axle boxes)
    yaw_stiffness: float = 2.0e6  # N m/rad (longitudinal springs × half-spacing²)
    radius: float = 0.46  # m, the FMU's wheelRadius

    def free(self) -> "Wheelset":
        """The same wheelset without springs."""
        return replace(self, lateral_stiffness=0.0, yaw_stiffness=0.0)


# ------------------------------------------------------------------------------------------------
# The FMU


def fmu_path(name: str = "WheelRailContact.fmu") -> Path:
    """The packed FMU, found as tests/python/conftest.py finds it."""
    if os.environ.get("RAILCONTACT_FMU_DIR"):
        return Path(os.environ["RAILCONTACT_FMU_DIR"]) / name
    if os.environ.get("CARGO_TARGET_DIR"):
        return Path(os.environ["CARGO_TARGET_DIR"]).resolve() / "fmu" / name
    return REPO_ROOT / "target" / "fmu" / name


INPUTS = ["y", "yaw", "vy", "yawRate", "omega", "vx"]
OUTPUTS = ["left.Fy", "right.Fy", "left.Mz", "right.Mz", "left.My", "right.My"]
# Velocity inputs of the implicit treatment and the generalised forces they act on.
VELOCITY_INPUTS = ["vy", "yawRate", "omega"]


class Contact:
    """One WheelRailContact instance, used as a function: inputs in, wrenches out."""

    def __init__(self, path: Path, unzipdir: str, **parameters: float | int | str) -> None:
        self.md = read_model_description(str(path))
        self.vars = {v.name: v for v in self.md.modelVariables}
        self.fmu = FMU2Slave(
            guid=self.md.guid,
            unzipDirectory=unzipdir,
            modelIdentifier=self.md.coSimulation.modelIdentifier,
            instanceName="contact",
        )
        self.fmu.instantiate()
        self.fmu.setupExperiment(startTime=0.0)
        self.set(**parameters)
        self.fmu.enterInitializationMode()
        self.fmu.exitInitializationMode()
        self.time = 0.0
        self._in = [self.vars[n].valueReference for n in INPUTS]
        self._out = [self.vars[n].valueReference for n in OUTPUTS]
        self.derivatives = bool(self.md.coSimulation.providesDirectionalDerivative)

    def set(self, **values: float | int | str) -> None:
        for name, value in values.items():
            v = self.vars[name]
            if v.type == "Integer":
                self.fmu.setInteger([v.valueReference], [int(value)])
            elif v.type == "String":
                self.fmu.setString([v.valueReference], [str(value)])
            elif v.type == "Boolean":
                self.fmu.setBoolean([v.valueReference], [bool(value)])
            else:
                self.fmu.setReal([v.valueReference], [float(value)])

    def get(self, *names: str) -> list[float]:
        return list(self.fmu.getReal([self.vars[n].valueReference for n in names]))

    def step(self, h: float, inputs: list[float]) -> np.ndarray:
        """Sets the inputs (INPUTS order), steps by h and returns the outputs (OUTPUTS order)."""
        self.fmu.setReal(self._in, inputs)
        # FMPy raises on fmi2Discard and fmi2Error (a pose off the rail ends the run).
        self.fmu.doStep(currentCommunicationPoint=self.time, communicationStepSize=h)
        self.time += h
        return np.array(self.fmu.getReal(self._out))

    def velocity_jacobian(self) -> np.ndarray:
        """J[i][j] = ∂f_i/∂v_j with f = (Fy, Mz, −My) of both wheels and v = (vy, yawRate,
        omega), from fmi2GetDirectionalDerivative at the last step's state."""
        unknowns = [self.vars[n].valueReference for n in OUTPUTS]
        J = np.zeros((3, 3))
        for j, name in enumerate(VELOCITY_INPUTS):
            d = self.fmu.getDirectionalDerivative(
                vUnknown_ref=unknowns, vKnown_ref=[self.vars[name].valueReference], dvKnown=[1.0]
            )
            J[0, j] = d[0] + d[1]
            J[1, j] = d[2] + d[3]
            J[2, j] = -(d[4] + d[5])
        return J

    def close(self) -> None:
        self.fmu.terminate()
        self.fmu.freeInstance()


class Host:
    """The extracted FMU, shared by every instance of a run."""

    def __init__(self, path: Path | None = None) -> None:
        self.path = path or fmu_path()
        if not self.path.is_file():
            raise FileNotFoundError(
                f"{self.path}: no packed FMU; run `cargo run --release -p fmu-pack` first"
            )
        self.unzipdir = extract(str(self.path))

    def contact(self, normal_model: int, **parameters: float | int | str) -> Contact:
        return Contact(self.path, self.unzipdir, normalModel=normal_model, **parameters)

    def close(self) -> None:
        shutil.rmtree(self.unzipdir, ignore_errors=True)


# ------------------------------------------------------------------------------------------------
# Closed loop


@dataclass
class Run:
    t: np.ndarray
    y: np.ndarray
    yaw: np.ndarray
    omega: np.ndarray


def simulate(
    contact: Contact,
    ws: Wheelset,
    speed: float,
    h: float,
    duration: float,
    y0: float,
    implicit: bool = False,
) -> Run:
    """Integrates the wheelset from y = y0 (at rest otherwise, rolling at ω = V/r) for
    `duration` seconds with communication step h."""
    M = np.diag([ws.mass, ws.yaw_inertia, ws.spin_inertia])
    contact.set(Qleft=ws.wheel_load, Qright=ws.wheel_load)
    n = int(round(duration / h))
    q = np.array([y0, 0.0])  # y, ψ
    v = np.array([0.0, 0.0, speed / ws.radius])  # vy, yaw rate, ω
    ts, ys, yaws, omegas = [0.0], [q[0]], [q[1]], [v[2]]
    for k in range(n):
        out = contact.step(h, [q[0], q[1], v[0], v[1], v[2], speed])
        f = np.array(
            [
                out[0] + out[1] - ws.lateral_stiffness * q[0],
                out[2] + out[3] - ws.yaw_stiffness * q[1],
                -(out[4] + out[5]),
            ]
        )
        if implicit:
            # Linearly implicit in the velocities: (M − h J) Δv = h f.
            dv = np.linalg.solve(M - h * contact.velocity_jacobian(), h * f)
        else:
            dv = h * f / np.diag(M)
        v = v + dv
        q = q + h * v[:2]
        if not (abs(q[0]) < 0.02 and math.isfinite(v[0])):
            break  # flange climb or a diverging (chattering) integration: stop the run here
        ts.append((k + 1) * h)
        ys.append(q[0])
        yaws.append(q[1])
        omegas.append(v[2])
    return Run(np.array(ts), np.array(ys), np.array(yaws), np.array(omegas))


def peaks(run: Run) -> tuple[np.ndarray, np.ndarray]:
    """Times and values of the local maxima of y (parabolic refinement)."""
    y = run.y
    k = np.where((y[1:-1] > y[:-2]) & (y[1:-1] >= y[2:]) & (y[1:-1] > 0))[0] + 1
    dt = run.t[1] - run.t[0]
    times, values = [], []
    for i in k:
        a, b, c = y[i - 1], y[i], y[i + 1]
        den = a - 2 * b + c
        s = 0.5 * (a - c) / den if den != 0 else 0.0
        times.append(run.t[i] + s * dt)
        values.append(b - 0.25 * (a - c) * s)
    return np.array(times), np.array(values)


def growth(run: Run) -> float:
    """Mean logarithmic growth of the peaks of y per cycle (> 0 unstable), over the second to
    fourth peaks (the start is not on the oscillation's own mode shape; later peaks drift away
    from the starting amplitude, where λ(A) differs)."""
    _, p = peaks(run)
    if len(p) < 3:
        # Diverged (stopped early) or did not oscillate: unstable if it left ±20 mm.
        return math.inf if abs(run.y[-1]) >= 0.02 or len(run.y) < 10 else -math.inf
    p = p[1:4]
    return float(np.polyfit(np.arange(len(p)), np.log(np.abs(p)), 1)[0])


def critical_speed_closed_loop(
    host: Host,
    normal_model: int,
    ws: Wheelset,
    h: float,
    amplitude: float,
    low: float,
    high: float,
    tolerance: float,
) -> float:
    """Bisection on V of the sign of the growth of an oscillation started at `amplitude`."""
    contact = host.contact(normal_model)
    try:
        while high - low > tolerance:
            mid = 0.5 * (low + high)
            # About six cycles of the kinematic wavelength (~9 m) at this speed.
            duration = 6 * 9.0 / mid
            if growth(simulate(contact, ws, mid, h, duration, amplitude)) > 0:
                high = mid
            else:
                low = mid
        return 0.5 * (low + high)
    finally:
        contact.close()


# ------------------------------------------------------------------------------------------------
# The element's own linear coefficients and the linear (Wickens) model


@dataclass
class Linear:
    f11: float  # longitudinal creep coefficient per wheel [N]
    f22: float  # lateral creep coefficient per wheel [N]
    gravity: float  # gravitational stiffness of the wheelset, harmonically linearised [N/m]
    conicity: float  # equivalent conicity (harmonic) at the amplitude [-]
    r0: float  # m
    e0: float  # m


def creep_coefficients(host: Host, normal_model: int, ws: Wheelset) -> tuple[float, float]:
    """f11, f22 of the centred wheelset from the FMU at small prescribed creepages (the linear,
    Kalker part of the element's creep-force law): f = −ΔF/Δc."""
    contact = host.contact(normal_model, creepageMode=2)
    contact.set(Qleft=ws.wheel_load, Qright=ws.wheel_load)
    small = 1e-6

    def forces(xi: float, eta: float) -> np.ndarray:
        contact.set(xi=xi, eta=eta, phi=0.0)
        contact.step(1e-3, [0.0, 0.0, 0.0, 0.0, 10.0 / ws.radius, 10.0])
        return np.array(contact.get("right.Fx", "right.Fy"))

    base = forces(0.0, 0.0)
    f11 = -(forces(small, 0.0)[0] - base[0]) / small
    f22 = -(forces(0.0, small)[1] - base[1]) / small
    contact.close()
    return f11, f22


def gravitational_stiffness(host: Host, normal_model: int, ws: Wheelset, amplitude: float) -> float:
    """k_g = −1/(πA) ∫₀^{2π} Fy(A sin τ) sin τ dτ of the wheelset's total lateral force at zero
    creepage (the normal forces' lateral components), by the midpoint rule on 48 points."""
    contact = host.contact(normal_model, creepageMode=2)
    contact.set(Qleft=ws.wheel_load, Qright=ws.wheel_load, xi=0.0, eta=0.0, phi=0.0)
    n = 48
    total = 0.0
    for k in range(n):
        tau = 2 * math.pi * (k + 0.5) / n
        contact.step(1e-3, [amplitude * math.sin(tau), 0.0, 0.0, 0.0, 10.0 / ws.radius, 10.0])
        fy = sum(contact.get("left.Fy", "right.Fy"))
        total += fy * math.sin(tau) * 2 * math.pi / n
    contact.close()
    return -total / (math.pi * amplitude)


def conicity(amplitudes: list[float]) -> dict:
    """`railcontact conicity` for the FMU's default profiles (S1002 on UIC60 1:40)."""
    exe = os.environ.get("RAILCONTACT_CLI")
    command = (
        [exe]
        if exe
        else ["cargo", "run", "--quiet", "--release", "-p", "railcontact-cli", "--"]
    )
    text = subprocess.run(
        command + ["conicity", "--amplitudes", ",".join(str(a) for a in amplitudes)],
        cwd=REPO_ROOT,
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    return json.loads(text)


def linear_model(host: Host, normal_model: int, ws: Wheelset, amplitude: float, cone: dict) -> Linear:
    """The element's own linear coefficients: creep coefficients, gravitational stiffness and
    the loaded conicity λ(A) (harmonic), with r0 and e0 of `railcontact conicity`."""
    f11, f22 = creep_coefficients(host, normal_model, ws)
    ys, dr = loaded_delta_r(host, normal_model, ws)
    return Linear(
        f11=f11,
        f22=f22,
        gravity=gravitational_stiffness(host, normal_model, ws, amplitude),
        conicity=harmonic(ys, dr, amplitude),
        r0=cone["r0"],
        e0=cone["e0"],
    )


def wickens_matrix(lin: Linear, ws: Wheelset, speed: float) -> np.ndarray:
    """State matrix of (y, ψ, ẏ, ψ̇) of the linear wheelset (Wickens 2003, ch. 2):
    m ÿ = −2 f22 (ẏ/V − ψ) − (ky + kg) y,
    Iz ψ̈ = −2 f11 e0² ψ̇/V − 2 f11 e0 λ y/r0 − kψ ψ."""
    m, iz = ws.mass, ws.yaw_inertia
    a = np.zeros((4, 4))
    a[0, 2] = a[1, 3] = 1.0
    a[2, 0] = -(ws.lateral_stiffness + lin.gravity) / m
    a[2, 1] = 2 * lin.f22 / m
    a[2, 2] = -2 * lin.f22 / (m * speed)
    a[3, 0] = -2 * lin.f11 * lin.e0 * lin.conicity / (lin.r0 * iz)
    a[3, 1] = -ws.yaw_stiffness / iz
    a[3, 3] = -2 * lin.f11 * lin.e0**2 / (iz * speed)
    return a


def critical_speed_linear(lin: Linear, ws: Wheelset, low: float = 1.0, high: float = 500.0) -> float:
    """The speed where the largest real part of the eigenvalues crosses zero (bisection)."""

    def unstable(v: float) -> bool:
        return max(np.linalg.eigvals(wickens_matrix(lin, ws, v)).real) > 0

    if unstable(low) or not unstable(high):
        raise ValueError("the linear model has no critical speed in the bracket")
    while high - low > 1e-3:
        mid = 0.5 * (low + high)
        low, high = (low, mid) if unstable(mid) else (mid, high)
    return 0.5 * (low + high)


# ------------------------------------------------------------------------------------------------
# The element's own rolling-radius difference under load


def loaded_delta_r(host: Host, normal_model: int, ws: Wheelset, y_max: float = 0.006, step: float = 1e-4):
    """Δr(y) of the loaded element: each wheel's rolling radius as the normal-force-weighted mean
    of its patches' `rollingRadius` outputs under the wheel loads, at zero creepage. The rigid
    EN 15302 Δr of `railcontact conicity` differs where the elastic patches smooth the rigid
    contact's jumps (S1002/UIC60 1:40: a jump of 0.45 mm at y = ±0.25 mm, where the loaded
    wheelset runs on two patches)."""
    contact = host.contact(normal_model, creepageMode=2)
    contact.set(Qleft=ws.wheel_load, Qright=ws.wheel_load, xi=0.0, eta=0.0, phi=0.0)
    ys = np.arange(-round(y_max / step), round(y_max / step) + 1) * step
    names = {
        s: ([f"{s}.p{k}.Fn" for k in (1, 2, 3)], [f"{s}.p{k}.rollingRadius" for k in (1, 2, 3)])
        for s in ("left", "right")
    }
    dr = []
    for y in ys:
        contact.step(1e-3, [y, 0.0, 0.0, 0.0, 10.0 / ws.radius, 10.0])
        radius = {}
        for side, (fn_names, r_names) in names.items():
            fn, r = np.array(contact.get(*fn_names)), np.array(contact.get(*r_names))
            radius[side] = float((fn * r).sum() / fn.sum())
        dr.append(radius["right"] - radius["left"])
    contact.close()
    return ys, np.array(dr)


def harmonic(ys: np.ndarray, dr: np.ndarray, amplitude: float, n: int = 2000) -> float:
    """λ(A) = 1/(2πA) ∫ Δr(A sin τ) sin τ dτ (midpoint rule, Δr interpolated linearly)."""
    tau = 2 * np.pi * (np.arange(n) + 0.5) / n
    return float(np.sum(np.interp(amplitude * np.sin(tau), ys, dr) * np.sin(tau)) / (n * amplitude))


def klingel_integration(ys: np.ndarray, dr: np.ndarray, amplitude: float, r0: float, e0: float) -> float:
    """Wavelength [m] of y'' = −Δr(y)/(2 e0 r0) from y = A, y' = 0 (classical Runge–Kutta,
    4000 steps per estimated wavelength): one full cycle."""
    lam = harmonic(ys, dr, amplitude)
    h = 2 * math.pi * math.sqrt(r0 * e0 / lam) / 4000
    k = 1 / (2 * e0 * r0)

    def acc(y: float) -> float:
        return -k * float(np.interp(y, ys, dr))

    x, y, p, lower = 0.0, amplitude, 0.0, False
    for _ in range(40000):
        k1y, k1p = p, acc(y)
        k2y, k2p = p + 0.5 * h * k1p, acc(y + 0.5 * h * k1y)
        k3y, k3p = p + 0.5 * h * k2p, acc(y + 0.5 * h * k2y)
        k4y, k4p = p + h * k3p, acc(y + h * k3y)
        yn = y + h / 6 * (k1y + 2 * k2y + 2 * k3y + k4y)
        pn = p + h / 6 * (k1p + 2 * k2p + 2 * k3p + k4p)
        if not lower and p < 0 <= pn:
            lower = True
        elif lower and p > 0 >= pn:
            return x + h * p / (p - pn)
        x, y, p = x + h, yn, pn
    raise ValueError("no oscillation")


# ------------------------------------------------------------------------------------------------
# Klingel


def klingel_wavelength(host: Host, ws: Wheelset, normal_model: int, y0: float, h: float) -> tuple[float, float]:
    """Wavelength [m] of the free wheelset's first full cycle at 10 m/s from y = y0, and the
    mean of its two positive peaks (the amplitude it ran at)."""
    contact = host.contact(normal_model)
    speed = 10.0
    run = simulate(contact, ws.free(), speed, h, 2.4 * 9.0 / speed, y0)
    contact.close()
    times, values = peaks(run)
    # The start (t = 0) is the first maximum; the next one ends the cycle.
    return float(times[0] * speed), float(0.5 * (y0 + values[0]))


# ------------------------------------------------------------------------------------------------
# Figures: SVG written directly (no plotting package needed)


def svg_plot(path: Path, series: list[tuple[str, str, np.ndarray, np.ndarray]], title: str, xlabel: str, ylabel: str) -> None:
    width, height, left, right, top, bottom = 900, 420, 80, 20, 40, 60
    xs = np.concatenate([s[2] for s in series])
    ys = np.concatenate([s[3] for s in series])
    x0, x1 = float(xs.min()), float(xs.max())
    ymax = float(np.abs(ys).max()) * 1.1 or 1.0
    y0, y1 = -ymax, ymax

    def px(x: float) -> float:
        return left + (x - x0) / (x1 - x0) * (width - left - right)

    def py(y: float) -> float:
        return top + (y1 - y) / (y1 - y0) * (height - top - bottom)

    out = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
        f'font-family="sans-serif" font-size="13">',
        f'<rect width="{width}" height="{height}" fill="white"/>',
        f'<text x="{width / 2}" y="22" text-anchor="middle" font-size="15" font-weight="bold">{title}</text>',
    ]
    for k in range(6):
        x = x0 + (x1 - x0) * k / 5
        out.append(f'<line x1="{px(x):.1f}" y1="{top}" x2="{px(x):.1f}" y2="{height - bottom}" stroke="#e6e6e6"/>')
        out.append(f'<text x="{px(x):.1f}" y="{height - bottom + 18}" text-anchor="middle">{x:.3g}</text>')
    for k in range(5):
        y = y0 + (y1 - y0) * k / 4
        out.append(f'<line x1="{left}" y1="{py(y):.1f}" x2="{width - right}" y2="{py(y):.1f}" stroke="#e6e6e6"/>')
        out.append(f'<text x="{left - 6}" y="{py(y) + 4:.1f}" text-anchor="end">{y:.3g}</text>')
    out.append(f'<rect x="{left}" y="{top}" width="{width - left - right}" height="{height - top - bottom}" fill="none" stroke="black"/>')
    out.append(f'<text x="{(left + width - right) / 2}" y="{height - 18}" text-anchor="middle">{xlabel}</text>')
    out.append(f'<text x="18" y="{(top + height - bottom) / 2}" text-anchor="middle" transform="rotate(-90 18 {(top + height - bottom) / 2})">{ylabel}</text>')
    for i, (label, colour, x, y) in enumerate(series):
        stride = max(1, len(x) // 3000)
        points = " ".join(f"{px(a):.1f},{py(b):.1f}" for a, b in zip(x[::stride], y[::stride]))
        out.append(f'<polyline points="{points}" fill="none" stroke="{colour}" stroke-width="1.5"/>')
        lx, ly = left + 12 + 300 * i, top + 18
        out.append(f'<line x1="{lx}" y1="{ly - 4}" x2="{lx + 24}" y2="{ly - 4}" stroke="{colour}" stroke-width="2"/>')
        out.append(f'<text x="{lx + 30}" y="{ly}">{label}</text>')
    out.append("</svg>")
    path.write_text("\n".join(out) + "\n")


# ------------------------------------------------------------------------------------------------
# The study


@dataclass
class Results:
    numbers: dict = field(default_factory=dict)

    def put(self, key: str, value) -> None:
        self.numbers[key] = value
        print(f"{key}: {value}", flush=True)


def study(full: bool, out: Path | None) -> dict:
    host = Host()
    ws = Wheelset()
    amplitude = 0.003
    r = Results()
    cone = conicity([0.001, 0.002, 0.003, 0.004, 0.005])
    r.put("r0_m", cone["r0"])
    r.put("e0_m", cone["e0"])
    try:
        # 1. Klingel at 10 m/s: the closed loop's first cycle against the Klingel integration of
        #    the element's loaded Δr at the amplitude the cycle ran at.
        rigid = {c["amplitude"]: c for c in cone["conicity"]}[amplitude]
        r.put("rigid_lambda_harmonic_3mm", rigid["harmonic"])
        r.put("rigid_lambda_klingel_3mm", rigid["klingel"])
        ys, dr = loaded_delta_r(host, 1, ws)
        r.put("loaded_lambda_harmonic_3mm", harmonic(ys, dr, amplitude))
        wavelength, ran_at = klingel_wavelength(host, ws, 1, amplitude, 2.5e-4)
        formula = klingel_integration(ys, dr, ran_at, cone["r0"], cone["e0"])
        r.put("klingel_amplitude_m", ran_at)
        r.put("klingel_lambda", cone["r0"] * cone["e0"] * (2 * math.pi / formula) ** 2)
        r.put("klingel_wavelength_closed_loop_m", wavelength)
        r.put("klingel_wavelength_formula_m", formula)
        r.put("klingel_error", wavelength / formula - 1)

        # 2. Critical speeds, closed loop against linear.
        steps = [1e-3, 5e-4, 2.5e-4] if full else [1e-3]
        models = [1, 6]
        for model in models:
            lin = linear_model(host, model, ws, amplitude, cone)
            v_lin = critical_speed_linear(lin, ws)
            r.put(f"model{model}_f11_N", lin.f11)
            r.put(f"model{model}_f22_N", lin.f22)
            r.put(f"model{model}_gravity_N_per_m", lin.gravity)
            r.put(f"model{model}_lambda", lin.conicity)
            r.put(f"model{model}_critical_linear_m_per_s", v_lin)
            for h in steps if model == 1 else steps[:1]:
                v_cl = critical_speed_closed_loop(
                    host, model, ws, h, amplitude, 0.5 * v_lin, 1.5 * v_lin, 0.01 * v_lin if full else 0.02 * v_lin
                )
                r.put(f"model{model}_critical_closed_loop_h{h * 1e3:g}ms_m_per_s", v_cl)

        # 3. Low-speed chatter at 1 ms: explicit against implicit.
        contact = host.contact(1)
        speed, h = 2.0, 1e-3
        explicit = simulate(contact, ws, speed, h, 0.2, amplitude)
        contact.close()
        r.put("chatter_explicit_max_abs_vy", float(np.max(np.abs(np.diff(explicit.y) / h))))
        r.put("chatter_explicit_steps_completed", len(explicit.t) - 1)
        contact = host.contact(1)
        if contact.derivatives:
            implicit = simulate(contact, ws, speed, h, 0.2, amplitude, implicit=True)
            r.put("chatter_implicit_max_abs_vy", float(np.max(np.abs(np.diff(implicit.y) / h))))
            r.put("chatter_implicit_steps_completed", len(implicit.t) - 1)
        contact.close()

        # 4. Figures of y(t) below and above the critical speed.
        if out is not None:
            out.mkdir(parents=True, exist_ok=True)
            v_c = r.numbers["model1_critical_closed_loop_h1ms_m_per_s"]
            contact = host.contact(1)
            below = simulate(contact, ws, 0.9 * v_c, 5e-4, 1.5, amplitude)
            above = simulate(contact, ws, 1.1 * v_c, 5e-4, 1.5, amplitude)
            contact.close()
            svg_plot(
                out / "hunting_y.svg",
                [
                    (f"V = {0.9 * v_c:.1f} m/s (0.9 V_crit)", "#0072b2", below.t, below.y * 1e3),
                    (f"V = {1.1 * v_c:.1f} m/s (1.1 V_crit)", "#d55e00", above.t, above.y * 1e3),
                ],
                "Suspended wheelset in closed loop with WheelRailContact (Hertz, h = 0.5 ms)",
                "t [s]",
                "y [mm]",
            )
            (out / "hunting.json").write_text(json.dumps(r.numbers, indent=2) + "\n")
    finally:
        host.close()
    return r.numbers


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--full", action="store_true", help="every step size (a few minutes)")
    parser.add_argument("--out", type=Path, help="directory for the figure and the numbers")
    args = parser.parse_args()
    study(args.full, args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
