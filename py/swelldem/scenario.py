# SPDX-License-Identifier: GPL-2.0-or-later
"""The paper's numerical swelling tests on a generated concrete specimen (ISR, ASR-fine, ASR-coarse),
with elastic (modulus developing with age) or aging viscoelastic contacts, with or without damage.

Run inside YADE with the plugin (scripts/swelling_test.py is the command-line face, generated from
the fields of :class:`SwellingTest`):

    from swelldem import scenario
    res = scenario.run(scenario.SwellingTest(scenario="isr", behaviour="viscoelastic", damage=True,
                                             size_mm=(30, 30), out="out/isr",
                                             kind_params={"MORTAR": {"tensileStrength": 5e6}}))

Decisions (docs/scenarios.md explains them):
- the paper's Table 3.3 q's are its micro (contact) parameters q_i*, and they are used as such by
  default (parameters="paper-micro"); parameters="macro" reads them as macroscopic values and
  derives the contact values through the factor beta measured on a random mortar assembly of the
  same packing (calibrate_modulus_factor: contacts of modulus E_c give a macroscopic modulus
  beta E_c, so E_c = E / beta and each micro q_i = beta q_i, the law being linear in the
  compliance). The calibration is a second simulation, run only for "macro";
- 'elastic' runs use aging-elastic mortar and ITZ contacts, E(t) = 1/J(t + 0.01 d, t) of the same
  B3 q's (the paper: "included the development over time of mortar and ITZ modulus");
  aggregate contacts are linear elastic (modulus paper.AGGREGATE_YOUNG, an assumption: the paper gives none);
- the specimen is free (no support) unless boundary_x / boundary_y (/ boundary_z in 3D) put platens on its sides
  (swelldem.dem.platens); strains are the least-squares affine fit of the skeleton's displacements.

Validation: SwellingTest.validate checks every field (NaN and infinity included) in Python, with
the one message form of swelldem.options; prepare() then makes the plugin's objects, whose
constructors check what ends up as a ContactKind or solver attribute. Both run before the
mesostructure is generated.
"""
import ast
import math
import os
import re
import signal
import sys
import time
import numpy as np
from dataclasses import MISSING, asdict, dataclass, field, fields

from . import options, paper
from .dem import SOLVERS

BEHAVIOURS = ("elastic", "viscoelastic")
PARAMETERS = ("paper-micro", "macro")


_bad = options.bad


def _field(default, help, unit=None, flag=None, choices=None, sets=None, factory=None, type=None):
    """A SwellingTest field with its help text, unit, command-line flag (default --the-name),
    choices, the plugin attribute it sets (whose constructor validates it) and the type of its
    command-line value (default: the default's type; needed when the default is None)."""
    meta = {"help": help, "unit": unit, "flag": flag, "choices": choices, "sets": sets, "type": type}
    return field(default_factory=factory, metadata=meta) if factory else field(default=default, metadata=meta)


#: The value a run recorded without a field had, for the fields whose default is not what swelldem did
#: before the field existed: results.json's config of such a run reads as this value, not the default.
VALUE_BEFORE_FIELD = {"gel_pockets": "single", "gel_displacement": "rule"}


