"""Vehicle runs on real track, coupled in closed loop to the WheelRailContact FMU (FMPy):

1. **Curve**: a suspended wheelset runs from straight track through a transition (curvature rising
   linearly with the distance) into a curve, at the balance speed of the curve's cant (no
   unbalanced lateral acceleration). The host feeds ``trackCurvature`` and integrates the
   wheelset's motion relative to the track frame; in the curve the wheelset settles where it
   rolls freely — its rolling-radius difference matching the curve — without angle of attack.
2. **Irregularities**: the same wheelset on straight track whose rails carry random lateral
   alignment, vertical level and cross-level irregularities generated from the ERRI B176 (ORE)
   spectra (low level), fed as ``left.rail.dy`` … ``right.rail.vz``; the same seed gives the
   same track.
3. **Elastic rails**: the curve run on rails that move: per rail a massless spring–damper
   laterally, vertically and in roll, driven by the wheel's forces on the rail (``s.rail.Fy``,
   ``s.rail.Fz``, ``s.rail.Mx``) and feeding back its displacements and velocities.

The wheelset (examples/wheelset_hunting.py's, 1500 kg, 60 kN per wheel) has lateral shift y, yaw
ψ (both relative to the track frame, which follows the centre line and turns at V κ) and spin ω.
Its axle boxes hang on a frame that follows the track's design centre line with yaw stiffness kψ
and lateral stiffness ky and damping cy. Relative to the turning frame, with κ′ = dκ/ds,

    m ÿ  = Fy_left + Fy_right − ky y − cy ẏ − m a_q          (a_q: unbalanced acceleration),
    Iz ψ̈ = Mz_left + Mz_right − kψ ψ − Iz V² κ′               (the track frame's own yaw rate),
    Iy ω̇ = −(My_left + My_right),

integrated explicitly (symplectic Euler) at 1 ms steps.

Run: ``.venv/bin/python examples/track_runs.py [--full] [--out DIR]`` after
``cargo run --release -p fmu-pack``. ``--out`` writes the figures (SVG) and the numbers
(``track_runs.json``); the short form (seconds) is what tests/python/test_track_example.py runs
in CI, ``--full`` runs longer tracks (docs/vehicle.md, "Real track").
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import math
import sys
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent


def _hunting():
    """examples/wheelset_hunting.py: the wheelset, the FMU's host and the SVG figures."""
    name = "wheelset_hunting"
    if name not in sys.modules:
        spec = importlib.util.spec_from_file_location(name, HERE / f"{name}.py")
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        spec.loader.exec_module(module)
    return sys.modules[name]


wh = _hunting()
SIDES = ("left", "right")
RAIL = ("dy", "dz", "roll", "vy", "vz", "rollRate")

# ------------------------------------------------------------------------------------------------
# The track


@dataclass(frozen=True)
class Curve:
    """Straight track, a transition of linearly rising curvature, then the full curve (radius
    > 0: a right-hand curve)."""

    radius: float = 500.0  # m
    straight: float = 20.0  # m
    transition: float = 40.0  # m

    def curvature(self, s: float) -> float:
        u = min(max((s - self.straight) / self.transition, 0.0), 1.0)
        return u / self.radius

    def curvature_slope(self, s: float) -> float:
        inside = self.straight < s < self.straight + self.transition
        return 1.0 / (self.radius * self.transition) if inside else 0.0


#: ERRI B176 (ORE) track irregularity spectra, low level: A [m rad], Ω [rad/m], b [m] half the
#: rail spacing. S_a(Ω) = A_a Ω_c² / ((Ω² + Ω_r²)(Ω² + Ω_c²)) [m²/(rad/m)] for the lateral
#: alignment, the same with A_v for the vertical level, and for the cross level (an angle)
#: S_c(Ω) = (A_v / b²) Ω_c² Ω² / ((Ω² + Ω_r²)(Ω² + Ω_c²)(Ω² + Ω_s²)) [rad²/(rad/m)].
ERRI_LOW = {"A_a": 2.119e-7, "A_v": 4.032e-7, "omega_c": 0.8246, "omega_r": 0.0206,
            "omega_s": 0.4380, "b": 0.75}