@dataclass
class SwellingTest:
    """One swelling test: every parameter with its unit and meaning (also the command line of
    scripts/swelling_test.py)."""
    scenario: str = _field("isr", "the paper's swelling test", choices=tuple(paper.SCENARIOS))
    behaviour: str = _field("viscoelastic", "contacts: elastic (mortar and ITZ modulus aging with B3) or aging viscoelastic (B3)",
                            choices=BEHAVIOURS)
    damage: bool = _field(True, "brittle contacts with the paper's Table 3.5 strengths (--no-damage: never break)",
                          sets="ContactKind.damage")
    size_mm: tuple = _field((30.0, 30.0), "specimen width and height, and its depth when dim is 3 (W H D)", unit="mm")
    dim: int = _field(2, "specimen: 2, a section of discs; 3, a box of spheres with polyhedral aggregates (either solver; "
                         "platens, applied stress and restraint springs on any face pair; not bars or the macro calibration)")
    seed: int = _field(1, "mesostructure seed (integer >= 0)")
    solver: str = _field("implicit", "quasi-static solver: implicit (each step's exact equilibrium by Newton and a sparse Cholesky factor) "
                         "or adr (adaptive dynamic relaxation, the paper's method)", choices=tuple(SOLVERS))
    steps_per_decade: float = _field(10.0, "physical steps per decade of log time", sets="solver.stepsPerDecade")
    tolerance: float = _field(None, "unbalanced-force ratio at which a step has converged (absent: the solver's own default, "
                                    "its class's tolerance)", type=float, sets="solver.tolerance")
    t_start_days: float = _field(1.0, "age of the stress-free start", unit="day", flag="--t-start", sets="solver.tStart")
    t_end_days: float = _field(0.0, "last time (0: the paper's, 3650 ISR / 50000 ASR)", unit="day", flag="--t-end", sets="solver.tEnd")
    temperature_c: float = _field(None, "constant temperature of every kind (none: each kind at its reference temperatures, "
                                        "the kinetics' referenceTemperature and creep's creepReferenceTemperature, 20 C)",
                                  unit="C", type=float, sets="ContactKind.temperatureDays, temperatures")
    temperature_csv: str = _field("", "temperature history of every kind, a file of rows 'day, deg C' (days >= 0 strictly "
                                      "increasing, linear in between, held before the first and after the last; '#' starts "
                                      "a comment)", sets="ContactKind.temperatureDays, temperatures")
    eps_inf: float = _field(paper.EPS_INF, "ultimate free swelling strain of the swelling material (d_inf = eps_inf x 2 R_mean)", unit="-")
    gel_fraction: float = _field(0.1, "asr-coarse: share of the aggregate contacts that swell (gel pockets)", unit="-")
    gel_pockets: str = _field("rim", "asr-coarse: which contacts are the gel pockets, a reading of the paper's \"10% of "
                                        "the coarse aggregates contacts\" and \"small areas of the aggregate, gel pockets "
                                        "(inside and near the boundary)\": " + "; ".join(
                                            f"{k}, {v}" for k, v in paper.GEL_POCKET_READINGS.items()),
                              choices=tuple(paper.GEL_POCKET_READINGS))
    gel_pocket_radius_mm: float = _field(1.0, "asr-coarse, gel_pockets clustered: radius of a pocket around its centre", unit="mm")
    gel_displacement: str = _field("aggregate", "asr-coarse: the pockets' ultimate swelling displacement, which the paper's Table 3.2 "
                                           "states for mortar and ITZ only: " + "; ".join(
                                               f"{k}, {v}" for k, v in paper.GEL_DISPLACEMENT_READINGS.items()),
                                   choices=tuple(paper.GEL_DISPLACEMENT_READINGS))
    shear_ratio: float = _field(0.3, "ks / kn of every contact", unit="-", sets="ContactKind.shearRatio")
    aggregate_young: float = _field(paper.AGGREGATE_YOUNG, "contact modulus of aggregate contacts", unit="Pa", sets="ContactKind(AGG).young")
    strength_scale: float = _field(1.0, "factor on the paper's Table 3.5 tensile strengths", unit="-")
    kelvin_units_per_decade: float = _field(1.0, "Kelvin chain density", unit="1/decade", sets="ContactKind.kelvinUnitsPerDecade")
    parameters: str = _field("paper-micro", "read the paper's Table 3.3 q's (and the aggregate modulus) as contact values "
                                            "(paper-micro), or as macroscopic ones scaled by the measured beta (macro)", choices=PARAMETERS)
    aggregate_area_fraction: float = _field(-1.0, "aggregate area fraction of the specimen (< 0: the generator's default)", unit="-")
    kind_params: dict = _field(None, "per-kind ContactKind attributes, KIND.attribute=value (repeatable), e.g. "
                                     "MORTAR.tensileStrength=5e6 [Pa]; contact values, applied last (after eps_inf, "
                                     "strength_scale and, in macro, the beta scaling of q's and young); KIND one of MORTAR, "
                                     "ITZ, AGG, and with bars BOND (a copy of the ITZ kind as run, not swelling, these "
                                     "values over it)",
                               flag="--kind-param", sets="ContactKind.<attribute>", factory=dict)
    boundary_x: str = _field("free", "platens on the x sides: free, fixed (restrained), stress:S (applied stress S [Pa], compression "
                                     "negative) or spring:K (partial restraint, K [N/m per metre of thickness]); "
                                     "swelldem.dem.platens")
    boundary_y: str = _field("free", "platens on the y sides, as boundary_x")
    boundary_z: str = _field("free", "platens on the z sides of a 3D box, as boundary_x (a spring's K per square metre of the face "
                                     "in 3D); free for a 2D section")
    rebar_ratio: float = _field(0.0, "reinforcement ratio: steel area over the specimen's cross-section, in one bar along x at "
                                     "mid-height, or in rebar_bars evenly spaced bars (0: none; swelldem.dem.rebar)", unit="-")
    rebar_bars: int = _field(1, "number of bars along x, evenly spaced across the height")
    rebar_young: float = _field(200e9, "steel modulus of the bars", unit="Pa")
    rebar_yield_stress: float = _field(500e6, "steel yield stress: the bars stay elastic, the first day they reach it is "
                                              "reported (results.json rebar.yield_day)", unit="Pa")
    solver_params: dict = _field(None, "settings of the solver, NAME=VALUE (repeatable), e.g. fallbackIterations=3 or "
                                       "stepsPerDecade=5: any setting of the chosen solver's class (AdrLogTimeIntegrator or "
                                       "ImplicitLogTimeSolver, LogTimeSolver's included), VALUE a Python literal, checked by the "
                                       "plugin; applied last (over --steps-per-decade, --tolerance, --t-start, --t-end)",
                                 flag="--solver-param", sets="solver.<setting>", factory=dict)
    humidity_faces: dict = _field(None, "a specimen face exposed to an ambient relative humidity, FACE H (repeatable): FACE one of "
                                        "x-, x+, y-, y+ (and z-, z+ in 3D), H a number in (0, 1] or a file of rows 'day, h' "
                                        "(days >= 0 strictly increasing, linear in between, held before the first and after "
                                        "the last; '#' starts a comment); faces not given are sealed (swelldem.moisture; "
                                        "docs/moisture.md)", flag="--humidity-face", factory=dict)
    humidity_initial: float = _field(1.0, "relative humidity of every particle at the stress-free start (1 with no face exposed: "
                                          "no moisture model, the saturated run)", unit="-")
    humidity_exponent: float = _field(8.0, "m of the swelling's humidity factor f(h) = h^m on each step's swelling increment (Capra "
                                           "and Bournazel 1998, Saouma and Perotti 2006)", unit="-", sets="SwellPhys.swellFactor")
    shrinkage: dict = _field(None, "drying-shrinkage coefficient k_sh of a kind, KIND=VALUE (repeatable) [strain per unit of h]: the "
                                   "contact's imposed free strain is -k_sh (h_start - h); absent kinds keep the defaults "
                                   "(swelldem.dem.humidity.DEFAULT_SHRINKAGE: MORTAR and ITZ shrink, AGG does not)",
                             flag="--shrinkage", sets="SwellPhys.imposedOpening", factory=dict)
    humidity_steps_per_decade: float = _field(40.0, "moisture time steps per decade of log time (each physical step split into at "
                                                    "least this many; backward Euler's error is about 1 % of the drop at 40)",
                                              unit="1/decade")
    vtk_every: int = _field(0, "ParaView files (DIR/vtk/) every k physical steps, and always of the last (0: only the last)")
    save_state: bool = _field(False, "save the scene (O.save) after every physical step to DIR/state.yade (binary), from which "
                                     "--resume DIR goes on, and at the end to DIR/final.yade.gz")
    out: str = _field("out/swelling", "output folder")

    def validate(self):
        """Every field's range, NaN and infinity included, in Python (options' one message form);
        the plugin's constructors check the same fields again when run() makes its objects. A
        tolerance looser than the useful range warns on stderr."""
        if self.scenario not in paper.SCENARIOS:
            _bad("scenario", self.scenario, ", ".join(paper.SCENARIOS))
        if self.behaviour not in BEHAVIOURS:
            _bad("behaviour", self.behaviour, ", ".join(BEHAVIOURS))
        if self.parameters not in PARAMETERS:
            _bad("parameters", self.parameters, ", ".join(PARAMETERS))
        options.choice("solver", self.solver, tuple(SOLVERS))
        if not isinstance(self.damage, bool):
            _bad("damage", self.damage, "True, False")
        if self.dim not in (2, 3) or isinstance(self.dim, bool):
            _bad("dim", self.dim, "2 (a section), 3 (a box of spheres)")
        lengths = "two finite lengths > 0 [mm] (W H)" if self.dim == 2 else "three finite lengths > 0 [mm] (W H D, dim 3)"
        try:
            options.numbers("size_mm", self.size_mm, count=self.dim, lo=0, unit="mm", allowed=lengths)
        except TypeError:
            _bad("size_mm", self.size_mm, lengths)
        if self.dim == 3:
            self._validate_3d()
        options.integer("seed", self.seed, lo=0)
        options.number("steps_per_decade", self.steps_per_decade, lo=0)
        if self.tolerance is not None:  # None: the solver's own, its class's default
            options.tolerance("tolerance", self.tolerance, solver=self.solver)
        options.number("t_start_days", self.t_start_days, lo=0, unit="day")
        if not (options.is_number(self.t_end_days) and self.t_end_days == 0):
            options.number("t_end_days", self.t_end_days, lo=self.t_start_days, unit="day",
                           allowed=f"0 (the paper's end) or t_start_days = {self.t_start_days:g} < t_end_days < inf [day]")
        options.number("eps_inf", self.eps_inf, lo=0, lo_incl=True, allowed="0 <= eps_inf < inf [-]")
        options.number("gel_fraction", self.gel_fraction, lo=0, hi=1, lo_incl=True, hi_incl=True)
        options.choice("gel_pockets", self.gel_pockets, tuple(paper.GEL_POCKET_READINGS))
        options.number("gel_pocket_radius_mm", self.gel_pocket_radius_mm, lo=0, unit="mm")
        options.choice("gel_displacement", self.gel_displacement, tuple(paper.GEL_DISPLACEMENT_READINGS))
        if self.gel_displacement == "aggregate" and self.scenario == "asr-coarse" and not self.gel_fraction > 0:
            _bad("gel_fraction", self.gel_fraction, "0 < gel_fraction <= 1 with gel_displacement aggregate (d = d_rule / gel_fraction)")
        options.number("shear_ratio", self.shear_ratio, lo=0)
        options.number("aggregate_young", self.aggregate_young, lo=0, unit="Pa")
        options.number("strength_scale", self.strength_scale, lo=0)
        options.number("kelvin_units_per_decade", self.kelvin_units_per_decade, lo=0, unit="1/decade")
        if not (options.is_number(self.aggregate_area_fraction) and self.aggregate_area_fraction < 0):
            options.number("aggregate_area_fraction", self.aggregate_area_fraction, lo=0, hi=1, lo_incl=True,
                           allowed="< 0 (the generator's default) or 0 <= aggregate_area_fraction < 1")
        options.integer("vtk_every", self.vtk_every, lo=0)
        if not isinstance(self.save_state, bool):
            _bad("save_state", self.save_state, "True, False")
        from .dem.platens import Boundary  # plain Python: the parse needs no YADE
        for axis in ("x", "y", "z"):
            Boundary.parse(f"boundary_{axis}", getattr(self, f"boundary_{axis}"))
        if self.dim == 2 and self.boundary_z != "free":
            _bad("boundary_z", self.boundary_z, "free for a 2D section (dim 2 has no z sides)")
        from .dem.rebar import MAX_RATIO
        options.number("rebar_ratio", self.rebar_ratio, lo=0, hi=MAX_RATIO, lo_incl=True, hi_incl=True)
        options.integer("rebar_bars", self.rebar_bars, lo=1)
        options.number("rebar_young", self.rebar_young, lo=0, unit="Pa")
        options.number("rebar_yield_stress", self.rebar_yield_stress, lo=0, unit="Pa")
        self.rebar_layout()  # a layout that does not fit the specimen, from the options alone
        self.temperature_history()  # the temperature options, the CSV file read and checked
        self.humidity_history()  # the humidity options, the CSV files read and checked
        # the mesostructure generator's own checks (a specimen too small for the sieve fractions, an
        # aggregate fraction it cannot place, ...), run here so that they too come before any work
        from .meso import MesoParameters
        MesoParameters().replace(**self.meso_overrides()).validate()
        options.output_folder("out", self.out)  # a folder the run can write into (made by run()), nothing made here
        if not isinstance(self.kind_params, dict):
            _bad("kind_params", self.kind_params, "a dict {kind name: {ContactKind attribute: value}}")
        for name, attrs in self.kind_params.items():
            # BOND exists only with bars; it starts as a copy of the ITZ (swelldem.dem.rebar)
            if name not in paper.KIND_NAMES and not (name == "BOND" and self.rebar_ratio > 0):
                _bad("kind_params kind", name, ", ".join(paper.KIND_NAMES) + ", and BOND when rebar_ratio > 0")
            if not isinstance(attrs, dict):
                _bad(f"kind_params['{name}']", attrs, "a dict {ContactKind attribute: value}")
            for attr, value in attrs.items():
                # the plugin checks only the values its behaviour uses (a NaN swellDispInf of a kind
                # that does not swell passes): no ContactKind number means anything at NaN or inf
                if options.is_number(value):
                    options.number(f"{name}.{attr}", value)
                elif isinstance(value, str) and value.strip().lower().lstrip("+-") in ("nan", "inf", "infinity"):
                    _bad(f"{name}.{attr}", value, "a finite number")
        if not isinstance(self.solver_params, dict) or not all(isinstance(k, str) for k in self.solver_params):
            _bad("solver_params", self.solver_params, "a dict {solver setting: value}")
        # the names and the values are the plugin's to check (prepare(): the solver's class)
        tol = self.solver_params.get("tolerance")
        if options.is_number(tol) and 0 < tol < 1:
            options.tolerance("solver_params tolerance", tol, solver=self.solver)  # the loose-tolerance warning

    def _validate_3d(self):
        """What a 3D box does not take (yet): bars (laid in a section) and the macro calibration (a
        2D test)."""
        if self.rebar_ratio != 0:
            _bad("rebar_ratio", self.rebar_ratio, "0 when dim is 3 (bars are laid in a section)")
        if self.parameters != "paper-micro":
            _bad("parameters", self.parameters, "paper-micro when dim is 3 (the macro calibration is a 2D test)")

    def meso_overrides(self):
        """The mesostructure generator's parameters this test sets: size (and depth and dim in 3D),
        and the aggregate fraction when given."""
        kw = dict(width_mm=self.size_mm[0], height_mm=self.size_mm[1])
        if self.dim == 3:
            kw.update(dim=3, depth_mm=self.size_mm[2])
        if not self.aggregate_area_fraction < 0:
            kw["aggregate_area_fraction"] = self.aggregate_area_fraction
        return kw

    def temperature_history(self):
        """(days [day], temperatures [K]) of temperature_c or temperature_csv, None without either;
        OptionError (the one message form) for a value out of range, both options given, or a
        CSV file that is missing, unreadable, has a malformed row or days not increasing."""
        if self.temperature_c is not None:
            options.number("temperature_c", self.temperature_c, lo=T_MIN_C, hi=T_MAX_C, hi_incl=True,
                           allowed=f"{T_MIN_C:g} < temperature_c <= {T_MAX_C:g} [C] (above 0 K, at most 100 C)")
            if self.temperature_csv != "":
                _bad("temperature_csv", self.temperature_csv, "'' when temperature_c is given (one of the two)")
            return [0.0], [self.temperature_c + KELVIN]
        if not isinstance(self.temperature_csv, str):
            _bad("temperature_csv", self.temperature_csv, "a file name, or '' for none")
        if not self.temperature_csv:
            return None
        days, celsius = read_temperature_csv(self.temperature_csv)
        return days, [c + KELVIN for c in celsius]

    @property
    def humidity(self):
        """Whether the run has a moisture model: a face exposed or an initial h below 1."""
        return bool(self.humidity_faces) or self.humidity_initial != 1.0

    def humidity_history(self):
        """{face: h or (days [day], h)} of humidity_faces (CSV files read), after checking every
        humidity option (the initial h, the faces for the specimen's dimension, the exponent, the
        shrinkage coefficients, the moisture steps), in the one message form."""
        from .dem.humidity import FACES_2D, FACES_3D, DEFAULT_SHRINKAGE
        options.number("humidity_initial", self.humidity_initial, lo=0, hi=1, hi_incl=True)
        options.number("humidity_exponent", self.humidity_exponent, lo=0, lo_incl=True)
        options.number("humidity_steps_per_decade", self.humidity_steps_per_decade, lo=0)
        if not isinstance(self.shrinkage, dict):
            _bad("shrinkage", self.shrinkage, "a dict {kind name: k_sh}")
        for name, k in self.shrinkage.items():
            if name not in DEFAULT_SHRINKAGE:
                _bad("shrinkage kind", name, ", ".join(DEFAULT_SHRINKAGE))
            options.number(f"shrinkage {name}", k, lo=0, lo_incl=True, allowed="0 <= k_sh < inf [strain per unit of h]")
        if not isinstance(self.humidity_faces, dict):
            _bad("humidity_faces", self.humidity_faces, "a dict {face: h or CSV file}")
        faces = FACES_3D if self.dim == 3 else FACES_2D
        out = {}
        for face, value in self.humidity_faces.items():
            if face not in faces:
                _bad("humidity_faces face", face, ", ".join(faces) + f" (the faces of a {'box' if self.dim == 3 else 'section'})")
            if isinstance(value, str) and not options.is_number(_number_or_text(value)):
                out[face] = read_humidity_csv(value, face)
            else:
                h = _number_or_text(value)
                options.number(f"humidity_faces {face}", h, lo=0, hi=1, hi_incl=True)
                out[face] = float(h)
        if self.humidity and self.rebar_ratio != 0:
            _bad("rebar_ratio", self.rebar_ratio, "0 with a moisture model (humidity_faces or humidity_initial < 1): the "
                                                  "moisture network needs every particle's cell, and a bar carves some out")
        return out

    def rebar_layout(self):
        """The bars' swelldem.dem.rebar.RebarLayout (None without bars), from the options alone (size,
        ratio, bar count, steel); OptionError for a layout that does not fit the specimen."""
        if not self.rebar_ratio > 0:
            return None
        from .dem import rebar  # plain Python: the layout needs no YADE
        return rebar.layout(self.size_mm[0] * 1e-3, self.size_mm[1] * 1e-3, self.rebar_ratio, n_bars=self.rebar_bars,
                            young=self.rebar_young, yield_stress=self.rebar_yield_stress)

    @property
    def t_end(self):
        """The last physical time [day]: t_end_days, or the paper's end of the scenario's kinetics."""
        return self.t_end_days or paper.KINETICS[paper.SCENARIOS[self.scenario]["kinetics"]][2]


#: Temperatures the scenarios take [C]: above 0 K and at most 100 C (ContactKind's 0 < T <= 373.15 K).
T_MIN_C, T_MAX_C, KELVIN = -273.15, 100.0, 273.15


def read_history_csv(path, name, columns, check_value, file_allowed):
    """(days [day], values) of a history file: one row 'day, value' per line (`columns` names
    them, e.g. 'day, deg C'), blank lines and '#' comments skipped; at least one row, days >= 0
    and strictly increasing, each value checked by check_value(line number, value). OptionError
    naming `name` (the option) with the file or the line otherwise; file_allowed: what the option
    takes, for a file that cannot be read."""
    try:
        with open(path, encoding="utf-8") as f:
            lines = f.read().splitlines()
    except (OSError, UnicodeDecodeError) as e:
        _bad(name, path, f"{file_allowed} ({getattr(e, 'strerror', None) or e})")
    days, values = [], []
    for n, line in enumerate(lines, 1):
        text = line.split("#", 1)[0].strip()
        if not text:
            continue
        cells = text.split(",")
        try:
            if len(cells) != 2:
                raise ValueError(text)
            day, value = float(cells[0]), float(cells[1])
        except ValueError:
            _bad(f"{name} line {n}", line, f"two numbers '{columns}'")
        if days:
            options.number(f"{name} day (line {n})", day, lo=days[-1], unit="day",
                           allowed=f"day > {days[-1]:g}, the previous row's (days strictly increasing) [day]")
        else:
            options.number(f"{name} day (line {n})", day, lo=0, lo_incl=True, unit="day")
        check_value(n, value)
        days.append(day)
        values.append(value)
    if not days:
        _bad(name, path, f"a file with at least one row '{columns}'")
    return days, values


def read_temperature_csv(path):
    """(days [day], temperatures [C]) of a temperature history file (read_history_csv, rows
    'day, deg C'), T_MIN_C < T <= T_MAX_C."""
    return read_history_csv(path, "temperature_csv", "day, deg C", lambda n, t: options.number(
        f"temperature_csv temperature (line {n})", t, lo=T_MIN_C, hi=T_MAX_C, hi_incl=True,
        allowed=f"{T_MIN_C:g} < T <= {T_MAX_C:g} [C] (above 0 K, at most 100 C)"), "a readable text file of rows 'day, deg C'")