def erri_psd(kind: str, omega: np.ndarray, p: dict = ERRI_LOW) -> np.ndarray:
    w2, c2, r2, s2 = omega**2, p["omega_c"] ** 2, p["omega_r"] ** 2, p["omega_s"] ** 2
    if kind == "alignment":
        return p["A_a"] * c2 / ((w2 + r2) * (w2 + c2))
    if kind == "level":
        return p["A_v"] * c2 / ((w2 + r2) * (w2 + c2))
    if kind == "cross_level":
        return p["A_v"] / p["b"] ** 2 * c2 * w2 / ((w2 + r2) * (w2 + c2) * (w2 + s2))
    raise ValueError(kind)


@dataclass
class Irregularities:
    """Random track irregularities as sums of cosines x(s) = Σ √(2 S(Ω_k) ΔΩ_k) cos(Ω_k s + φ_k)
    over wavelengths 3–150 m (n harmonics evenly spaced in Ω), phases uniform from NumPy's
    ``default_rng(seed)``: the variance is the spectrum's integral over the band, the same seed
    gives the same track."""

    seed: int = 1
    n: int = 400
    shortest: float = 3.0  # m
    longest: float = 150.0  # m

    def __post_init__(self) -> None:
        rng = np.random.default_rng(self.seed)
        edges = np.linspace(2 * np.pi / self.longest, 2 * np.pi / self.shortest, self.n + 1)
        self.omega = 0.5 * (edges[1:] + edges[:-1])
        d_omega = np.diff(edges)
        self.amplitude = {k: np.sqrt(2 * erri_psd(k, self.omega) * d_omega)
                          for k in ("alignment", "level", "cross_level")}
        self.phase = {k: rng.uniform(0, 2 * np.pi, self.n) for k in self.amplitude}

    def at(self, kind: str, s: float) -> tuple[float, float]:
        """The irregularity and its slope d/ds at s."""
        arg = self.omega * s + self.phase[kind]
        a = self.amplitude[kind]
        return float(a @ np.cos(arg)), float(-(a * self.omega) @ np.sin(arg))

    def variance(self, kind: str) -> float:
        return float(np.sum(self.amplitude[kind] ** 2) / 2)

    def rails(self, s: float, speed: float) -> dict[str, float]:
        """Both rails' inputs at s: alignment a moves both rails laterally, level v both
        vertically, cross level c (an angle, positive lowering the right rail) by ±b c."""
        a, da = self.at("alignment", s)
        v, dv = self.at("level", s)
        c, dc = self.at("cross_level", s)
        b = ERRI_LOW["b"]
        out = {}
        for side, sign in (("left", -1.0), ("right", 1.0)):
            out[f"{side}.rail.dy"], out[f"{side}.rail.vy"] = a, speed * da
            out[f"{side}.rail.dz"] = v + sign * b * c
            out[f"{side}.rail.vz"] = speed * (dv + sign * b * dc)
        return out


@dataclass(frozen=True)
class ElasticRail:
    """A massless rail support per rail: stiffness k and damping c laterally, vertically and in
    roll (about the rail's top), c ẋ + k x = F, advanced exactly over a step for a constant F."""

    k: tuple[float, float, float] = (5.0e7, 1.0e8, 5.0e5)  # N/m, N/m, N m/rad
    c: tuple[float, float, float] = (2.0e5, 2.0e5, 2.0e3)  # N s/m, N s/m, N m s/rad

    def advance(self, x: np.ndarray, force: np.ndarray, h: float) -> tuple[np.ndarray, np.ndarray]:
        k, c = np.array(self.k), np.array(self.c)
        rest = force / k
        x = rest + (x - rest) * np.exp(-k * h / c)
        return x, (force - k * x) / c


# ------------------------------------------------------------------------------------------------
# The closed loop


@dataclass(frozen=True)
class Suspension:
    lateral_stiffness: float = 0.0  # N/m to the frame on the design centre line
    lateral_damping: float = 3.0e4  # N s/m
    yaw_stiffness: float = 2.0e6  # N m/rad


OUT = [f"{s}.{q}" for q in ("Fy", "Mz", "My", "Fx", "YQ", "Tgamma") for s in SIDES] + [
    f"{s}.rail.{q}" for s in SIDES for q in ("Fy", "Fz", "Mx")
]


class Element(wh.Contact):
    """examples/wheelset_hunting.py's instance, stepped with any inputs by name."""

    def __init__(self, host, **parameters) -> None:
        super().__init__(host.path, host.unzipdir, **parameters)
        self._out = [self.vars[n].valueReference for n in OUT]

    def step(self, h: float, inputs: dict[str, float]) -> dict[str, float]:
        self.fmu.setReal([self.vars[n].valueReference for n in inputs], list(inputs.values()))
        self.fmu.doStep(currentCommunicationPoint=self.time, communicationStepSize=h)
        self.time += h
        return dict(zip(OUT, self.fmu.getReal(self._out)))


def run(host, ws, suspension: Suspension, speed: float, length: float, curve: Curve | None = None,
        irregularities: Irregularities | None = None, rail: ElasticRail | None = None,
        normal_model: int = 1, h: float = 1e-3) -> dict[str, np.ndarray]:
    """The wheelset over `length` metres of track; every step's state and outputs by name."""
    element = Element(host, normalModel=normal_model, Qleft=ws.wheel_load, Qright=ws.wheel_load)
    y = yaw = vy = yaw_rate = 0.0
    omega = speed / ws.radius
    rail_state = {s: np.zeros(3) for s in SIDES}
    rail_rate = {s: np.zeros(3) for s in SIDES}
    log: dict[str, list[float]] = {}
    try:
        for k in range(int(round(length / speed / h))):
            s = speed * k * h
            inputs = {"y": y, "yaw": yaw, "vy": vy, "yawRate": yaw_rate, "omega": omega,
                      "vx": speed}
            kappa = curve.curvature(s) if curve else 0.0
            inputs["trackCurvature"] = kappa
            if irregularities:
                inputs.update(irregularities.rails(s, speed))
            if rail:
                for side in SIDES:
                    for q, x in zip(("dy", "dz", "roll"), rail_state[side]):
                        inputs[f"{side}.rail.{q}"] = x
                    for q, x in zip(("vy", "vz", "rollRate"), rail_rate[side]):
                        inputs[f"{side}.rail.{q}"] = x
            out = element.step(h, inputs)
            for name, value in {**inputs, **out, "s": s}.items():
                log.setdefault(name, []).append(value)
            slope = curve.curvature_slope(s) if curve else 0.0
            fy = out["left.Fy"] + out["right.Fy"] - suspension.lateral_stiffness * y \
                - suspension.lateral_damping * vy
            mz = out["left.Mz"] + out["right.Mz"] - suspension.yaw_stiffness * yaw
            vy += h * fy / ws.mass
            yaw_rate += h * (mz / ws.yaw_inertia - speed**2 * slope)
            omega += h * -(out["left.My"] + out["right.My"]) / ws.spin_inertia
            y += h * vy
            yaw += h * yaw_rate
            if rail:
                for side in SIDES:
                    force = np.array([out[f"{side}.rail.{q}"] for q in ("Fy", "Fz", "Mx")])
                    rail_state[side], rail_rate[side] = rail.advance(rail_state[side], force, h)
    finally:
        element.close()
    return {name: np.array(values) for name, values in log.items()}


def free_rolling_shift(host, ws, speed: float, kappa: float, normal_model: int = 1) -> float:
    """The lateral shift where the rigid wheelset without yaw rolls freely on the curve κ: each
    wheel needs ω = V (1 − κ (y + yPos)) / r (its contact's distance from the centre line); the
    shift where both wheels need the same ω (bisection on ±8 mm)."""
    element = Element(host, normalModel=normal_model, Qleft=ws.wheel_load,
                      Qright=ws.wheel_load)
    names = [f"{s}.p1.{q}" for s in SIDES for q in ("rollingRadius", "yPos")]
    refs = [element.vars[n].valueReference for n in names]

    def gap(y: float) -> float:
        element.step(1e-3, {"y": y, "vx": speed, "trackCurvature": kappa,
                            "omega": speed / ws.radius})
        r_l, p_l, r_r, p_r = element.fmu.getReal(refs)
        return (1 - kappa * (y + p_r)) / r_r - (1 - kappa * (y + p_l)) / r_l

    lo, hi = -0.008, 0.008
    g_lo = gap(lo)
    try:
        for _ in range(40):
            mid = 0.5 * (lo + hi)
            if gap(mid) * g_lo > 0:
                lo = mid
            else:
                hi = mid
    finally:
        element.close()
    return 0.5 * (lo + hi)


# ------------------------------------------------------------------------------------------------
# The study