def _number_or_text(value):
    """A number given as text becomes the number; other text stays (a file name)."""
    if isinstance(value, str):
        try:
            return float(value)
        except ValueError:
            return value
    return value


def read_humidity_csv(path, face):
    """(days [day], h [-]) of an ambient humidity history file for `face` (read_history_csv, rows
    'day, h'), 0 < h <= 1."""
    name = f"humidity_faces {face}"
    return read_history_csv(path, name, "day, h", lambda n, h: options.number(f"{name} h (line {n})", h, lo=0, hi=1, hi_incl=True),
                            "a number in (0, 1] or a readable text file of rows 'day, h'")


def parse_kind_param(text):
    """'KIND.attribute=value' -> (KIND, attribute, value); value a Python literal (5e6, True, ...)
    or else the text itself (viscoelastic)."""
    head, eq, value = text.partition("=")
    kind, dot, attr = head.partition(".")
    if not (eq and dot and kind and attr):
        _bad("kind_param", text, "KIND.attribute=value, e.g. MORTAR.tensileStrength=5e6")
    try:
        value = ast.literal_eval(value)
    except (ValueError, SyntaxError):
        pass
    return kind.strip(), attr.strip(), value


def parse_name_value(text, option="solver_param", form="NAME=VALUE, e.g. fallbackIterations=3"):
    """'NAME=VALUE' -> (NAME, value); value a Python literal (5, 1e-6, True, [1.0, 2.0]) or else the
    text itself (the option's checks, or the plugin's, then refuse it where a number is due).
    `option` and `form` name the option and its form in the message for text without '='."""
    name, eq, value = text.partition("=")
    if not (eq and name.strip()):
        _bad(option, text, form)
    try:
        value = ast.literal_eval(value)
    except (ValueError, SyntaxError):
        pass
    return name.strip(), value


def parse_solver_param(text):
    """A --solver-param 'NAME=VALUE' (parse_name_value)."""
    return parse_name_value(text)


def add_arguments(parser):
    """Adds one command-line option per SwellingTest field to an argparse parser."""
    for f in fields(SwellingTest):
        m = f.metadata
        flag = m["flag"] or "--" + f.name.replace("_", "-")
        unit = f" [{m['unit']}]" if m["unit"] and m["unit"] != "-" else ""
        sets = f" (sets {m['sets']})" if m["sets"] else ""
        default = f.default_factory() if f.default is MISSING else f.default
        help_text = (m["help"] + unit + sets).replace("%", "%%")  # argparse formats help with %
        if f.type is bool or isinstance(default, bool):
            if default:
                parser.add_argument("--no-" + f.name.replace("_", "-"), dest=f.name, action="store_false", help=help_text)
            else:
                parser.add_argument(flag, dest=f.name, action="store_true", help=help_text)
        elif isinstance(default, tuple):
            # size_mm takes W H, or W H D for a 3D box (validate() checks the count against dim)
            parser.add_argument(flag, dest=f.name, type=type(default[0]), nargs="+" if f.name == "size_mm" else len(default),
                                default=default, metavar="W H [D]" if f.name == "size_mm" else None,
                                help=help_text + f" (default {default})")
        elif f.name == "humidity_faces":
            parser.add_argument(flag, dest=f.name, action="append", nargs=2, default=[], metavar=("FACE", "H|CSV"), help=help_text)
        elif isinstance(default, dict):
            parser.add_argument(flag, dest=f.name, action="append", default=[],
                                metavar={"kind_params": "KIND.ATTR=VALUE", "shrinkage": "KIND=VALUE"}.get(f.name, "NAME=VALUE"),
                                help=help_text)
        else:
            parser.add_argument(flag, dest=f.name, type=m["type"] or type(default), default=default, choices=m["choices"],
                                help=help_text + f" (default {default})")


def add_solver_argument(parser, default=None):
    """Adds --solver, as the SwellingTest field has it, to a study's parser. default: the field's, or a
    study's own (paper_study.py keeps the paper's ADR)."""
    f = next(f for f in fields(SwellingTest) if f.name == "solver")
    default = default or f.default
    parser.add_argument("--solver", default=default, choices=f.metadata["choices"], help=f.metadata["help"] + f" (default {default})")


def from_arguments(ns):
    """The SwellingTest of parsed arguments (see add_arguments); ValueError for a malformed --kind-param
    or --solver-param."""
    kw = {f.name: getattr(ns, f.name) for f in fields(SwellingTest)}
    kw["size_mm"] = tuple(kw["size_mm"])
    params = {}
    for text in kw["kind_params"]:
        kind, attr, value = parse_kind_param(text)
        params.setdefault(kind, {})[attr] = value
    kw["kind_params"] = params
    kw["solver_params"] = dict(parse_solver_param(text) for text in kw["solver_params"])
    faces = {}
    for face, value in kw["humidity_faces"]:
        if face in faces:
            _bad("humidity_faces face", face, "each face once")
        faces[face] = _number_or_text(value)
    kw["humidity_faces"] = faces
    kw["shrinkage"] = dict(parse_name_value(text, "shrinkage", "KIND=VALUE, e.g. MORTAR=3e-3") for text in kw["shrinkage"])
    return SwellingTest(**kw)


def add_resume_argument(parser):
    """Adds --resume DIR to a swelling test's parser (resumed_test() reads it)."""
    parser.add_argument("--resume", metavar="DIR", default="",
                        help="continue the run in DIR, stopped (interrupted, failed or killed) after some steps, from its last "
                             "saved step: a run made with --save-state; its own settings, results.json's config, are used, and "
                             "an option given beside --resume must have the recorded value")


def given_options(parser, argv):
    """The names (dests) of the options that argv gives, whatever their value: argparse fills in a
    default only where the namespace has no value yet, so those left at a marker were not given."""
    import argparse
    unset = object()
    names = [a.dest for a in parser._actions if a.dest != argparse.SUPPRESS and a.dest != "help"]
    ns = argparse.Namespace(**{n: unset for n in names})
    for a in parser._actions:
        if isinstance(a, argparse._AppendAction):
            setattr(ns, a.dest, [])  # appended to: given when not empty
    parser.parse_args(argv, ns)
    return {n for n in names if getattr(ns, n) is not unset and getattr(ns, n) != []}


def _json_value(v):
    import json
    return json.loads(json.dumps(v, default=float))


def resumed_test(folder, given_test=None, given=()):
    """The SwellingTest of the run to resume in `folder`, from its results.json's config (out:
    `folder`). Refused, in the one message form, before any work: a folder without a swelling test's
    results.json, a run that finished, one without its saved state (made without --save-state), and
    an option among `given` (names of SwellingTest fields, given_options()) whose value in
    `given_test` differs from the recorded one (another setting would not continue this run)."""
    from . import report
    from .dem.recorder import STATE_FILE
    if not isinstance(folder, str) or not os.path.isdir(folder):
        _bad("resume", folder, "the folder of a run made with --save-state")
    try:
        res = report.load_results(os.path.join(folder, "results.json"))
    except report.ResultsError as e:
        _bad("resume", folder, f"the folder of a run made with --save-state ({e})")
    if res["status"] == "finished":
        _bad("resume", folder, "the folder of a run that did not finish (this one finished)")
    if not os.path.exists(os.path.join(folder, STATE_FILE)):
        _bad("resume", folder, f"the folder of a run made with --save-state (no {STATE_FILE} in it)")
    cfg = res.get("config") or {}
    names = [f.name for f in fields(SwellingTest)]
    kw = {n: cfg[n] for n in names if n in cfg}
    kw["size_mm"] = tuple(kw.get("size_mm", ()))
    kw["out"] = folder
    test = SwellingTest(**kw)
    for name in sorted(set(given) & set(names)):
        mine = getattr(given_test, name)
        if name == "out":
            if os.path.abspath(mine) != os.path.abspath(folder):
                _bad("out", mine, f"{folder}, the folder --resume continues, or left out")
        elif _json_value(mine) != _json_value(getattr(test, name)):
            _bad(name, mine, f"{getattr(test, name)!r}, the run's in {folder} (--resume continues it with its own settings)")
    return test


def _job_folder_name(description, line):
    # a description synthesized by YADE (e.g. "scenario='isr',seed=3") holds quotes and commas
    name = re.sub(r"[^A-Za-z0-9._=+-]+", "_", str(description)).strip("_")
    return name or f"line{line}"


def from_batch_table(test, table_line=None):
    """The SwellingTest of one line of a yade-batch table: the fields of `test` (the command line's)
    are the defaults, each table column sets the SwellingTest field of its name (swelling_test.py
    --help lists them; a 'description' column names the job). Values are Python literals without
    spaces, as yade.utils.readParamsFromTable reads them: 'isr' (quoted), True, (12,12),
    {'MORTAR':{'tensileStrength':5e6}}.

    table_line: 'file.table:N' (N the line number as seen in an editor); default the YADE_BATCH
    environment variable that yade-batch sets for each job. Without either, returns `test`
    unchanged. The job writes into <out>/<description>, out being the table's 'out' column or else
    out/<table file name without extension>, so that every line has its own folder.
    readParamsFromTable also sets O.tags 'description', 'params', 'line' and 'd.id' (kept by
    to_yade's reset, written to results.json's yade_tags). ValueError for a column that is not a
    SwellingTest field or a value that is not a literal, before any work."""
    table_line = table_line if table_line is not None else os.environ.get("YADE_BATCH", "")
    if not table_line:
        return test
    from .plugin import require
    yade, _ = require("swelldem.scenario.from_batch_table")
    from yade import utils
    table, _, line = table_line.rpartition(":")
    names = [f.name for f in fields(SwellingTest)]
    try:
        rows = utils.TableParamReader(table).paramDict()
    except (OSError, IndexError) as e:
        _bad("batch table", table_line, f"a readable yade-batch table file:line ({e})")
    row = rows.get(int(line)) if line.isdigit() else None
    if row is None:
        _bad("batch table line", table_line, f"one of the table's lines {', '.join(map(str, sorted(rows)))}")
    for col in row:
        if col != "description" and not col.startswith("!") and col not in names:
            _bad("batch table column", col, ", ".join(["description"] + names))
    defaults = {name: getattr(test, name) for name in names}
    try:
        utils.readParamsFromTable(tableFileLine=table_line, noTableOk=False, **defaults)
    except (NameError, SyntaxError) as e:  # eval of a value: an unquoted word, a space inside a value
        _bad("batch table value", f"{table_line} ({e})", "Python literals without spaces, strings quoted: 'isr'")
    from yade.params import table as values
    kw = {name: getattr(values, name) for name in names}
    if isinstance(kw["size_mm"], list):
        kw["size_mm"] = tuple(kw["size_mm"])
    base = kw["out"] if "out" in row else os.path.join("out", os.path.splitext(os.path.basename(table))[0])
    kw["out"] = os.path.join(base, _job_folder_name(yade.Omega().tags["description"], line))
    return SwellingTest(**kw)


def _dem():
    from . import dem
    from .plugin import require
    require("swelldem.scenario")
    return dem


def calibrate_modulus_factor(shear_ratio=0.3, seed=11, size_mm=15.0, strain=1e-4, **meso_overrides):
    """beta = E_macro / E_c of a random mortar assembly (no aggregates) whose contacts have modulus
    E_c and shear ratio `shear_ratio`, from a uniaxial tension test solved with the ADR solver:
    the left band held in x, the right band moved by strain x width, y free but for one disc."""
    dem = _dem()
    from . import meso
    from .dem.uniaxial import bands
    import numpy as np
    import yade
    a = meso.generate(seed=seed, width_mm=size_mm, height_mm=size_mm, aggregate_area_fraction=0, **meso_overrides)
    e_c = 1e9
    kind = dem.contact_kind("MORTAR", behaviour="elastic", young=e_c, shear_ratio=shear_ratio)
    solver = dem.make_solver("adr", tStart=1.0, tEnd=10.0, stepsPerDecade=1, tolerance=1e-6, verbose=False)
    dem.to_yade(a, {"MORTAR": kind}, solver)
    O = yade.Omega()
    left, right = bands(a)
    delta = strain * a.width_m
    for i in left:
        O.bodies[int(i)].state.blockedDOFs = "xzXY"
    bottom = int(left[np.argmin(a.y[left])])
    O.bodies[bottom].state.blockedDOFs = "xyzXY"
    for i in right:
        O.bodies[int(i)].state.blockedDOFs = "xzXY"
    # The solver's set-up first: it records the held bodies where they are, so that the move below
    # reaches the contacts' shear too (YADE's geometry takes the shear from velocities). Moved before
    # the set-up, the band's contacts kept the jump's shear part unseen and beta came out 24 % low
    # (0.380 against 0.499, also given by NewtonIntegrator loading, docs/residual-properties.md).
    O.step()
    for i in right:
        b = O.bodies[int(i)]
        b.state.pos = b.state.pos + yade.Vector3(delta, 0, 0)
    dem.run_to_end(solver)
    reaction = -sum(O.forces.f(int(i))[0] for i in right)
    sigma = reaction / (a.height_m * a.thickness_m)
    beta = sigma / strain / e_c
    return {"run": True, "beta": beta, "e_macro_per_e_c": beta, "n_particles": len(a.x), "size_mm": size_mm, "seed": seed,
            "shear_ratio": shear_ratio, "strain": strain, "adr_iterations": solver.totalIterations}


def gel_kinds(test):
    """The kind names the gel pockets of an asr-coarse test are drawn from (gel_pockets.pool_kinds)."""
    from .meso import gel_pockets
    return tuple(paper.KIND_NAMES[k] for k in gel_pockets.pool_kinds(test.gel_pockets))


def make_kinds(test):
    """The three ContactKind objects of a test with the paper's values as contact values, the
    test's factors and its kind_params; each constructor validates its values. Swelling kinds get
    swellDispInf 0 here: it depends on the mesostructure (set_swelling)."""
    dem = _dem()
    sc = paper.SCENARIOS[test.scenario]
    history = test.temperature_history()
    temperature = {} if history is None else {"temperatureDays": history[0], "temperatures": history[1]}
    kinds = {}
    for name in paper.KIND_NAMES:
        swells = name in sc["swelling_kinds"] or (test.scenario == "asr-coarse" and name in gel_kinds(test))
        common = dict(shear_ratio=test.shear_ratio, kinetics=sc["kinetics"], damage=test.damage,
                      tensile_strength=paper.TENSILE_STRENGTH[name] * test.strength_scale, swelling=swells)
        given = {**temperature, **test.kind_params.get(name, {})}
        if name == "AGG":
            kinds[name] = dem.contact_kind(name, behaviour=given.pop("behaviour", "elastic"), young=test.aggregate_young, **common, **given)
        else:
            # a kind's own behaviour (KIND.behaviour=...) over the test's
            behaviour = given.pop("behaviour", "viscoelastic" if test.behaviour == "viscoelastic" else "aging-elastic")
            extra = {"kelvinUnitsPerDecade": test.kelvin_units_per_decade, **given}
            kinds[name] = dem.contact_kind(name, behaviour=behaviour, b3=paper.B3_OF_KIND[name], **common, **extra)
    return kinds


def scale_kinds(kinds, beta, kind_params):
    """parameters='macro': micro q_i = beta q_i and E_c = E / beta (the law is linear in the compliance);
    values given in kind_params are contact values and stay as given."""
    for name, k in kinds.items():
        given = kind_params.get(name, {})
        if name == "AGG":
            if "young" not in given:
                k.young = k.young / beta
            continue
        for q in ("q1", "q2", "q3", "q4"):
            if q not in given:
                setattr(k, q, beta * getattr(k, q))


def gel_displacement(test, d_rule):
    """The gel pockets' ultimate swelling displacement [m] of an asr-coarse test from Table 3.2's
    d = eps_inf x 2 R_mean (d_rule), under the test's gel_displacement reading."""
    from .meso import gel_pockets
    return gel_pockets.pocket_displacement(d_rule, test.gel_displacement, test.gel_fraction)


def _quantiles(values):
    """The 5, 50 and 95 % quantiles of `values` (NaN for none), as the gel-pocket record holds them."""
    import numpy as np
    return np.quantile(values, [0.05, 0.5, 0.95]).tolist() if len(values) else [float("nan")] * 3