def study(full: bool, out: Path | None) -> dict:
    host = wh.Host()
    ws = wh.Wheelset()
    suspension = Suspension()
    numbers: dict[str, float] = {}
    try:
        curve = Curve(radius=500.0)
        speed = 20.0
        length = curve.straight + curve.transition + (200.0 if full else 80.0)
        rigid = run(host, ws, suspension, speed, length, curve=curve)
        y_free = free_rolling_shift(host, ws, speed, 1.0 / curve.radius)
        tail = rigid["s"] > length - 20.0
        numbers.update(
            curve_radius_m=curve.radius,
            curve_speed_m_per_s=speed,
            curve_y_free_rolling_m=y_free,
            curve_y_end_m=float(np.mean(rigid["y"][tail])),
            curve_yaw_end_rad=float(np.mean(rigid["yaw"][tail])),
            curve_fx_end_n=float(np.mean((rigid["left.Fx"] + rigid["right.Fx"])[tail])),
            curve_tgamma_end_n=float(np.mean((rigid["left.Tgamma"] + rigid["right.Tgamma"])[tail])),
            curve_yq_max=float(np.max(np.maximum(rigid["left.YQ"], rigid["right.YQ"]))),
        )
        elastic = run(host, ws, suspension, speed, length, curve=curve, rail=ElasticRail())
        rail = ElasticRail()
        numbers.update(
            elastic_y_end_m=float(np.mean(elastic["y"][tail])),
            elastic_rail_dy_end_m=float(np.mean(elastic["right.rail.dy"][tail])),
            elastic_rail_dy_static_m=float(np.mean(elastic["right.rail.Fy"][tail]) / rail.k[0]),
            elastic_rail_roll_end_rad=float(np.mean(elastic["right.rail.roll"][tail])),
            elastic_rail_roll_static_rad=float(np.mean(elastic["right.rail.Mx"][tail]) / rail.k[2]),
            elastic_force_balance=float(np.max(np.abs(elastic["right.rail.Fy"] + elastic["right.Fy"]))),
        )
        track = Irregularities(seed=1)
        speed_irr = 30.0
        rough = run(host, ws, replace(suspension, lateral_stiffness=2.0e6), speed_irr,
                    300.0 if full else 120.0, irregularities=track)
        alignment = rough["right.rail.dy"]
        numbers.update(
            irregularity_alignment_rms_m=float(np.std(alignment)),
            irregularity_alignment_rms_spectrum_m=math.sqrt(track.variance("alignment")),
            irregularity_y_rms_m=float(np.std(rough["y"])),
            irregularity_y_alignment_correlation=float(np.corrcoef(rough["y"], alignment)[0, 1]),
            irregularity_yq_max=float(np.max(np.maximum(rough["left.YQ"], rough["right.YQ"]))),
        )
        if out is not None:
            out.mkdir(parents=True, exist_ok=True)
            s = rigid["s"]
            wh.svg_plot(out / "track_curve_y.svg",
                        [("lateral shift y [mm]", "#1f77b4", s, 1e3 * rigid["y"]),
                         ("on elastic rails", "#2ca02c", elastic["s"], 1e3 * elastic["y"]),
                         ("angle of attack [mrad]", "#d62728", s, 1e3 * rigid["yaw"])],
                        f"Curve entry: straight, {curve.transition:g} m transition, R = "
                        f"{curve.radius:g} m at {speed:g} m/s (free rolling at "
                        f"{1e3 * y_free:.2f} mm)", "distance s [m]", "mm, mrad")
            wh.svg_plot(out / "track_curve_forces.svg",
                        [("Y/Q left (outer)", "#1f77b4", s, rigid["left.YQ"]),
                         ("Y/Q right (inner)", "#ff7f0e", s, rigid["right.YQ"]),
                         ("Tgamma both wheels [kN]", "#2ca02c", s,
                          1e-3 * (rigid["left.Tgamma"] + rigid["right.Tgamma"]))],
                        "Curve entry: Y/Q and Tγ", "distance s [m]", "-, kN")
            wh.svg_plot(out / "track_irregularities.svg",
                        [("alignment [mm]", "#7f7f7f", rough["s"], 1e3 * alignment),
                         ("wheelset y [mm]", "#1f77b4", rough["s"], 1e3 * rough["y"])],
                        f"ERRI B176 low-level alignment, seed {track.seed}, {speed_irr:g} m/s",
                        "distance s [m]", "mm")
            (out / "track_runs.json").write_text(json.dumps(numbers, indent=2) + "\n")
    finally:
        host.close()
    return numbers


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--full", action="store_true", help="longer tracks")
    p.add_argument("--out", type=Path, help="write the figures and numbers here")
    a = p.parse_args()
    print(json.dumps(study(a.full, a.out), indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