def gel_pocket_record(test, built):
    """results.json's 'gel_pockets' of an asr-coarse run before it runs: the reading, the pockets'
    count and d_inf [m], the quantiles (5 / 50 / 95 %) of their fully restrained forces -E_c A/L x d
    [kN] (swelldem.meso.gel_pockets), and the force balance's bound on the 5 % quantile of the AGG
    forces [kN] with the whole swelling (xi = 1) and with the run's xi(t_end) - xi(t_start)."""
    import numpy as np
    from .meso import gel_pockets
    a, gel = built.assembly, np.asarray(built.gel, dtype=np.int64)
    d = gel_displacement(test, built.d_inf)
    k = built.kinds["AGG"]
    history = test.temperature_history() or ((), ())
    t_end = built.solver.tEnd
    xi_start, xi_end = paper.larive_xi_under([test.t_start_days, t_end], k.tauC, k.tauL, *history)
    dxi = float(xi_end - xi_start)
    # ITZ pockets (with-itz) at the ITZ's modulus at the end of the run, its aging-elastic value
    young = {paper.AGG: k.young, paper.ITZ: 1.0 / built.kinds["ITZ"].compliance(t_end + 0.01, t_end)}
    full = gel_pockets.restrained_forces(a, gel, d, young)
    return {"reading": test.gel_pockets, "displacement": test.gel_displacement, "radius_mm": test.gel_pocket_radius_mm,
            "n": int(len(gel)), "n_agg": int((a.kind[gel] == paper.AGG).sum()), "n_itz": int((a.kind[gel] == paper.ITZ).sum()),
            "d_inf_m": d, "xi_run": dxi, "restrained_kN_q05_q50_q95": _quantiles(full / 1e3),
            "agg_p05_bound_kN": gel_pockets.quantile_bound(a, gel, full) / 1e3,
            "agg_p05_bound_run_kN": gel_pockets.quantile_bound(a, gel, full * dxi) / 1e3,
            "restrained_kN": (full / 1e3).tolist()}


def gel_pocket_forces(record, built):
    """Adds to a gel-pocket record the pockets' final normal forces: their quantiles [kN] and the
    restraint degree F / (restrained force x the run's xi) of the intact AGG pockets (5 / 50 / 95 %;
    1: fully restrained, 0: free)."""
    import numpy as np
    from .plugin import require
    O = require("swelldem.scenario.gel_pocket_forces")[0].Omega()
    gel = np.asarray(built.gel, dtype=np.int64)
    fn, intact = [], []
    for c in gel:
        i, j = built.scene.contacts[int(c)]
        I = O.interactions[int(i), int(j)]
        fn.append(I.phys.Fn if I is not None and I.isReal else 0.0)
        intact.append(bool(I is not None and I.isReal and not I.phys.broken))
    fn, intact = np.array(fn), np.array(intact, dtype=bool)
    full = np.asarray(record["restrained_kN"]) * 1e3 * record["xi_run"]
    sel = intact & (built.assembly.kind[gel] == paper.AGG) & (full < 0)
    record["fn_kN_q05_q50_q95"] = _quantiles(fn / 1e3)
    record["restraint_q05_q50_q95"] = _quantiles(fn[sel] / full[sel])
    return record


def set_swelling(test, kinds, d_inf):
    """swellDispInf = d_inf [m] of the kinds whose every contact swells (unless kind_params sets it)."""
    for name in paper.SCENARIOS[test.scenario]["swelling_kinds"]:
        if "swellDispInf" not in test.kind_params.get(name, {}):
            kinds[name].swellDispInf = d_inf


def make_humidity(test, built, solver):
    """The moisture of a built test (swelldem.dem.humidity.HumidityDriver): its faces, initial h,
    exponent and shrinkage coefficients (the defaults for kinds the test leaves out), on the
    solver's planned times."""
    from .dem import humidity
    t0 = time.time()
    swelling = [k for k in built.kinds.values() if k.swelling]
    xi = None
    if swelling:  # the swelling kinds share the scenario's kinetics and temperatures
        k = swelling[0]
        xi = lambda t: paper.larive_xi_under(t, k.tauC, k.tauL, list(k.temperatureDays), list(k.temperatures),  # noqa: E731
                                             T0=k.referenceTemperature, Uc=k.Uc, UL=k.UL)
    driver = humidity.HumidityDriver(built.assembly, built.scene, solver, test.humidity_history(), test.humidity_initial,
                                     humidity.Coupling(test.humidity_exponent, {**humidity.DEFAULT_SHRINKAGE, **test.shrinkage}),
                                     steps_per_decade=test.humidity_steps_per_decade, xi=xi)
    hist = driver.history
    print(f"swelldem: set-up: moisture {len(hist.times_days) - 1} steps, {int(np.sum(hist.iterations))} Newton iterations, "
          f"h at the end {driver.mean_h()['specimen'][-1]:.3f} (specimen mean), {time.time() - t0:.1f} s", flush=True)
    return driver


def humidity_record(test, driver):
    """The moisture of a run as results.json records it: the faces (sealed ones left out) with
    their ambient h or history, the initial h, the coupling, and per planned time the mean h of
    each kind's contacts and particles and of the specimen (the h history is computed before the
    run: the transport does not depend on the mechanics)."""
    hist = driver.history
    faces = {face: (v if not isinstance(v, tuple) else {"days": list(v[0]), "h": list(v[1])})
             for face, v in driver.faces.items()}
    return {"faces": faces, "sources": {f: str(v) for f, v in test.humidity_faces.items()},
            "h_initial": test.humidity_initial, "exponent": driver.coupling.exponent,
            "shrinkage_per_h": driver.coupling.shrinkage, "steps_per_decade": test.humidity_steps_per_decade,
            "moisture_steps": int(len(hist.times_days) - 1), "newton_iterations": int(np.sum(hist.iterations)),
            "balance_residual_max": float(np.max(hist.relative_balance_residual())) if len(hist.times_days) > 1 else 0.0,
            "times_days": driver.times.tolist(), "mean_h": driver.mean_h(),
            "swelling_factor_mean": driver.factor.mean(axis=1).tolist() if driver.factor.size else []}


def temperature_record(test, kinds):
    """The temperature history of a run as results.json records it: its source, and per kind the
    days [day] and temperatures [K] it holds (empty: none, the kind at its reference
    temperatures, also recorded) and whether its creep follows them."""
    source = ("temperature_c" if test.temperature_c is not None else
              test.temperature_csv if test.temperature_csv else "none: each kind at its reference temperatures")
    return {"source": source, "per_kind": {
        name: {"days": list(k.temperatureDays), "temperatures_K": list(k.temperatures),
               "temperatures_C": [T - KELVIN for T in k.temperatures], "referenceTemperature_K": k.referenceTemperature,
               "thermalCreep": k.thermalCreep, "creepReferenceTemperature_K": k.creepReferenceTemperature}
        for name, k in kinds.items()}}


class Interrupted(Exception):
    """A stop signal (SIGTERM, Ctrl-C) reached a running swelling test; its results.json says so.
    `where`: the step it stopped in and how far into it ('' before the solver has started)."""
    where = ""


class RunFailed(RuntimeError):
    """A swelling test that stopped before its end: the solver found no equilibrium, diverged, or
    met a value it refuses. Its results.json says 'failed: <message>' (`status`) and keeps the
    steps done; str() is the solver's message."""

    def __init__(self, message, out):
        super().__init__(message)
        self.out = out

    @property
    def status(self):
        return f"failed: {self}"


def _catch_stop_signals():
    """SIGTERM and SIGINT stop the run between two chunks of iterations with Interrupted, so that
    results.json records 'interrupted: <signal>' (a SIGKILL cannot be caught: the run is then
    left 'running' with the time of its last step, results.json's 'updated'). Returns the
    handlers to restore; none outside the main thread, where Python cannot set them."""
    def stop(signum, frame):
        raise Interrupted(signal.Signals(signum).name)
    try:
        return {sig: signal.signal(sig, stop) for sig in (signal.SIGTERM, signal.SIGINT)}
    except ValueError:
        return {}


def prepare(test, extra_times=()):
    """Checks everything before any work: test.validate(), then the plugin objects of the test
    (the three ContactKinds and the solver), whose constructors check their values. Returns
    (kinds, solver) for run(); ValueError in the one message form otherwise.
    extra_times [day]: further physical times the solver stops at (its extraTimes), e.g. the ages
    of virtual tests."""
    test.validate()
    try:
        kinds = make_kinds(test)
        if test.kind_params.get("BOND"):  # the bars' BOND kind, made at the build, checked by its constructor here
            from .dem import rebar
            rebar.bond_kind(kinds["ITZ"], test.kind_params["BOND"])
    except TypeError as e:  # e.g. MORTAR.tensileStrength=abc: boost.python cannot make a double of it
        text = {f"{n}.{a}": v for n, attrs in test.kind_params.items() for a, v in attrs.items() if isinstance(v, str)}
        if len(text) == 1:
            (name, value), = text.items()
            _bad(name, value, f"a value of the attribute's type: a number, True/False or a name ({e})")
        _bad("kind_params", test.kind_params, f"values of each attribute's type: a number, True/False or a name ({e})")
    return kinds, make_solver(test, extra_times)


def make_solver(test, extra_times=()):
    """The solver of a test: its class (test.solver) with the test's schedule (t_start_days, t_end,
    steps_per_decade), its tolerance when given, extra_times [day] as extraTimes, and last the
    test's solver_params, all passed to the constructor, which validates every value; a setting the
    test leaves out keeps the class's default (the one place defaults are stated). ValueError in the
    one message form for a name that is not a setting of that solver (listing the allowed ones) or a
    value of the wrong type."""
    dem = _dem()
    dem.check_solver_settings(test.solver, list(test.solver_params))
    settings = dict(tStart=test.t_start_days, tEnd=test.t_end, stepsPerDecade=test.steps_per_decade, label="swelldemSolver")
    if len(extra_times):
        settings["extraTimes"] = sorted(float(t) for t in extra_times)
    if test.tolerance is not None:
        settings["tolerance"] = test.tolerance
    settings.update(test.solver_params)
    try:
        solver = dem.make_solver(test.solver, **settings)
        solver.checkMpiRanks()  # under mpirun, a solver that would leave the other ranks idle: before any work
        return solver
    except TypeError as e:  # e.g. fallbackIterations=abc: boost.python cannot make a number of it
        why = " ".join(str(e).split())
        text = ", ".join(f"{k}={v!r}" for k, v in test.solver_params.items())
        _bad("solver_params", text or settings, f"values of each setting's type: a number, True/False, a list or a name ({why})")


def make_assembly(test):
    """The mesostructure of a test (swelldem.meso.generate of its size, seed and aggregate
    fraction), with the discs its bars replace carved out; plain Python."""
    from . import meso
    size = " x ".join(f"{v:g}" for v in test.size_mm)
    print(f"swelldem: set-up: mesostructure {size} mm, seed {test.seed}", flush=True)
    assembly = meso.generate(seed=test.seed, **test.meso_overrides())
    lay = test.rebar_layout()  # checked by validate(), before any work
    if lay is not None:
        from .dem import rebar
        assembly = rebar.carve(assembly, lay)  # the discs the bar replaces
    return assembly


@dataclass
class Built:
    """A swelling test built as a YADE scene (build()): what run() records and a benchmark times."""
    test: SwellingTest
    kinds: dict  # name -> ContactKind, as run (macro scaling and swellDispInf applied)
    solver: object  # the LogTimeSolver, last engine of O.engines (label 'swelldemSolver')
    assembly: object  # swelldem.meso.Assembly (bars carved out)
    scene: object  # swelldem.dem.YadeScene
    d_inf: float  # [m] swelling displacement at infinity of the swelling kinds
    r_mean: float  # [m] mean disc radius
    calibration: dict  # the macro calibration's record, or why none was run
    gel: list = field(default_factory=list)  # asr-coarse: the gel-pocket contacts
    bars: object = None  # swelldem.dem.rebar's bars, or None
    platens: object = None  # swelldem.dem.platens' platens
    layout: object = None  # the bars' RebarLayout, or None

    @property
    def solver_settings(self):
        """{setting: value} of the solver as it runs (every setting of its class)."""
        return _dem().solver_settings(self.solver)

    @property
    def kind_settings(self):
        """{kind name: {setting: value}} of every kind of the scene as it runs (the three of the
        test, and the bars' and platens' when present): the kinds the Ip2 holds."""
        dem = _dem()
        return {name: dem.kind_settings(k) for name, k in dem.functor_kinds(self.scene.ip2).items()}


def build(test, prepared=None, extra_times=(), assembly=None, reset=True, t0=None):
    """The one way a swelling test becomes a YADE scene, for run() and the benchmarks: prepare()
    (unless `prepared`, its result, is given), the mesostructure (make_assembly(), unless
    `assembly` is given), in macro the modulus calibration and the kinds' scaling, the swelling
    kinds' d_inf, the scene (dem.to_yade: O.reset, discs, engines with the solver last, bonded
    contacts), the gel pockets, the bars and the platens. Writes nothing. reset=False builds into
    the current scene, which must be empty (e.g. one made by O.addScene). Returns a Built; the
    solver has not run yet (dem.run_to_end(built.solver), or O.run). t0: the time.time() the
    set-up line counts from (default now)."""
    kinds, solver = prepared or prepare(test, extra_times)
    dem = _dem()
    t0 = time.time() if t0 is None else t0
    if assembly is None:
        assembly = make_assembly(test)
    lay = test.rebar_layout()
    if test.parameters == "macro":
        print("swelldem: set-up: calibrating the contact moduli (parameters = macro)", flush=True)
        cal = calibrate_modulus_factor(shear_ratio=test.shear_ratio)
        scale_kinds(kinds, cal["beta"], test.kind_params)
        # the specimen's moduli the contact values imply: beta x E_c (E_c = 1/J(28.01, 28) for mortar and ITZ)
        cal["macro_young_28d_Pa"] = {name: cal["beta"] / kinds[name].compliance(28.01, 28.0) for name in ("MORTAR", "ITZ")}
        cal["macro_young_28d_Pa"]["AGG"] = cal["beta"] * kinds["AGG"].young
    else:
        cal = {"run": False, "why": "parameters = paper-micro: the paper's values are contact values, beta is not needed"}
    r_mean = float(assembly.r.mean())
    d_inf = test.eps_inf * 2 * r_mean  # the paper's micro-macro rule (Table 3.2)
    set_swelling(test, kinds, d_inf)
    ys = dem.to_yade(assembly, kinds, solver, reset=reset)
    print(f"swelldem: set-up: {len(assembly.x)} {'spheres' if test.dim == 3 else 'discs'}, {len(ys.contacts)} bonded contacts, "
          f"{time.time() - t0:.1f} s", flush=True)
    gel = []
    if test.scenario == "asr-coarse":
        gel = dem.set_gel_pockets(ys, assembly, test.gel_fraction, gel_displacement(test, d_inf), test.seed,
                                  test.gel_pockets, test.gel_pocket_radius_mm * 1e-3)
    bars = None
    if lay is not None:
        from .dem import rebar
        bars = rebar.add_bars(assembly, ys, lay, kinds["ITZ"], test.kind_params.get("BOND"))
    from .dem.platens import Boundary, add_platens
    platens = add_platens(assembly, ys, *(Boundary.parse(f"boundary_{a}", getattr(test, f"boundary_{a}")) for a in ("x", "y", "z")))
    return Built(test=test, kinds=kinds, solver=solver, assembly=assembly, scene=ys, d_inf=d_inf, r_mean=r_mean, calibration=cal,
                 gel=gel, bars=bars, platens=platens, layout=lay)


def run_or_exit(test, prog, prepared=None, **kw):
    """run(test, prepared, **kw) for a script `prog`: the results dict of a run that finished; a
    run that stops ends the program with one line on stderr and exit status 1, no traceback:
    '<prog>: failed: <the solver's message> (<out>/results.json)' for a failed run (results.json
    holds that status and the steps done), '<prog>: interrupted by <signal> ...' for a stop
    signal, '<prog>: <message>' for a ValueError raised before the run (e.g. aggregates that do
    not fit the specimen: the generator's draw, which the checks cannot foresee)."""
    try:
        return run(test, prepared, **kw)
    except RunFailed as e:
        sys.exit(f"{prog}: {e.status} ({os.path.join(e.out, 'results.json')})")
    except Interrupted as e:  # results.json says "interrupted: <signal>"; the steps done are kept
        where = f" {e.where}" if e.where else ""
        sys.exit(f"{prog}: interrupted by {e}{where}; results so far in {os.path.join(test.out, 'results.json')}")
    except ValueError as e:
        sys.exit(f"{prog}: {e}")


def run_all(tests, prog, keep_failed=False):
    """Runs every SwellingTest of the dict `tests` in this process, one after the other, for a
    study script `prog`; a test whose out folder already holds a finished run (or, with
    keep_failed, a failed one) is read back instead, so that a study that stopped resumes. A run
    that fails is reported on stdout and its results.json (the steps it did) kept. Returns
    {key: results dict}."""
    from . import report
    keep = ("finished", "failed") if keep_failed else ("finished",)
    results = {}
    for key, test in tests.items():
        path = os.path.join(test.out, "results.json")
        if os.path.exists(path):
            res = report.load_results(path)  # a run kept from an earlier version of swelldem reads in today's form
            if res.get("status", "").split(":")[0] in keep:
                results[key] = res
                continue
        print(f"{prog}: {key}", flush=True)
        try:
            results[key] = run(test)
        except RunFailed as e:  # reported; its results.json (the steps done) is read back and the others go on
            print(f"{prog}: {key} {e.status}", flush=True)
            results[key] = report.load_results(path)
    return results


#: O.tags a yade-batch job carries (yade.utils.readParamsFromTable sets them), kept in results.json.
BATCH_TAGS = ("id", "line", "description", "params", "defaultParams", "d.id")


def batch_tags():
    """The BATCH_TAGS present in O.tags, as a dict (empty outside YADE)."""
    try:
        from .plugin import require
        yade, _ = require("swelldem.scenario.batch_tags")
    except Exception:  # noqa: BLE001 - plain Python has no O.tags
        return {}
    tags = yade.Omega().tags
    return {k: tags[k] for k in BATCH_TAGS if k in tags.keys()}


def run(test, prepared=None, extra_times=(), after_step=None, resume=False):
    """Runs one swelling test inside YADE; writes results.json, tables, plots and VTK into test.out.
    Order: prepare() (Python checks, then the plugin objects, whose constructors validate; pass
    its result as `prepared` to check before other work, with the same extra_times), then the
    mesostructure, the (macro) calibration, the scene and the run.
    extra_times [day]: see prepare(); after_step: a callable run without arguments after the
    recorder at every converged step (e.g. saving the scene at a test age, swelldem.residual).
    resume: go on with the run in test.out (resumed_test() gives its test) from its saved state:
    the scene is built again as the run built it (its assembly.npz), which gives the recorder the
    run's start, then the state (recorder.STATE_FILE) is loaded over it and the run goes on; the
    results of the steps done are kept, results.json's 'resumed' lists each resume."""
    kinds, solver = prepared or prepare(test, extra_times)
    from . import report
    from .dem import recorder
    from .dem import scene as dem_scene
    t0 = time.time()
    os.makedirs(test.out, exist_ok=True)
    if resume:
        from . import meso
        assembly = meso.load(os.path.join(test.out, "assembly.npz"))
    else:
        assembly = make_assembly(test)
        assembly.save(os.path.join(test.out, "assembly.npz"))
    built = build(test, (kinds, solver), assembly=assembly, t0=t0)
    ys, cal, gel, bars, platens, lay, d_inf = built.scene, built.calibration, built.gel, built.bars, built.platens, built.layout, built.d_inf
    r_mean = built.r_mean
    counts = {name: int((assembly.kind == k).sum()) for k, name in enumerate(paper.KIND_NAMES)}
    res = {"scenario": test.scenario, "behaviour": test.behaviour, "damage": test.damage, "solver": test.solver, "tolerance": solver.tolerance, "config": asdict(test),
           "solver_settings": built.solver_settings, "kinds": built.kind_settings,
           "calibration": cal, "d_inf_m": d_inf, "r_mean_m": r_mean, "n_particles": int(len(assembly.x)),
           "n_contacts_by_kind": counts, "n_gel_pockets": int(len(gel)), "times_days": [], "swelling_strain_x": [],
           "swelling_strain_y": [], "swelling_strain_area": [], "platen_stress_x_Pa": [], "platen_stress_y_Pa": [],
           "platen_disp_x_m": [], "platen_disp_y_m": [], "unbalanced_ratio": [], "iterations_per_step": [], "step_at_round_off": [],
           "round_off_ratio": [], "iterations": 0,
           "newton_iterations": 0, "relaxation_iterations": 0,
           "per_kind": {n: {"fn_p05_kN": [], "fn_p95_kN": [], "broken": [], "born_broken": []} for n in paper.KIND_NAMES},
           "temperature": temperature_record(test, kinds),
           "status": "running", "wall_s": 0.0, "yade_tags": batch_tags()}
    if len(gel):
        res["gel_pockets"] = gel_pocket_record(test, built)
        g = res["gel_pockets"]
        print(f"swelldem: gel pockets ({g['reading']}, d {g['displacement']}): {g['n']} contacts, d_inf {g['d_inf_m']:.3g} m, "
              f"fully restrained force {g['restrained_kN_q05_q50_q95'][1]:.1f} kN (median); bound on the AGG 5 % quantile "
              f"{g['agg_p05_bound_run_kN']:.1f} kN at the run's end", flush=True)
    if test.dim == 3:  # a box: the z strain and the volume change instead of the area change
        del res["swelling_strain_area"]
        res.update(dim=3, swelling_strain_z=[], swelling_strain_volume=[], platen_stress_z_Pa=[], platen_disp_z_m=[])
    if bars is not None:
        res["rebar"] = {"ratio": lay.ratio, "n_bars": lay.n_bars, "y_m": list(lay.y_m), "thickness_m": lay.thickness_m,
                        "disc_radius_m": lay.radius_m, "young_Pa": lay.young, "yield_stress_Pa": lay.yield_stress, "yield_day": None,
                        "n_bond_contacts": bars.n_bond}
        res["rebar_stress_max_Pa"], res["rebar_stress_mean_Pa"] = [], []
    if resume:  # the recorded results, not the fresh ones (the configuration is the run's)
        res = report.load_results(os.path.join(test.out, "results.json"))
        res["status"] = "running"
    rec = recorder.StepRecorder(assembly, ys, solver, res, test.out, vtk_every=test.vtk_every, platens=platens, bars=bars,
                                save_state=test.save_state, resuming=resume)
    if resume:
        from .plugin import require
        yade, _ = require("swelldem.scenario.run")
        state = os.path.join(test.out, recorder.STATE_FILE)
        yade.Omega().load(state)
        solver = yade.Omega().engines[-1]
        t0 -= float(res.get("wall_s") or 0.0)  # wall_s counts the sessions before
        done = rec.resume(solver)
        res.setdefault("resumed", []).append({"steps_done": done, "time": time.time()})
        print(f"swelldem: resumed from {state}: {done} of {solver.nSteps} physical steps done", flush=True)
    humidity = None
    if test.humidity:
        humidity = make_humidity(test, built, solver)
        if not resume:
            res["humidity"] = humidity_record(test, humidity)
        from .dem.humidity import save_history
        save_history(test.out, humidity)  # known before the run: the transport does not depend on the mechanics
        rec.particle_fields = lambda ids: [("h", np.float64, humidity.h_at(solver.physTime)[ids])]
        humidity.apply(max(1, int(solver.step)))  # the first step to run (after a resume: the coming one)
    hooks = [h for h in (rec, after_step, humidity) if h is not None]
    solver.stepHook = rec if len(hooks) == 1 else (lambda: [h() for h in hooks])
    handlers = _catch_stop_signals()
    try:
        # chunks of about a second: a stop signal is acted on between two of them
        dem_scene.run_to_end(solver, chunk=100, seconds=1.0)  # through the module, so that a benchmark can time it
        res["status"] = "finished"
    except Interrupted as e:
        res["status"] = f"interrupted: {e}"
        if solver.times and 0 < solver.step <= solver.nSteps:
            e.where = (f"during step {solver.step}/{solver.nSteps} (t = {solver.times[solver.step - 1]:.4g} to "
                       f"{solver.times[solver.step]:.4g} d), {solver.iterInStep} iterations into it, "
                       f"{solver.totalIterations} in all")
        res["wall_s"] = time.time() - t0
        report.write_results(test.out, res)
        raise
    except Exception as e:  # noqa: BLE001 - the message goes into the results, then up
        res["status"] = f"failed: {e}"
        report.write_results(test.out, res)
        if isinstance(e, (RuntimeError, ValueError)):  # the solver's stop (or a value it refused): a result, not a bug
            raise RunFailed(str(e), test.out) from e
        raise
    finally:
        res["wall_s"] = time.time() - t0
        for sig, handler in handlers.items():
            signal.signal(sig, handler)
    if len(gel):
        gel_pocket_forces(res["gel_pockets"], built)
    rec.export_vtk()
    if test.save_state:
        recorder.save_scene(os.path.join(test.out, recorder.FINAL_FILE))
        os.remove(os.path.join(test.out, recorder.STATE_FILE))  # the same scene as the final one
    report.write_results(test.out, res)
    report.write_all(test.out, res, assembly, recorder.broken_contacts(rec.bonded))
    return res
