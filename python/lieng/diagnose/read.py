"""Stage 1 of ``lieng diagnose``: a measured record as labs record it, read
and conditioned.

Two kinds of record are read (comma, semicolon, TAB or whitespace separated,
units in the header in brackets or the defaults below):

* **displacement records** ``t,x[,y][,v0]``: time (s), the dynamometer's
  spring extension x (mm: friction force over the tangential stiffness), an
  optional normal channel y (mm, any affine reading of the normal load) and
  the drive velocity v0 (mm/s);
* **force records** ``t,F[,N][,position|v0]`` with ``stiffness`` (N/m): the
  friction force read through the spring (N, mN, uN or kN), the normal force,
  the drive (stage) position (mm, um, m) or velocity; x = F / stiffness.
  Without the stiffness the diagnosis estimates it from the sticks (x rises
  at the drive velocity while the slider sticks) and says so.  A friction
  coefficient column (``mu``, ``COF``) stands for F: times the normal force
  column when there is one, else a force in units of the (constant) load,
  whose scale only the sticks can give.
* **rotary records** (a torsion spring turned by a motor: a rheometer's
  tribology cell, a clutch or bearing rig): a friction torque (N·m, N m,
  Nm, mN·m, N·mm, lbf·in, ...) with ``stiffness`` in N·m per the record's
  angle unit, or the spring's twist as an angle (deflection, twist: deg,
  rad, mrad), beside a motor's angle or angular speed (deg/s, rad/s, rpm);
  read as a linear record is, the angles in mrad where a linear record's
  lengths are in mm (``Record.length_unit``); a bare ``v0`` is in the
  record's angle unit per second (its twist's or drive's unit, else rad).

A spreadsheet workbook (``.xlsx``: its first worksheet) is read as such a
table, a MATLAB ``.mat`` or NumPy ``.npz`` file by its vectors' names.

Without a drive column the constant ``v0`` is used; a drive may be signed
and may reverse (reciprocating rigs: see :mod:`.segment`).  Uneven sampling
and gaps are resampled onto the median interval, spikes (isolated samples or
runs of up to three) replaced by the line between their neighbours, and a
mains-hum line (50 or 60 Hz and harmonics) that stands far above the spectrum
around it removed; each is said in
``Record.notes``.  A thesis-style TRC readings deck is accepted as well.
"""

from __future__ import annotations

import math
import re
import unicodedata
from dataclasses import dataclass, field

import numpy as np

from lieng.errors import LiengInputError
from lieng.io.table import read_table

__all__ = ["Record", "read_record", "record_from_trc_deck", "record_from_arrays", "check_fn", "MAX_SAMPLES"]

#: the longest record read (samples), about 2 GB of working memory at most
MAX_SAMPLES = 5_000_000
MIN_SAMPLES = 50

_NAMES = {
    "t": ("t", "time", "timestamp", "datetime", "date_time", "date", "zeit", "temps", "x_value", "tijd", "czas"),
    "x": ("x", "disp", "displacement", "extension", "ext", "spring", "deflection", "defl", "dx", "d_x",
          "lateral_deflection"),
    "y": ("y", "xn", "normal_disp", "normal_displacement", "dz", "d_z", "normal_deflection"),
    "v0": ("v0", "vd", "drive", "velocity", "speed", "drive_velocity", "geschwindigkeit"),
    "F": ("f", "friction", "force", "friction_force", "ft", "ff", "f_f", "fr", "fx", "tangential", "tangential_force",
          "ffric", "f_fric", "fric", "ffriction", "f_friction", "ftan", "f_tan", "ftang", "f_tang", "f_t", "fric_force",
          "lateral_force", "kraft", "reibkraft", "reibungskraft", "tangentialkraft", "tau", "stress", "shear_stress",
          "tau_s", "tob", "torque_on_bit"),
    "mu": ("mu", "µ", "μ", "cof", "coefficient_of_friction", "friction_coefficient", "fnorm", "mu_k"),
    "N": ("n", "normal", "load", "normal_force", "fnormal", "fn", "fz", "f_n", "f_z", "normal_load", "normalkraft",
          "sigma", "sigma_n", "normal_stress", "fnorm", "f_norm", "wob", "weight_on_bit", "w"),
    "position": ("position", "pos", "stage", "stage_position", "drive_position", "xdrive", "weg", "distance",
                 "sliding_distance", "travel", "xd", "x_d", "stroke", "s", "d", "u"),
}
#: time column names whose plain numbers between 20000 and 80000 are a spreadsheet's serial dates (days)
EXCEL_DAY_NAMES = ("date", "datetime", "date_time", "date/time", "timestamp", "time stamp", "date time")
#: (and the inch-based units of an American rig: in, mil = 0.001 in)
_LENGTH = {"": 1.0, "mm": 1.0, "um": 1e-3, "µm": 1e-3, "micron": 1e-3, "m": 1e3, "cm": 10.0, "nm": 1e-6,
           "in": 25.4, "inch": 25.4, "mil": 0.0254}
_VELOCITY = {"": 1.0, "mm/s": 1.0, "um/s": 1e-3, "µm/s": 1e-3, "m/s": 1e3, "cm/s": 10.0, "mm/min": 1 / 60,
             "mm/sec": 1.0, "um/sec": 1e-3, "µm/sec": 1e-3, "m/min": 1e3 / 60, "in/s": 25.4, "in/min": 25.4 / 60,
             "nm/s": 1e-6, "um/min": 1e-3 / 60, "µm/min": 1e-3 / 60}
_TIME = {"": 1.0, "s": 1.0, "sec": 1.0, "ms": 1e-3, "msec": 1e-3, "us": 1e-6, "µs": 1e-6, "usec": 1e-6,
         "min": 60.0, "h": 3600.0, "hr": 3600.0}
#: forces (N), also the gravitational units a balance or an old rig writes (gram-, kilogram-, pound-force)
_FORCE = {"": 1.0, "n": 1.0, "mn": 1e-3, "un": 1e-6, "µn": 1e-6, "nn": 1e-9, "kn": 1e3, "dan": 10.0, "gf": 9.80665e-3,
          "kgf": 9.80665, "kp": 9.80665, "lbf": 4.4482216152605, "lb": 4.4482216152605, "cn": 1e-2,
          "kg": 9.80665, "g": 9.80665e-3}
#: the force units that name nothing else (a mass's kg and g, a pound's lb, read as forces on a force column, also
#: stand for masses and an accelerometer's g): a column of no known name is taken for a force only in these
_FORCE_ONLY = frozenset(_FORCE) - {"", "kg", "g", "lb"}
#: stresses (Pa): a shear and a normal stress stand for the forces (a rock-mechanics biaxial rig)
_STRESS = {"pa": 1.0, "kpa": 1e3, "mpa": 1e6, "gpa": 1e9, "bar": 1e5, "psi": 6894.757}


@dataclass
class Record:
    """A record ready for the diagnosis, on an even time grid.

    Attributes
    ----------
    t : ndarray
        Time (s), evenly spaced.
    x : ndarray
        Spring extension (mm): the friction force over the tangential
        stiffness, signed as the force.
    vd : ndarray
        Drive velocity (mm/s), signed.
    y : ndarray or None
        The normal channel (a normal force, or an affine reading of it).
    y_is_force : bool
        y is the normal force itself (its relative change is the load's).
    drive_recorded : bool
        The drive came from a column (not a nominal ``--v0``).
    notes : list of str
        What was done to the data (resampling, spikes, hum).
    warnings : list of str
        What in the data may mislead the diagnosis (a sensor at its limit).
    hum_hz : tuple of float
        The mains hum lines removed from the channels (Hz): a line read
        there later is the hum's; one at a mains frequency elsewhere (a
        shaker's, a motor's) is read as any other.
    """

    t: np.ndarray
    x: np.ndarray
    vd: np.ndarray
    y: np.ndarray | None = None
    y_is_force: bool = False
    drive_recorded: bool = False
    source: str = "record"
    notes: list = field(default_factory=list)
    warnings: list = field(default_factory=list)
    fn_hint: float | None = None
    #: a force record read without --stiffness: x is the force (N) times
    #: 1000 until the diagnosis estimates the stiffness (N/m) from the sticks
    stiffness_unknown: bool = False
    stiffness: float | None = None
    #: the unit of that stiffness: N/m, Pa/m for a stress record, 1/m for
    #: a friction coefficient without a normal force
    stiffness_unit: str = "N/m"
    hum_hz: tuple = ()
    #: the drive's direction was read from the force's side
    #: (:func:`.segment.drive_from_force`): x already rises with it
    drive_from_force: bool = False
    #: the time constant (s) of the high-pass undone on x (:func:`undo_highpass`), None when x was read as recorded
    highpass: float | None = None
    #: x is an extension read from two positions on a drive that goes both ways, its zero set midway between
    #: the directions' levels (:func:`_zero_between_directions`): a direction asymmetry cannot be read
    zero_unknown: bool = False
    #: the unit of x (mm; mrad for a rotary record: a torque and angles, :func:`_rotary`)
    length_unit: str = "mm"

    @property
    def dt(self) -> float:
        return float(self.t[1] - self.t[0])


#: units written in Chinese or Japanese characters, as the tables below spell them
_CJK_UNITS = {"秒": "s", "毫秒": "ms", "分": "min", "牛顿": "n", "牛": "n", "毫牛": "mn", "千牛": "kn", "毫米": "mm",
              "微米": "um", "米": "m", "厘米": "cm", "毫米/秒": "mm/s", "毫米每秒": "mm/s"}


def _unit_key(unit: str) -> str:
    """A unit as the tables below spell it: lower case, no blanks, the micro
    sign for a Greek mu (U+03BC, as some loggers write it); a unit in
    Chinese or Japanese characters as its symbol (秒 s, 牛顿 N, 毫米 mm)."""
    u = unit.strip().lower().replace(" ", "").replace("\u03bc", "\u00b5")
    return _CJK_UNITS.get(u, u)


#: units as they are written, for the messages
_SHOWN = {"n": "N", "mn": "mN", "un": "uN", "µn": "µN", "nn": "nN", "kn": "kN", "dan": "daN", "kgf": "kgf", "kp": "kp", "lbf": "lbf", "gf": "gf", "pa": "Pa", "kpa": "kPa", "mpa": "MPa",
          "gpa": "GPa", "cn": "cN", "lb": "lb", "kg": "kg", "g": "g"}


def _fail(msg):
    raise LiengInputError(msg)


#: the drive velocities a rig can have (mm/s): 1 nm/s to 1 km/s
V0_RANGE = (1e-6, 1e6)


def _check_v0(v0, unit: str = "mm/s", to_range: float = 1.0) -> None:
    """``v0`` (in ``unit``) times ``to_range`` within V0_RANGE (mm/s; a
    rotary record's rad/s)."""
    if not (math.isfinite(v0) and V0_RANGE[0] <= abs(v0 * to_range) <= V0_RANGE[1]):
        _fail(f"--v0 {v0:g}: the drive velocity must be a number of magnitude {V0_RANGE[0] / to_range:g} to "
              f"{V0_RANGE[1] / to_range:g} {unit}")


#: words that give a column its role when its name is none of _NAMES
#: ("Tangential force", "Normal load", "Stage position", "Clamp force", "Torque arm force", "F_arm"), first
#: match wins (a normal word before a force's: "clamp_force" is the normal force)
_WORDS = (("mu", ("coefficient", "cof", "coeff", "coeficiente", "coefficiente", "reibwert", "reibungskoeffizient")),
          ("N", ("normal", "load", "normale", "clamp", "clamping", "carico", "carga", "normalkraft", "auflast",
                 "squeeze", "preload", "normaalkracht", "nacisku", "docisku")),
          ("F", ("friction", "tangential", "lateral", "shear", "traction", "tangentielle", "frottement", "torque",
                 "moment", "drehmoment", "couple", "par", "tension", "pull", "zugkraft",
                 "drag", "f", "force", "friccion", "rozamiento", "attrito", "atrito", "tangenziale", "reibung",
                 "reibkraft", "kraft", "fuerza", "forza", "forca", "wrijving", "wrijvingskracht", "kracht", "tarcia",
                 "sila", "sia")),
          ("position", ("position", "stage", "distance", "travel", "track", "encoder", "actuator", "crosshead",
                        "posicion", "posizione", "posicao", "weg", "stroke", "hub", "pos", "positie", "pozycja")),
          ("v0", ("velocity", "speed", "vitesse", "velocidad", "velocita", "velocidade", "geschwindigkeit",
                  "snelheid", "predkosc")),
          ("t", ("time", "temps", "tiempo", "tempo", "zeit", "tijd", "czas")),
          ("x", ("displacement", "extension", "deplacement", "deflection", "laser", "lds", "lvdt", "dvrt",
                 "capacitive", "eddy", "desplazamiento", "spostamento", "deslocamento", "verschiebung", "verplaatsing",
                 "przemieszczenie")))


#: the roles a column of a given unit's dimension can have
_FITS = (("position", _LENGTH), ("x", _LENGTH), ("y", _LENGTH), ("v0", _VELOCITY), ("t", _TIME), ("F", _FORCE),
         ("N", _FORCE), ("F", _STRESS), ("N", _STRESS))


#: Chinese and Japanese terms of a column name, as the English words they stand for (longest first: 摩擦系数 is a
#: coefficient, not a friction force; 垂直荷重 a normal load)
_CJK_WORDS = (("摩擦系数", "coefficient"), ("摩擦係数", "coefficient"), ("摩擦系數", "coefficient"),
              ("经过时间", "time"), ("経過時間", "time"), ("时间", "time"), ("時間", "time"), ("时刻", "time"),
              ("時刻", "time"), ("摩擦力", "friction"), ("垂直荷重", "normal"), ("法向力", "normal"),
              ("法向载荷", "normal"), ("正压力", "normal"), ("载荷", "load"), ("荷重", "load"), ("试验力", "force"),
              ("試験力", "force"), ("位移", "displacement"), ("変位", "displacement"), ("变位", "displacement"),
              ("ストローク", "stroke"), ("行程", "stroke"), ("速度", "speed"))


def _words(name: str) -> set:
    """A column name's words, lower case, with their accents taken off ("Déplacement", "Force normale"), and
    the English words of its Chinese or Japanese terms (:data:`_CJK_WORDS`)."""
    out = set(re.split(r"[^a-z0-9]+", unicodedata.normalize("NFKD", name.strip().lower())
                       .encode("ascii", "ignore").decode()))
    rest = name
    for term, word in _CJK_WORDS:
        if term in rest:
            out.add(word)
            rest = rest.replace(term, " ")
    return out


#: German compounds' first parts that make a force (-kraft) the normal one: a clamp's, a blank holder's, a
#: contact's, a support's
_GERMAN_NORMAL = ("normal", "klemm", "niederhalter", "anpress", "andruck", "auflage", "spann", "halte")


def _german_compounds(words: set) -> set:
    """A column name's words with the last part of a German compound added
    as a word of its own: a force (``Standardkraft``, ``Zugkraft``: the
    test machine's load cell, the pull) or a normal one (``Klemmkraft``,
    ``Niederhalterkraft``), a travel (``Traversenweg``: the crosshead's,
    the drive's position; ``Federweg``, the spring's, is its extension),
    a speed (``Traversengeschwindigkeit``)."""
    out = set(words)
    for w in words:
        if w.endswith("kraft") and len(w) > 5:
            out.add("normal" if w.startswith(_GERMAN_NORMAL) else "kraft")
        elif w.endswith("weg") and len(w) > 3:
            out.add("displacement" if w.startswith("feder") else "weg")
        elif w.endswith("geschwindigkeit") and len(w) > 15:
            out.add("geschwindigkeit")
        elif w.endswith("zeit") and len(w) > 4:
            out.add("zeit")                 # Prüfzeit, Messzeit: the test's clock
    return out


#: the words that make a tension the slack side's (a capstan's or a belt's load), not the tight side's
_SLACK_WORDS = {"tail", "back", "holdback", "slack", "input", "incoming", "entry", "t1", "pre", "hold"}


#: the words of a pressure column ("Apply pressure", "Anpressdruck", "Pression"): a pressure on a piston, a
#: bellows or a pad is the contact's normal load over an area
_PRESSURE_WORDS = {"pressure", "druck", "pression", "presion", "pressione", "pressao", "cisnienie"}


#: a multi-axis force sensor's tangential channels ("Fx", "Fy", "Fx_N", "Force X", "F_y [N]")
_AXIS = re.compile(r"^\s*f(?:orce)?[\s_]*\(?([xy])\)?(?:_[a-zµ]+)?\s*$", re.IGNORECASE)


def _sliding_axis(roles, tab, cols, units) -> str | None:
    """A multi-axis force sensor's friction (an ATI six-axis cell's ``Fx``
    and ``Fy`` beside ``Fz``, the normal load): the tangential channel that swings the more
    (2nd to 98th percentile), ``Fx`` unless ``Fy`` swings more, said.  A rig
    that slides along y puts its friction in ``Fy``, and ``Fx`` holds
    crosstalk and noise (a blind generator's records were read on ``Fx``, a
    drop a hundred times too small)."""
    # (only beside a normal channel on z, Fz: the other two axes are then both tangential; a rig whose y is its
    # normal axis writes Fy for the load)
    if "F" not in cols or "N" not in cols or not re.match(r"^\s*f(?:orce)?[\s_]*\(?z\)?(?:_[a-zµ]+)?\s*$",
                                                         cols["N"][0], re.IGNORECASE):
        return None
    m = _AXIS.match(cols["F"][0])
    if m is None:
        return None
    other = "y" if m.group(1).lower() == "x" else "x"
    cand = [(n, u) for n, role, u in roles if n != cols["F"][0] and (m2 := _AXIS.match(n)) is not None
            and m2.group(1).lower() == other and n in tab.columns]
    if len(cand) != 1:
        return None
    n, u = cand[0]
    a, b = np.asarray(cols["F"][1], float), np.asarray(tab.columns[n], float)
    if not (np.all(np.isfinite(b)) and units["F"].strip().lower() == u.strip().lower()):
        return None
    swing = lambda v: float(np.subtract(*np.percentile(v, [98, 2])))
    if not swing(b) > swing(a):
        return None
    note = (f"column {n} read as the friction: it swings {swing(b) / max(swing(a), 1e-300):.3g} times as far as "
            f"{cols['F'][0]} (a multi-axis sensor's tangential channels: the rig slides along its axis)")
    cols["F"], units["F"] = (n, b), u
    return note


def _is_pressure(name: str, unit: str = "") -> bool:
    """Whether a column is a pressure by its name (:data:`_PRESSURE_WORDS`,
    a German compound ending in ``druck``) and its unit (a pressure's, or
    none)."""
    w = _words(name.strip().lower().replace(" ", "_").replace("-", "_"))
    w |= {"druck" for x in w if x.endswith("druck")}
    return bool(w & _PRESSURE_WORDS) and (not unit.strip() or _is_stress(unit))


def _pressure_as_load(roles, tab, cols, units) -> str | None:
    """With no normal channel named, a record's one pressure column (a
    pneumatic or hydraulic apply pressure, in a pressure's unit or none) is
    read as the normal load's reading, and said; a column named for the
    load always comes first, and two pressures are left unread (which one
    presses?)."""
    if {"N", "y"} & cols.keys():
        return None
    taken = {c[0] for c in cols.values()}
    cand = [(n, u) for n, role, u in roles if role is None and n not in taken and _is_pressure(n, u)]
    if len(cand) != 1:
        return None
    n, u = cand[0]
    cols["N"], units["N"] = (n, tab.columns[n]), u
    return (f"column {n}{f' ({u})' if u.strip() else ''} read as the normal load's reading: a pressure on the "
            f"contact (an apply piston's, a bellows')")


#: one-letter names read by convention (W the load, s, d, u the travel): their unit must be of that role's
#: dimension, or the column has no role
_WEAK_NAMES = {"w": _FORCE, "s": _LENGTH, "d": _LENGTH, "u": _LENGTH}


def _weak_unit_misfits(key: str, u: str) -> bool:
    """Whether a one-letter conventional name's unit is not of its role's dimension (``s`` in seconds is the
    time, which the unit decides as before)."""
    return u not in _WEAK_NAMES[key] and not (key == "s" and u in _TIME)


def _role(name: str, unit: str = ""):
    """The column's role from its name; a unit that is a length, velocity,
    time or force rules out the roles of another dimension ("Load point
    displacement (um)" is the drive's position, not a normal load)."""
    key = name.strip().lower().replace(" ", "_").replace("-", "_")
    u = _unit_key(unit)
    if u in _ANGLE_UNITS:
        return None                      # an angle (a rotary encoder's, a disc's): no linear role
    fits = {r for r, table in _FITS if u in table} if u else None
    if u and torque_scale(unit) is not None:
        fits = {"F"}                     # a torque ("Nm" is not a nanometre): the friction of a rotary rig
    if fits is not None and not fits:
        fits = None                      # a unit of none of them: the name decides (and the unit's check fails)
    words = _german_compounds(_words(key))
    if words & {"strain", "dehnung"}:
        return None                      # a strain ('Tensile strain (Extension)', %): a testing machine's, no role
    if words & {"sequence", "seq", "counter", "index", "status"}:
        return None                      # a counter or a status word (an ATI sensor's 'F/T Sequence'): no role
    if "load" in words and words & {"friction", "tangential", "lateral", "shear", "traction"}:
        words = words - {"load"}             # "Tangential load", "Friction load": the friction force
    if {"load", "cell"} <= words:
        words = (words - {"load"}) | {"force"}    # a load cell is a force transducer: which force, the other words say
    if "tension" in words and words & _SLACK_WORDS:
        # a capstan's, a belt's or a yarn tester's slack-side tension (the tail's, the back tension, the input
        # tension) is what the wrap multiplies, its load; the tight side's (the spring's, the output's) the friction
        words = (words - {"tension"}) | {"normal"}
    if "squeeze" in words and words & {"film", "thickness", "gap", "h"}:
        words = words - {"squeeze"}          # a squeeze film's thickness is the lubricant's, not a load
    if {"load", "point"} <= words or "lp" in words:
        words = (words - {"load", "point", "lp"}) | {"position"}     # rock mechanics: the load point is the drive
    if key in _WEAK_NAMES and u and _weak_unit_misfits(key, u):
        return None                      # "w [rad/s]" is an angular speed, "u [V]" a raw channel: not W or u
    named = [role for role, alts in _NAMES.items() if key in alts] + \
            [role for role, alts in _WORDS if words & set(alts)]
    if "v" in words and words & _STAGE_WORDS:
        named.insert(0, "v0")            # "v_drive", "v_stage": the drive's velocity, not its position
    elif words & {"x", "pos", "p", "s"} and words & _STAGE_WORDS:
        named.insert(0, "position")      # "x_drive", "s_stage": the drive's position, not the extension
    if fits is not None and "position" in fits and words & _STAGE_WORDS and not set(named) & fits:
        named.insert(0, "position")      # "Drive [mm]": a length named for the drive is its position
    if fits is not None and "N" not in fits and "y" in fits:
        # a normal channel in a length ("Clamp gauge [mm]", "Normal LVDT [um]"): a reading of the load, y
        named = ["y" if r == "N" else r for r in named]
    # the first role the unit allows; else the one role of the unit's dimension when it has one (a velocity
    # is the drive's, a time the clock) and the name gave a role; else the first by name (whose unit check
    # then names the column)
    if named and fits is not None and not set(named) & fits and len(fits) == 1:
        return next(iter(fits))
    return next((r for r in named if fits is None or r in fits), named[0] if named else None)


#: the units and words of an angle column (a pin-on-disc's or a rotary stage's)
_ANGLE_WORDS = {"angle", "theta", "rotation", "revolution", "revolutions", "revs", "azimuth"}
#: a rotary record's angles in its internal unit, the milliradian (as a linear record's lengths are in mm: a
#: torque over a torsional stiffness in N·m/rad, times 1000, is the twist in mrad as a force over N/m is mm)
_ANGLE = {"rad": 1e3, "radian": 1e3, "radians": 1e3, "mrad": 1.0, "µrad": 1e-3, "urad": 1e-3,
          "deg": math.pi / 0.18, "degree": math.pi / 0.18, "degrees": math.pi / 0.18, "°": math.pi / 0.18,
          "arcmin": math.pi / 10.8, "arcsec": math.pi / 648.0, "rev": 2e3 * math.pi, "revolutions": 2e3 * math.pi,
          "turns": 2e3 * math.pi}
_ANGLE_UNITS = frozenset(_ANGLE)
#: angular velocities (mrad/s)
_ANGULAR_VELOCITY = {"rad/s": 1e3, "mrad/s": 1.0, "deg/s": math.pi / 0.18, "°/s": math.pi / 0.18,
                     "rpm": 2e3 * math.pi / 60, "1/min": 2e3 * math.pi / 60, "min-1": 2e3 * math.pi / 60,
                     "min^-1": 2e3 * math.pi / 60, "rev/min": 2e3 * math.pi / 60, "r/min": 2e3 * math.pi / 60,
                     "rev/s": 2e3 * math.pi, "rps": 2e3 * math.pi, "deg/min": math.pi / 10.8, "rad/min": 1e3 / 60}
#: torques (N·m): a force times a length, its N written in capitals ("Nm" is a newton metre, "nm" a nanometre)
_TORQUE_RE = re.compile(r"^\s*(?P<p>[mµμuk]?)N\s*[·*.⋅×x\- ]?\s*(?P<l>mm|cm|m)\s*$")
_TORQUE_OTHER = {"lbf·in": 0.1129848290, "lbfin": 0.1129848290, "in·lbf": 0.1129848290, "inlbf": 0.1129848290,
                 "lbf·ft": 1.3558179483, "lbfft": 1.3558179483, "ft·lbf": 1.3558179483, "ftlbf": 1.3558179483,
                 "ozf·in": 0.0070615518, "ozfin": 0.0070615518, "in·ozf": 0.0070615518, "kgf·m": 9.80665,
                 "kgfm": 9.80665, "kgf·cm": 0.0980665, "kgfcm": 0.0980665, "gf·cm": 9.80665e-5, "gfcm": 9.80665e-5}


def torque_scale(unit: str) -> float | None:
    """The factor from ``unit`` to N·m when it is a torque (N·m, N m, Nm,
    mN·m, µNm, N·mm, N·cm, kN·m, lbf·in, ozf·in, kgf·cm, ...), else None."""
    m = _TORQUE_RE.match(unit.replace("\u03bc", "\u00b5"))
    if m:
        pre = {"": 1.0, "m": 1e-3, "µ": 1e-6, "u": 1e-6, "k": 1e3}[m.group("p")]
        return pre * {"m": 1.0, "cm": 1e-2, "mm": 1e-3}[m.group("l")]
    key = re.sub(r"[\s*.⋅×\-]", "·", unit.strip().lower()).replace("··", "·")
    return _TORQUE_OTHER.get(key, _TORQUE_OTHER.get(key.replace("·", "")))


def _is_angle(name: str, unit: str = "") -> bool:
    """Whether a column (of no role) is an angle, by its unit or its name."""
    words = set(re.split(r"[^a-z0-9]+", name.strip().lower()))
    return unit.strip().lower() in _ANGLE_UNITS or bool(words & _ANGLE_WORDS)


#: words that name the slider's own position and the drive's (stage's) position
_SLIDER_WORDS = {"slider", "pin", "mass", "block", "carriage", "specimen", "sample", "rider", "body", "puck", "sled"}
_STAGE_WORDS = {"stage", "drive", "table", "motor", "belt", "actuator", "encoder", "driver", "puller", "cart",
                "trolley", "winch", "pulled", "crosshead"}


def _is_slider(name: str) -> bool:
    """Whether a column's name says it is the slider's own position (its
    words name the slider and not the stage)."""
    words = set(re.split(r"[^a-z0-9]+", name.strip().lower()))
    return bool(words & _SLIDER_WORDS) and not words & _STAGE_WORDS


#: a position column's unit that is a video's pixel (its scale among the metadata: :attr:`.io.table.Table.stated_scale`)
_PIXEL = ("px", "pix", "pixel", "pixels")


#: a lone position written without its unit (a video tracker's, calibrated in m or cm): the unit its travel
#: over the record says against --v0 (the slider keeps up with the drive on average), when within this factor
UNIT_FROM_TRAVEL = 1.3
_TRAVEL_UNITS = {"mm": 1.0, "cm": 10.0, "m": 1e3, "in": 25.4, "um": 1e-3}


def _unit_from_travel(path, name: str, x, cols, units, v0: float, notes: list) -> float | None:
    """A lone position column without a unit beside --v0: the factor to mm of the length unit (mm, cm, m,
    in, um) whose travel over the record matches the drive's at --v0 within UNIT_FROM_TRAVEL (a slider
    keeps up with its drive on average), said in ``notes``; None when none does (an extension, which rises
    and falls about a level, travels nowhere) or the time is unknown."""
    if "t" not in cols:
        return None
    try:
        tv = cols["t"][1] * _scale(path, cols["t"][0], units["t"], _TIME, "time")
    except LiengInputError:
        return None
    travel = abs(float(x[-1] - x[0]))
    want = abs(v0) * float(tv[-1] - tv[0])
    if not (travel > 0 and want > 0):
        return None
    # a position follows the drive all along (its slope on the drive's travel near 1 in size, little about
    # the line): an extension that merely ends higher than it starts does not
    drive = abs(v0) * (tv - tv[0])
    if not (np.all(np.isfinite(drive)) and np.all(np.isfinite(x)) and float(np.ptp(drive)) > 0):
        return None
    try:
        slope, icpt = np.polyfit(drive, x, 1)
    except (np.linalg.LinAlgError, ValueError):
        return None
    if not float(np.std(x - (icpt + slope * drive))) <= 0.5 * abs(slope) * float(np.std(drive)):
        return None
    for unit, k in _TRAVEL_UNITS.items():
        if 1.0 / UNIT_FROM_TRAVEL <= k * travel / want <= UNIT_FROM_TRAVEL and \
                1.0 / UNIT_FROM_TRAVEL <= k * abs(float(slope)) <= UNIT_FROM_TRAVEL:
            if k != 1.0:
                notes.append(f"column {name} has no unit: its travel over the record, against --v0 "
                             f"{v0:g} mm/s, says {unit}: read in {unit}")
            return k
    return None


def _position_scale(path, name: str, unit: str, tab) -> float:
    """A position column's factor to mm: its length unit's, or a pixel's at the scale the metadata states
    (refused, naming the column, without one)."""
    if unit in _PIXEL:
        if tab.stated_scale is None:
            _fail(f"{path}: column {name}: in pixels, and no line above the header states the scale (mm per "
                  f"pixel): convert the column to mm, or add a line such as '# scale: 0.25 mm/px'")
        return tab.stated_scale[0]
    return _scale(path, name, unit, _LENGTH, "position")


def _position_unit(name: str, unit: str) -> str | None:
    """A position column's length unit: the header's, or a name's last part ("block_x_mm", "cart_x_px");
    "" for none written; None when the column is not a length (or a pixel)."""
    u = _unit_key(unit)
    if not u and "_" in name:
        u = _unit_key(name.rsplit("_", 1)[1])
        u = u if u in _LENGTH or u in _PIXEL else ""
    return u if u in _LENGTH or u in _PIXEL else None


def _maybe_position(name: str, unit: str) -> bool:
    """Whether a column of no role may be a position along the track (read beside another:
    :func:`_slider_and_stage`): a length or a pixel, named for the slider, the stage or an x coordinate (a
    video tracker's "mass A x"), not a vertical one ("mass A y")."""
    if _position_unit(name, unit) is None:
        return False
    words = _words(name)
    return bool(words & (_SLIDER_WORDS | _STAGE_WORDS | {"x", "pos", "position"})) and "y" not in words


def _still_beside(a, b) -> tuple:
    """How often each of two positions stands still while the other moves: (the share of windows in which
    ``a`` moves under a tenth of ``b``'s move, and ``b`` under a tenth of ``a``'s), over windows in which the
    two move ten of their smallest steps at the median (a video tracker's pixels).  A slider that sticks
    stands still through its sticks while the drive runs on; the drive never stands while the slider slips
    (a slip is a few times faster than the drive, not ten)."""
    n = a.size
    if n < 50:
        return 0.0, 0.0
    steps = [np.abs(np.diff(v)) for v in (a, b)]
    nz = [d[d > 0] for d in steps]
    if not all(z.size for z in nz):
        return 0.0, 0.0
    q = max(float(np.percentile(z, 10)) for z in nz)
    k = 1
    while k < max(n // 20, 1):
        big = np.maximum(np.abs(a[k:] - a[:-k]), np.abs(b[k:] - b[:-k]))
        if float(np.median(big)) >= 10.0 * q:
            break
        k = 2 * k
    da, db = np.abs(a[k:] - a[:-k]), np.abs(b[k:] - b[:-k])
    return float(np.mean(da < 0.1 * db)), float(np.mean(db < 0.1 * da))


#: of two position columns named alike (a video tracker's "mass A x", "mass B x"), the slider's stands still
#: while the other moves in at least this share of the windows, and the drive's in at most a third as many
#: (:func:`_still_beside`)
SLIDER_STILL_SHARE = 0.1


def _slider_and_stage(roles, tab=None):
    """((name, unit) of the slider's position, (name, unit) of the stage's)
    when the header's columns ``roles`` ((name, role, unit) each) have
    exactly one of each among their position columns (lengths, a name's
    last part as the unit, or pixels), else None.  Two position columns
    whose names do not tell them apart (a video tracker's "mass A x" and
    "mass B x"; vertical coordinates, "y", are not positions along the
    track) are told apart by their motion when ``tab`` is given
    (:data:`SLIDER_STILL_SHARE`)."""
    sl, dr, other = [], [], []
    for n, role, u2 in roles:
        unit = _position_unit(n, u2)
        if role not in ("position", "x", None) or unit is None or (role is None and not _maybe_position(n, u2)):
            continue
        words = set(re.split(r"[^a-z0-9]+", n.strip().lower()))
        if _is_slider(n) and not words & {"a", "b", "1", "2"}:
            sl.append((n, unit))
        elif words & _STAGE_WORDS and not words & _SLIDER_WORDS:
            dr.append((n, unit))
        else:
            other.append((n, unit))
    if len(sl) == 1 and len(dr) == 1:
        return sl[0], dr[0]
    both = sl + dr + other
    if tab is None or len(both) != 2:
        return None
    share = _still_beside(*(np.asarray(tab.columns[n], float) for n, _ in both))
    j = int(np.argmax(share))
    if share[j] >= SLIDER_STILL_SHARE and share[1 - j] <= share[j] / 3.0:
        return both[j], both[1 - j]
    return None


#: words that name a rotary rig's twist (the torsion spring's extension) and its drive
_TWIST_WORDS = {"deflection", "twist", "extension", "spring", "torsion", "displacement", "deformation", "windup",
                "wind", "coupling", "delta", "relative"}
_ROTOR_WORDS = _STAGE_WORDS | {"input", "rotor", "spindle", "shaft", "angle", "position", "rotation", "speed",
                               "velocity", "omega", "td", "topdrive"}
#: an angular speed named for what the spring turns (a drill string's bit, a lower disc), not for the drive
#: (unless named for the drive too: _DRIVING_WORDS)
_TURNED_WORDS = {"bit", "lower", "slider", "output", "follower"}
_DRIVING_WORDS = _STAGE_WORDS | {"top", "td", "topdrive", "input", "upper"}


#: stiffnesses (N/m)
_STIFFNESS = {"n/m": 1.0, "n/mm": 1e3, "kn/m": 1e3, "kn/mm": 1e6, "n/um": 1e6, "n/µm": 1e6, "mn/mm": 1.0,
              "mn/m": 1e-3, "n/cm": 1e2, "lbf/in": 175.1268352}


def _with_units(stiffness, v0, rotary, notes):
    """--stiffness and --v0 given with their units ((number, unit)) as the
    bare numbers the record's kind takes (N/m and mm/s; a rotary record's
    N·m and its angle unit per second), each said in ``notes``; a unit of
    the other kind (an angular speed for a linear record) refused, naming
    the option."""
    ru = rotary["unit"] if rotary else None
    if isinstance(stiffness, tuple):
        val, unit = stiffness
        num, _, den = unit.rpartition("/")
        k = _STIFFNESS.get(_unit_key(unit)) if not rotary else None
        if k is None and not rotary and _unit_key(num) in _FORCE and _unit_key(den) in _LENGTH and num and den:
            k = _FORCE[_unit_key(num)] / (1e-3 * _LENGTH[_unit_key(den)])   # any force over any length: gf/mm
        if rotary and torque_scale(num) is not None and _unit_key(den) in _ANGLE:
            k = torque_scale(num) * _ANGLE[ru] / _ANGLE[_unit_key(den)]
        if k is None:
            _fail(f"--stiffness {val:g} {unit}: " + (f"a rotary record's stiffness is a torque per angle (N·m/rad, "
                                                       f"mN·m/deg)" if rotary else
                                                       f"unit not understood for a linear stiffness (a force "
                                                       f"over a length: N/m, N/mm, kN/m, N/um, gf/mm, lbf/in)"))
        notes.append(f"--stiffness {val:g} {unit}: {val * k:.6g} " + (f"N·m/{ru}" if rotary else "N/m"))
        stiffness = val * k
    if isinstance(v0, tuple):
        val, unit = v0
        key = _speed_key(unit)
        if rotary and key in _ANGULAR_VELOCITY:
            f = _ANGULAR_VELOCITY[key] / _ANGLE[ru]
        elif not rotary and _unit_key(unit) in _VELOCITY:
            f = _VELOCITY[_unit_key(unit)]
        else:
            _fail(f"--v0 {val:g} {unit}: " + ("a rotary record's drive is an angular speed (rad/s, deg/s, rpm)"
                                               if rotary else "unit not understood for a linear drive (mm/s, um/s, "
                                                              "m/s, mm/min)"))
        notes.append(f"--v0 {val:g} {unit}: {val * f:.6g} " + (f"{ru}/s" if rotary else "mm/s"))
        v0 = val * f
    return stiffness, v0


def _speed_key(unit: str) -> str:
    """An angular speed's unit as :data:`_ANGULAR_VELOCITY` spells it (a degree sign as deg: "°/min")."""
    k = _unit_key(unit)
    return k if k in _ANGULAR_VELOCITY else k.replace("°", "deg")


def _rotational(unit: str) -> bool:
    """Whether ``unit`` is an angle's or an angular speed's (a rotary record's column)."""
    return _unit_key(unit) in _ANGLE or _speed_key(unit) in _ANGULAR_VELOCITY


def _rotary(path, roles, tab, cols, units):
    """A rotary rig's record (a torsion spring turned by a motor, a clutch,
    a disc in a bearing: a friction torque and angles): its columns read
    into ``cols``/``units`` as a linear record's are, the torque in N·m (as
    N), the angles in mrad (as mm), the angular speeds in mrad/s (as mm/s);
    returns {"unit": the record's angle unit, "note": ...}, or None when
    the record is not rotary (no torque, and no angle named as the spring's
    twist).  An angle named as the twist (deflection, twist, spring) is the
    extension x; one named for the motor or the drive (or an angle of no
    such name beside them) the drive's angle; an angular speed the drive's
    velocity.  The record's angle unit (the twist's, else the drive's, else
    rad) is the one a bare --stiffness (N·m per it) and --v0 (it per
    second) are read in."""
    angles, speeds = [], []
    for (n, role, u), u0 in zip(roles, tab.units):
        u = u or u0
        if _unit_key(u) in _ANGLE:
            angles.append((n, u))
        elif _speed_key(u) in _ANGULAR_VELOCITY:
            speeds.append((n, u))
    torque = "F" in cols and torque_scale(units["F"]) is not None
    twist = [(n, u) for n, u in angles if _words(n) & _TWIST_WORDS and not _words(n) & (_STAGE_WORDS | {"input"})]
    # an angle named for a deflection that turns one way only is the drive's (a rheometer's 'Deflection Angle',
    # 'Displacement (rad)': the measuring system's rotation); a spring's twist rises and falls every cycle
    along = [(n, u) for n, u in twist if _one_way(tab.columns[n])]
    twist = [q for q in twist if q not in along]
    if not torque and not ("x" not in cols and "F" not in cols and twist):
        return None
    used = []
    if torque and "N" not in cols:
        # a rheometer's 'Axial force' (along the shaft) beside the torque: the normal force
        axial = [(n, u) for n, role, u in roles if role == "F" and "axial" in _words(n) and n != cols["F"][0]
                 and _unit_key(u or "") in _FORCE]
        if axial:
            n, u = axial[0]
            cols["N"], units["N"] = (n, tab.columns[n]), u
            used.append(f"{n} ({u}) as the normal force")
    if torque:
        name, vals = cols["F"]
        used.append(f"{name} ({units['F']}) as the friction torque")
        cols["F"], units["F"] = (name, vals * torque_scale(units["F"])), "N"
    if twist:
        name, u = twist[0]
        cols["x"], units["x"] = (name, tab.columns[name] * _ANGLE[_unit_key(u)]), "mm"
        used.append(f"{name} ({u}) as the torsion spring's twist")
    drive = [(n, u) for n, u in angles if (n, u) not in twist[:1] and (_words(n) & _ROTOR_WORDS or (n, u) in along)]
    turned = [(n, u) for n, u in speeds if _words(n) & _TURNED_WORDS and not _words(n) & _DRIVING_WORDS]
    if turned:
        # the speed of what the spring turns (a bit's, a lower disc's): the slider's, not the drive's
        speeds = [q for q in speeds if q not in turned]
        if "v0" in cols and cols["v0"][0] in [n for n, _ in turned]:
            cols.pop("v0"), units.pop("v0", None)
        used.append(f"{', '.join(n for n, _ in turned)} not read (the speed of what the spring turns, not the "
                    f"drive's)")
    if speeds:
        n, u = speeds[0]
        cols["v0"], units["v0"] = (n, tab.columns[n] * _ANGULAR_VELOCITY[_speed_key(u)]), "mm/s"
        cols.pop("position", None), units.pop("position", None)
        used.append(f"{n} ({u}) as the drive's angular speed")
    elif drive:
        n, u = drive[0]
        cols["position"], units["position"] = (n, tab.columns[n] * _ANGLE[_unit_key(u)]), "mm"
        cols.pop("v0", None), units.pop("v0", None)
        used.append(f"{n} ({u}) as the drive's angle")
    first = twist[:1] or drive[:1] or speeds[:1]
    unit = _unit_key(first[0][1]).replace("°", "deg").split("/")[0] if first else "rad"
    unit = {"radian": "rad", "radians": "rad", "degree": "deg", "degrees": "deg", "°": "deg",
            "revolutions": "rev", "turns": "rev"}.get(unit, unit)
    if unit not in _ANGLE:
        # a speed's unit that names no angle (rpm, 1/min, rps): the angle it counts, the revolution
        unit = "rev"
    note = (f"a rotary record: {', '.join(used)}; its angles in mrad (x is the twist), its torques in N·m; "
            f"a --stiffness is read in N·m/{unit} and a --v0 in {unit}/s (the record's angle unit)")
    return {"unit": unit, "note": note}


def _suffix_fits(role, suffix: str) -> bool:
    """Whether a name's last part ``suffix`` is a unit of the role the rest
    of the name has: a length, velocity, time, force or stress of its role,
    or a rotary rig's (an angle, of no role; an angular speed, the drive's;
    a torque, the friction's)."""
    u = _unit_key(suffix)
    if role is None:
        return u in _ANGLE_UNITS
    if (role == "v0" and u in _ANGULAR_VELOCITY) or (role == "F" and torque_scale(suffix) is not None):
        return True
    return any(r == role and u in units_of for r, units_of in _FITS)


def _column_role(name: str, unit: str = ""):
    """(role, unit) of a header cell: :func:`_role`, or with the unit as the
    name's last part ("time_ms", "force_mN", a velocity's two: "speed_um_s",
    "speed_mm_per_s"; a rotary rig's: "angle_deg", "speed_rpm", "speed_deg_s",
    "torque_Nm") when the rest names a role (the last part is read as the
    unit before the whole name is: "Time_ms" is a time in ms, not in s)."""
    key = name.strip().lower().replace(" ", "_").replace("-", "_")
    if not unit and "_" in name and not any(key in alts for alts in _NAMES.values()):   # ("tau_s" is a name)
        parts = name.split("_")
        if len(parts) >= 4 and parts[-2].lower() == "per":
            parts = parts[:-2] + parts[-1:]          # "mm_per_s": a velocity's two parts
        for k in (2, 1):
            if len(parts) <= k:
                continue
            suffix = "/".join(parts[-k:])
            role = _role("_".join(parts[:-k]), suffix)
            if _suffix_fits(role, suffix):
                return role, suffix
    role = _role(name, unit)
    if role is None and not unit and "_" in name:
        stem, suffix = name.rsplit("_", 1)
        if suffix and any(suffix.lower() in units_of for units_of in (_LENGTH, _VELOCITY, _TIME, _FORCE, _STRESS)):
            role, unit = _role(stem, suffix), suffix
    return role, unit


def _kind(name: str, unit: str = ""):
    """What a header cell is read as: its role (:func:`_column_role`),
    "angular" for a rotary rig's angle or angular speed, or None for a
    column not read (a temperature, a comment)."""
    role, u = _column_role(name, unit)
    return role if role is not None else ("angular" if _rotational(u or unit) else None)


def _scale(path, name, unit, table, what):
    u = _unit_key(unit)
    if u not in table:
        _fail(f"{path}: column {name}: unit {unit!r} not understood for a {what} "
              f"(use {', '.join(_SHOWN.get(k, k) for k in table if k)})")
    return table[u]


def _is_stress(unit: str) -> bool:
    return _unit_key(unit) in _STRESS


def _force(path, cols, units, role):
    """Column ``role`` (F or N) as recorded: a force (N) or a stress (Pa)."""
    (name, values), unit = cols[role], units[role]
    if _is_stress(unit):
        return values * _STRESS[_unit_key(unit)]
    return values * _scale(path, name, unit, _FORCE, "force (or a stress: Pa, kPa, MPa)")


def _friction_from_mu(path, cols, units, stiffness, normal_load=None) -> str:
    """A friction coefficient column (mu, COF) as the friction force: mu N
    with a normal force column, or times the constant ``normal_load`` (N)
    the user gives (a dead weight's); without either, mu itself, a force in
    units of the (constant) normal load, whose scale the sticks give (the
    stiffness read from them is then k / N, in 1/m)."""
    name, mu = cols["mu"]
    if units["mu"].strip() not in ("", "-", "1"):
        _fail(f"{path}: column {name}: unit {units['mu']!r}: a friction coefficient has none")
    if "N" in cols:
        if normal_load is not None:
            _fail(f"--normal-load: {path} records the normal force (column {cols['N'][0]}): leave --normal-load out")
        cols["F"], units["F"] = (f"{name} x {cols['N'][0]}", mu * _force(path, cols, units, "N")), \
            "Pa" if _is_stress(units["N"]) else "N"
        return f"friction force = column {name} (a friction coefficient) x column {cols['N'][0]}"
    elif normal_load is not None:
        cols["F"], units["F"] = (f"{name} x {normal_load:g} N", mu * normal_load), "N"
        return f"friction force = column {name} (a friction coefficient) x --normal-load {normal_load:g} N"
    elif stiffness is not None:
        _fail(f"{path}: column {name} is a friction coefficient and there is no normal force column: the force "
              f"--stiffness {stiffness:g} N/m would act on is unknown; give the normal load with --normal-load "
              f"(N), add the normal force column, or leave out --stiffness (the scale of mu is then read from the "
              f"sticks)")
    else:
        cols["F"], units["F"] = (name, mu), "N"
        return (f"column {name} is a friction coefficient and no normal force is recorded: read as a force in units "
                f"of the normal load (constant), so the stiffness read from the sticks is k / N (1/m)")


def _smooth_derivative(y, dt, win):
    from scipy.signal import savgol_filter

    win = max(5, int(win) | 1)
    if win >= y.size:
        win = (y.size - 1) | 1
        if win < 5:
            return np.gradient(y, dt)
    return savgol_filter(y, win, 2, deriv=1, delta=dt)


#: a position column that advances by less than its own resolution per sample is differentiated over
#: this many of its steps (an encoder's counts: over 0.02 s its derivative is a train of pulses)
QUANT_STEPS = 8


#: a step of the position column this many times the fast end of its moves (the 90th percentile of its
#: steps that move), over at most JUMP_RUN samples, is no travel: a stage moves no faster than its drive
JUMP_FACTOR = 100.0
JUMP_RUN = 5


def _position_jumps(pos, notes):
    """The position column with its jumps taken out (JUMP_FACTOR, JUMP_RUN:
    a re-zeroed or wrapped encoder, a re-homed stage's counter, a spike),
    the travel going on through each at its pace beside it, and said; as it
    is when it has none."""
    d = np.diff(pos)
    ad = np.abs(d)
    moving = ad[ad > 0]
    if moving.size < 20:
        return pos
    big = ad > JUMP_FACTOR * float(np.percentile(moving, 90))
    if not np.any(big):
        return pos
    edges = np.flatnonzero(np.diff(np.r_[0, big.astype(int), 0]))
    runs = [(a, b) for a, b in zip(edges[::2], edges[1::2]) if b - a <= JUMP_RUN]
    if not runs:
        return pos
    size = max(abs(float(np.sum(d[a:b]))) for a, b in runs)
    d = d.copy()
    for a, b in runs:
        # (the travel goes on through the jump at its pace beside it)
        near = np.r_[d[max(a - 10, 0):a], d[b:b + 10]]
        near = near[~big[np.r_[max(a - 10, 0):a, b:min(b + 10, d.size)]]]
        d[a:b] = float(np.median(near)) if near.size else 0.0
    notes.append(f"the position column jumps {len(runs)} time{'s' if len(runs) > 1 else ''} (by up to {size:.4g} mm "
                 f"within {JUMP_RUN} samples, {JUMP_FACTOR:g} times faster than it moves otherwise): a re-zeroed or "
                 f"wrapped encoder, not the stage's travel; taken out")
    return np.r_[pos[0], pos[0] + np.cumsum(d)]


def _drive_from_position(pos, dt, notes):
    """The drive velocity (mm/s) from a position column (mm): its smoothed
    derivative over 0.02 s, or, where the position is quantised more
    coarsely, or is noisier, than it moves in a sample (its smallest step,
    or its white noise, larger than its typical travel per sample while it
    moves), over QUANT_STEPS of those steps (at most a twentieth of the
    record): a derivative over 0.02 s of an LVDT noisier than its travel
    there changes sign sample by sample and cuts a one-way drive into
    hundreds of "strokes"."""
    win = 0.02 / dt
    d = np.abs(np.diff(pos))
    nz = d[d > 0]
    m = 200
    if nz.size >= 10 and pos.size >= 4 * m:
        q = float(np.percentile(nz, 5))
        noise = noise_level(pos)
        # (its travel while it moves: blocks that travel beyond five times what the noise makes of a block's
        # travel; a slide-hold-slide record stands still most of the time)
        travel = np.abs(pos[m::m] - pos[:-m:m]) / m
        travel = travel[travel > 5.0 * noise * math.sqrt(2.0) / m]
        per_sample = float(np.median(travel)) if travel.size else 0.0
        what, step = (("noise", noise) if noise > q else ("steps", q))
        if 0 < per_sample < step:
            w = min(QUANT_STEPS * step / per_sample, pos.size / 20)
            if w > win:
                win = w
                notes.append((f"the position column moves in steps of {q:.3g} mm, more than it travels in a sample "
                              if what == "steps" else
                              f"the position column's noise ({noise:.3g} mm) is more than it travels in a sample ")
                             + f"({per_sample:.3g} mm): the drive velocity is its derivative over {win * dt:.3g} s "
                               f"({QUANT_STEPS} {'steps' if what == 'steps' else 'times the noise'})")
    return _smooth_derivative(pos, dt, win)


def read_record(path, v0: float | None = None, stiffness: float | None = None, rate: float | None = None,
                highpass: float | None = None, names=None, normal_load=None, run=None) -> Record:
    """Read a displacement or force record (see the module docstring).

    Parameters
    ----------
    path : str or path-like
        The table.
    v0 : float or (float, str), optional
        The drive velocity (mm/s) when the record has no drive column; may be
        negative (a drive in the negative direction).  A rotary record's in
        its angle unit per second (rad/s when it has no angle column).  Or
        a number and its unit, ``(0.5, "um/s")``, ``(6.0, "deg/s")``.
    stiffness : float or (float, str), optional
        Tangential stiffness (N/m): needed for a force record.  A rotary
        record's torsional stiffness in N·m per its angle unit.  Or a
        number and its unit, ``(2.5, "N/mm")``, ``(0.05, "N·m/rad")``.
    rate : float, optional
        Sampling rate (Hz) of a table without a time column (its rows are
        evenly spaced samples); ignored, and said, when there is one.
    highpass : float, optional
        The time constant (s) of a first-order high-pass the friction
        channel went through (an AC-coupled sensor: a piezoelectric force
        cell's charge amplifier), undone (:func:`undo_highpass`).
    names : sequence of str, optional
        The columns' names with their units, in order (``["t [s]",
        "F [N]", "N [N]"]``): they replace the file's header (a
        data-acquisition program's ``Dev1/ai0``) or head a file that has
        none; a ``.mat`` or ``.npz`` file's one matrix is read column by
        column under them (:func:`lieng.io.table.read_table`).
    normal_load : float or (float, str), optional
        The constant normal load (N; or a number and its force unit,
        ``(30.1, "gf")``) of a record whose friction is a coefficient (mu,
        COF) without a normal-force column (a dead weight's): the friction
        force is mu times it.  Refused beside a normal-force column; said
        and not used on a record of a force or an extension.
    run : str or int, optional
        The run to read from a logger's export of several runs side by
        side (PASCO Capstone's ``Time (s) Run #2``, Vernier's ``Run 2: Time
        (s)``): ``2`` or ``"latest"`` (:func:`lieng.io.table.read_table`).

    Returns
    -------
    Record

    Raises
    ------
    LiengInputError
        Naming the line and column, or the option, of bad input.
    """
    _check_highpass(highpass)
    # (a column of no role, a temperature or a comment, is not read: neither a word nor a gap in it matters)
    tab = read_table(path, "t,x[,y][,v0] (s, mm, mm, mm/s) or t,F[,N][,position|v0] with --stiffness",
                     missing="drop", unused=lambda name, unit: _kind(name, unit) is None and
                     not _maybe_position(name, unit) and not (unit.strip() and _unit_key(unit) in _FORCE_ONLY)
                     and not _is_pressure(name, unit) and not _AXIS.match(name),
                     sparse=lambda name, unit: _kind(name, unit) in ("position", "v0", "y", "N", "angular")
                     or _is_pressure(name, unit),
                     names=names, run=run)
    roles = [(name, *_column_role(name, unit)) for name, unit in zip(tab.names, tab.units)]   # (name, role, unit)
    cols, units = {}, {}
    for name, role, unit in roles:
        if role and tab.names.count(name) > 1:
            where = [str(i + 1) for i, m in enumerate(tab.names) if m == name]
            _fail(f"{path}: header: columns {' and '.join(where)} are both named {name!r}: rename one (which is "
                  f"the {role} channel?)")
        if role and role not in cols:
            cols[role], units[role] = (name, tab.columns[name]), unit
    pair_note = _friction_among_normals(roles, tab, cols, units)
    if "mu" in cols and {"F", "x"} & cols.keys() and "N" not in cols and \
            cols["mu"][0].strip().lower().replace(" ", "_") in _NAMES["N"]:
        # "Fnorm" unitless reads as a coefficient (F normalised), but beside the friction force it is the
        # normal force (the coefficient would be the one over the other)
        cols["N"], units["N"] = cols.pop("mu"), units.pop("mu")
        pair_note = (f"column {cols['N'][0]} beside the friction force {(cols.get('F') or cols['x'])[0]}: read as "
                     f"the normal force")
    pull_note = None
    press_note = _pressure_as_load(roles, tab, cols, units)
    axis_note = _sliding_axis(roles, tab, cols, units)
    if "N" in cols and not {"F", "mu"} & cols.keys() and cols["N"][0].strip().lower() == "load" and \
            ("x" not in cols or _one_way(cols["x"][1])):
        # a universal testing machine's friction test (ASTM D1894, ISO 8295: a sled pulled over a plane by the
        # crosshead): its one force, 'Load', is the pull that drags the slider, and its 'Extension' the
        # crosshead's travel (read as the drive's below)
        cols["F"], units["F"] = cols.pop("N"), units.pop("N")
        pull_note = (f"column {cols['F'][0]} is the record's only force and nothing presses in it (a testing "
                     f"machine's pull test): read as the friction force that drags the slider")
    # a slider's position beside the stage's (a laser on the slider, an encoder on the stage) and no force or
    # extension: the spring's extension is their difference
    pair = _slider_and_stage(roles, tab) if "x" not in cols and "F" not in cols else None
    notes_pair = None
    if pair is not None:
        (sn, su), (dn, du) = pair
        ks, kd = _position_scale(path, sn, su, tab), _position_scale(path, dn, du, tab)
        scale_note = ""
        if su in _PIXEL or du in _PIXEL:
            scale_note = (f" (in pixels, at the {tab.stated_scale[0]:.4g} mm per pixel that line {tab.stated_scale[1]} "
                          f"states)")
        elif not su and not du:
            scale_note = " (no unit written: read as mm; the evidence is in units of the drop and does not depend on it)"
        ext = tab.columns[dn] * kd - tab.columns[sn] * ks
        cols["x"], units["x"] = (f"{dn} - {sn}", ext), "mm"
        cols["position"], units["position"] = (dn, tab.columns[dn] * kd), "mm"
        how = "" if (_is_slider(sn) and _words(dn) & _STAGE_WORDS) else " (told apart by their motion: the slider's " \
            "stands still through its sticks, the stage's runs on)"
        notes_pair = (f"columns {sn} and {dn}: the slider's and the stage's positions{how}; the spring's extension "
                      f"x is the stage's less the slider's{scale_note}")
    slider_note = None
    if "x" in cols and "F" in cols and _is_slider(cols["x"][0]):
        # a force beside the slider's own position (an LVDT or laser on the slider): the force is the
        # spring's, the position is not its extension
        slider_note = (f"column {cols['x'][0]} is the slider's position, not the spring's extension: not read "
                       f"(the friction force {cols['F'][0]} is)")
        cols.pop("x"), units.pop("x")
    rotary = _rotary(path, roles, tab, cols, units)
    given = []
    stiffness, v0 = _with_units(stiffness, v0, rotary, given)
    # a rotating drive's angle (a pin-on-disc's): not a linear drive, and its radius is not in the record
    angle = None if rotary else \
        next((n for (n, role, _), u in zip(roles, tab.units) if role is None and _is_angle(n, u)), None)
    drive_note = None
    if "x" in cols and "F" in cols and "position" not in cols and "v0" not in cols and _one_way(cols["x"][1]):
        # a displacement beside a force that only goes one way is the stage's travel, not the spring's extension
        cols["position"], units["position"] = cols.pop("x"), units.pop("x")
        drive_note = (f"column {cols['position'][0]} moves one way only (a stage's travel, not a spring's extension "
                      f"beside the force {cols['F'][0]}): read as the drive's position")
    elif "F" in cols and "position" not in cols and "v0" not in cols:
        drive_note = _stage_beside_force(roles, tab, cols, units, None if rotary else stiffness)
    if rate is not None and not (math.isfinite(rate) and 1.0 / DT_RANGE[1] <= rate <= 1.0 / DT_RANGE[0]):
        _fail(f"--rate {rate:g}: the sampling rate must be a number from {1.0 / DT_RANGE[1]:.3g} to "
              f"{1.0 / DT_RANGE[0]:.3g} Hz")
    # an array file (.mat, .npz) has no header: its variables are the columns, and one of another length or
    # shape is passed over (the role it would have had is then missing: said beside the missing role)
    where = "among the variables" if tab.passed_over or str(path).lower().endswith((".npz", ".mat")) \
        else "in the header"
    over = (f" (variable{'s' if len(tab.passed_over) > 1 else ''} {', '.join(tab.passed_over)[:120]} passed over: not "
            f"vectors of the record's length)"
            if tab.passed_over else "")
    stated, unread = None, ""
    if "t" not in cols and rate is None and tab.stated_rate is not None and tab.stated_rate[0] is not None and \
            1.0 / DT_RANGE[1] <= tab.stated_rate[0] <= 1.0 / DT_RANGE[0]:
        # no time column, and no --rate: the rate the instrument's metadata states (the rows evenly spaced)
        rate, line, text = tab.stated_rate
        stated = (f"no time column: the rows are samples {1.0 / rate:.4g} s apart, at the {rate:g} Hz that line "
                  f"{line} states ({text!r}; --rate overrides it)")
    elif "t" not in cols and rate is None and tab.stated_rate is not None:
        unread = (f"; line {tab.stated_rate[1]} ({tab.stated_rate[2]!r}) states a rate that is not read: "
                  + ("it can be read two ways" if tab.stated_rate[0] is None else
                     f"{tab.stated_rate[0]:g} Hz is out of range"))
    if "t" not in cols and rate is None:
        _fail(f"{path}: no time column (t or time) {where}{over}{_as_read(roles, cols)}{unread}: add one, or give "
              f"--rate (the sampling rate, Hz)")
    if isinstance(normal_load, tuple):
        val, unit = normal_load
        if _unit_key(unit) not in _FORCE:
            _fail(f"--normal-load {val:g} {unit}: unit not understood for a force (N, mN, kN, gf, kgf, lbf)")
        normal_load = val * _FORCE[_unit_key(unit)]
    if normal_load is not None and not (math.isfinite(normal_load) and normal_load > 0):
        _fail(f"--normal-load {normal_load:g}: the normal load is a positive force (N)")
    mu_read = "x" not in cols and "F" not in cols and "mu" in cols
    mu_note = _friction_from_mu(path, cols, units, stiffness, normal_load) if mu_read else None
    load_note = None if normal_load is None or mu_read else \
        f"--normal-load {normal_load:g} N: not used (the record's friction is a force or an extension, not a coefficient)"
    lone = None
    if "x" not in cols and "F" not in cols and v0 is not None and "v0" not in cols:
        # one position and --v0 (a video of the slider alone, a laser on it): the slider's position, the drive
        # given by --v0; read as an x that follows the drive's travel (:func:`_extension_of_slider`)
        cand = [(n, _position_unit(n, u)) for n, role, u in roles
                if role == "position" or (role is None and _maybe_position(n, u))]
        if len(cand) == 1 and cand[0][1] is not None:
            n, u = cand[0]
            cols.pop("position", None), units.pop("position", None)
            # (pixels at the stated scale; a unit that is not written is read from the travel below)
            cols["x"], units["x"] = (n, tab.columns[n] * _position_scale(path, n, u, tab)), "mm" if u else ""
            lone = n
    lone_force = None
    if "x" not in cols and "F" not in cols:
        # a record's one force whose name says nothing (a data-acquisition channel's, 'Dev1/ai0', with its unit
        # from the file's header): the friction force, said; two such are refused (which is which?)
        taken = {c[0] for c in cols.values()}
        forces = [(n, u) for n, role, u in roles if role is None and n.strip() and u.strip() and n not in taken
                  and _unit_key(u) in _FORCE_ONLY]
        # not beside a column of no unit that lieng cannot name (a friction coefficient in a language it does
        # not read: the force is then its normal load), nor when the force stands still (a normal load's does;
        # a friction force in stick-slip swings by its drops)
        bare = [n for n, role, u in roles if role is None and n.strip() and not u.strip() and n not in taken
                and not _words(n) & _NOT_A_QUANTITY]
        if len(forces) == 1 and not bare:
            n, u = forces[0]
            lo, hi, mid = np.nanpercentile(tab.columns[n], [1, 99, 50])
        if len(forces) == 1 and not bare and hi - lo > LONE_FORCE_SWING * abs(mid):
            cols["F"], units["F"] = (n, tab.columns[n]), u
            lone_force = (f"column {n} ({u}), the record's one force whose name lieng does not know, read as the "
                          f"friction force (--names sets each column's role)")
    if "x" not in cols and "F" not in cols:
        unread = any(nm.strip() and nm not in {c[0] for c in cols.values()} for nm, _, _ in roles)
        _fail(f"{path}: no displacement (x), friction force (F) or friction coefficient (mu) column {where}{over}"
              f"{_as_read(roles, cols)}" + (": rename the columns, or give their names with --names "
                                            "('t [s],F [N],N [N]', in the file's order)" if unread else ""))
    n = len(tab)
    if n < MIN_SAMPLES:
        _fail(f"{path}: {n} samples: too short for stick-slip analysis (at least {MIN_SAMPLES})")
    if n > MAX_SAMPLES:
        _fail(f"{path}: {n} samples: more than the {MAX_SAMPLES} this command reads; cut the record")
    dated = "t" in cols and cols["t"][0] in tab.dates
    serial_note = None
    if dated:
        t = cols["t"][1]                  # date-times: seconds from the first row's
    elif "t" in cols:
        t = cols["t"][1] * _scale(path, cols["t"][0], units["t"], _TIME, "time")
        tv = cols["t"][1]
        if not units["t"] and cols["t"][0].strip().lower() in EXCEL_DAY_NAMES \
                and np.all((tv > 20000.0) & (tv < 80000.0)) and float(np.ptp(tv)) < 30.0:
            # a spreadsheet's serial date (days since 1899-12-30: 45363.43 is 2024-03-11 10:19): days, read as
            # seconds from the first row's
            t = (tv - tv[0]) * 86400.0
            serial_note = (f"{cols['t'][0]}: spreadsheet serial dates (days since 1899-12-30), read as seconds from "
                           f"the first row's")
    else:
        t = np.arange(n) / float(rate)
    d = np.diff(t)
    bad = np.flatnonzero(d <= 0)

    def take(keep):
        """The rows ``keep`` of the time and the columns read (their line
        numbers with them): (t, cols, its steps, the steps that do not increase)."""
        tab.lines = tab.lines[keep]
        tk = t[keep]
        dk = np.diff(tk)
        return tk, {k: (nm, col[keep]) for k, (nm, col) in cols.items()}, dk, np.flatnonzero(dk <= 0)

    restart = bad[t[bad + 1] <= t[0]] if bad.size else bad
    runs_note = None
    if restart.size and restart.size >= 0.5 * (n - 1):
        # most steps go back: a record written last sample first, not runs appended to one file
        _fail(f"{path}: column {cols['t'][0]}: the time goes back at {restart.size} of the {n - 1} steps from "
              f"line {tab.lines[0]} on: the rows must be in time order (sort them by time)")
    if restart.size and restart.size == bad.size:
        # the clock starts again: runs appended to one file; the longest is analysed
        edges = np.r_[0, restart + 1, n]
        j = int(np.argmax(np.diff(edges)))
        keep = slice(int(edges[j]), int(edges[j + 1]))
        runs_note = (f"the time starts again {restart.size} time{'s' if restart.size > 1 else ''} (runs appended to "
                     f"one file): the longest run, lines {tab.lines[keep.start]} to {tab.lines[keep.stop - 1]}, is "
                     f"analysed")
        t, cols, d, bad = take(keep)
        n = t.size
        if n < MIN_SAMPLES:
            _fail(f"{path}: {n} samples in the longest run: too short for stick-slip analysis (at least {MIN_SAMPLES})")
    dup_note = None
    if bad.size and np.all(d[bad] == 0) and bad.size <= 0.05 * n:
        # a row written twice (a logger's buffer flushed again): the same time and the same reading in every
        # column read is no sample; dropped and said
        rep = bad + 1
        if all(np.array_equal(col[rep], col[rep - 1], equal_nan=True) for _, col in cols.values()):
            keep = np.ones(n, bool)
            keep[rep] = False
            dup_note = (f"{rep.size} row{'s' if rep.size > 1 else ''} repeat{'' if rep.size > 1 else 's'} the row "
                        f"before exactly (first at line {tab.lines[rep[0]]}; a row written twice): dropped")
            t, cols, d, bad = take(keep)
            n = t.size
    stamps_note = None
    # stamps written coarser than the sampling: they repeat (1 ms stamps at 2 kHz), or, sampled between one
    # and two of their steps apart, step by one or two (1 ms stamps every 1.245 ms)
    uneven = not bad.size and d.size >= 2 and float(np.max(d)) > 1.01 * float(np.min(d))
    stamped = _stamps_quantised(t) if bad.size and np.all(d[bad] == 0) else \
        _stamps_quantised(t, between=True) if uneven else None
    if stamped is not None:
        # (a line of positive slope: the times it gives increase, nothing is left bad)
        (t, q), bad = stamped, bad[:0]
        stamps_note = (f"the time stamps {'step unevenly' if uneven else 'repeat'} (written to {q:.3g} s, coarser than "
                       f"the sampling): the samples are taken as evenly spaced, {(t[-1] - t[0]) / (t.size - 1):.4g} s "
                       f"apart, over the stamps' span")
    if bad.size:
        what = "repeats" if d[bad[0]] == 0 else "goes back"
        _fail(f"{path}: line {tab.lines[bad[0] + 1]}, column {cols['t'][0]}: time {what} "
              f"({t[bad[0] + 1]:g} after {t[bad[0]]:g}): t must increase")
    notes = [m for m in (rotary["note"] if rotary else None, *given, pair_note, press_note, axis_note, pull_note, notes_pair, slider_note, mu_note, load_note, lone_force,
                         drive_note,
                         serial_note, runs_note, dup_note, stamps_note) if m]
    if dated:
        notes.append(f"column {cols['t'][0]} holds date-times: read as seconds from {tab.dates[cols['t'][0]]}")
    if stated:
        notes.append(stated)
    elif rate is not None:
        notes.append(f"--rate ignored: the record gives the time (column {cols['t'][0]})" if "t" in cols else
                     f"no time column: the rows are samples {1.0 / rate:.4g} s apart (--rate {rate:g} Hz)")
    notes.extend(tab.notes())
    if "x" in cols:
        x = cols["x"][1] * _scale(path, cols["x"][0], units["x"], _LENGTH, "displacement")
        if pair is None and v0 is not None and not {"position", "v0"} & cols.keys():
            # a displacement without its unit beside --v0 that travels with the drive (a video tracker's one
            # track, in m or cm): the slider's position, in the unit its travel says (:func:`_extension_of_slider`)
            k = _unit_from_travel(path, cols["x"][0], x, cols, units, float(v0), notes) if not units["x"] else None
            x = x * (k or 1.0)
            if (k or lone is not None) and float(x[-1] - x[0]) * float(v0) < 0:
                # (its axis counts the other way: a camera's image coordinates, a laser facing the slider)
                x = -x
                notes.append(f"column {cols['x'][0]} runs against --v0's direction: its sign is turned")
        if stiffness is not None:
            notes.append("--stiffness ignored: the record gives the displacement x itself")
        y, y_force = None, False
        if "y" in cols:
            y = cols["y"][1] * _scale(path, cols["y"][0], units["y"], _LENGTH, "displacement")
        elif "N" in cols:
            y, y_force = _force(path, cols, units, "N"), True
    else:
        unknown = stiffness is None
        # (a torsion spring's N·m per angle is small: a fine coupling's 1e-9 N·m/rad is a linear 1e-3 N/m at 1 mm)
        k_unit, k_lo = (f"N·m/{rotary['unit']}", 1e-9) if rotary else ("N/m", 1e-6)
        if not unknown and not (math.isfinite(stiffness) and k_lo <= stiffness <= 1e12):
            _fail(f"--stiffness {stiffness:g}: the stiffness must be a number from {k_lo:g} to 1e+12 ({k_unit})")
        if _is_stress(units["F"]):
            if not unknown:
                _fail(f"{path}: column {cols['F'][0]} is a stress ({units['F']}): --stiffness (N/m) does not apply; "
                      f"leave it out (the stiffness per area is then read from the sticks)")
            notes.append(f"column {cols['F'][0]} is a stress: read as the friction force per area, so the stiffness "
                         f"read from the sticks is per area (Pa/m)")
        F = _force(path, cols, units, "F")
        # (mm from N over N/m; a rotary record's mrad from N·m over N·m per its angle unit)
        x = F / (1.0 if unknown else stiffness) * (_ANGLE[rotary["unit"]] if rotary and not unknown else 1e3)
        y, y_force = None, False
        if "N" in cols:
            y, y_force = _force(path, cols, units, "N"), True
        elif "y" in cols:
            y = cols["y"][1] * _scale(path, cols["y"][0], units["y"], _LENGTH, "displacement")
    if y_force and not np.any(y):
        # a normal force of zero throughout (a channel not connected, a bridge not powered) loads nothing
        notes.append(f"the normal force {cols['N'][0]} is zero throughout (a channel not connected?): not read")
        y, y_force = None, False
    if y_force and float(np.mean(y < 0)) > 0.99:
        # a normal force written negative throughout: a compression, as a load cell's z axis reads it
        y = -y
        notes.append(f"the normal force {cols['N'][0]} is written negative (a compression, as a load cell's z "
                     f"axis reads it): read as its magnitude")
    # the drive
    vcol = pos = None
    if "v0" in cols:
        vcol = cols["v0"][1] * _scale(path, cols["v0"][0], units["v0"], _VELOCITY, "velocity")
    elif "position" in cols:
        pos = cols["position"][1] * _scale(path, cols["position"][0], units["position"], _LENGTH, "position")
        if v0 is not None and not np.nanmax(pos) - np.nanmin(pos) > 1e-9:
            # a position that never moves beside --v0 (an SRV's 'Stroke', the amplitude set): a setting, not
            # the drive; the drive is --v0
            notes.append(f"column {cols['position'][0]} never moves: a setting, not the drive's position (the "
                         f"drive is --v0)")
            pos = None
    elif v0 is None:
        if angle is not None:
            _fail(f"{path}: column {angle} is an angle (a rotating drive's): the drive velocity is needed as a "
                  f"sliding speed: give --v0 (mm/s: the angular speed times the track radius)")
        _fail(f"{path}: no drive column (v0 or position){_as_read(roles, cols)} and no --v0: the drive velocity is "
              f"needed (give --v0, or name the stage's column 'position')")
    elif angle is not None:
        notes.append(f"column {angle} (an angle: a rotating drive's) is not read: the drive is --v0, the sliding "
                     f"speed at the track")
    if v0 is not None and (vcol is not None or pos is not None):
        notes.append("--v0 ignored: the record gives the drive")
    if v0 is not None and vcol is None and pos is None:
        if rotary:
            # (the record's angle unit per second, held in mrad/s; in rad/s within the range a linear drive has
            # in mm/s)
            _check_v0(v0, f"{rotary['unit']}/s", _ANGLE[rotary["unit"]] / 1e3)
            v0 = v0 * _ANGLE[rotary["unit"]]
        else:
            _check_v0(v0)
    rec = _regularise(path, t, {"x": x, "y": y, "v0": vcol, "pos": pos}, notes)
    t, x, y, vcol, pos = rec["t"], rec["x"], rec["y"], rec["v0"], rec["pos"]
    dt = float(t[1] - t[0])
    if vcol is not None:
        vd, recorded = vcol, True
    elif pos is not None:
        if not np.ptp(pos) > 1e-9:          # a picometre: rounding, not a drive
            _fail(f"{path}: column {cols['position'][0]}: the drive never moves (its position spans "
                  f"{float(np.ptp(pos)):.3g} mm)")
        vd, recorded = _drive_from_position(_position_jumps(pos, notes), dt, notes), True
    else:
        vd, recorded = np.full_like(t, float(v0)), False
    if not np.any(np.abs(vd) > 0):
        _fail(f"{path}: the drive never moves (all zero): no stick-slip")
    slider = False
    if "x" in cols and "F" not in cols and pair is None:
        x, slider = _extension_of_slider(x, vd, dt, pos, cols["x"][0], notes, lone is not None)
        if lone is not None and not slider:
            _fail(f"{path}: column {lone}, the record's only position, is read as the slider's (--v0 gives the "
                  f"drive), but it does not follow the drive's travel at --v0 {float(v0):g} mm/s: check --v0 and "
                  f"the column's unit, or give the spring's extension or the force")
    zero_unknown = False
    if pair is not None or slider:
        # an extension from two positions: its zero is where their origins put it
        x, zero_unknown = _zero_between_directions(x, vd, notes)
    elif recorded:
        # a friction that keeps its sign though the drive reverses: written unsigned, or off its zero
        x, zero_unknown = _one_sided(x, vd, notes)
    # a column the record carries but nothing reads (its name gives no role, or another column took it) is
    # said: a seal rig's "squeeze [mm]" was dropped in silence before the word was known
    used = {c[0] for c in cols.values()}
    unread = [n for n, _, _ in roles if n not in used and not any(n in note for note in notes) and n.strip()]
    if unread:
        notes.append(f"not read: column{'s' if len(unread) > 1 else ''} {', '.join(unread)} (no role from "
                     f"{'their names' if len(unread) > 1 else 'its name'}, or another column's)")
    out = Record(t=t, x=x, vd=vd, y=y, y_is_force=y_force, drive_recorded=recorded, source=str(path), notes=notes,
                 zero_unknown=zero_unknown,
                 stiffness_unknown="F" in cols and "x" not in cols and stiffness is None,
                 stiffness=stiffness if "F" in cols and "x" not in cols else None,
                 stiffness_unit="Pa/m" if "F" in cols and _is_stress(units["F"]) else
                 "1/m" if mu_note and "N" not in cols and normal_load is None else
                 (f"N·m/{rotary['unit']}" if stiffness is not None else "N·m/rad") if rotary else "N/m",
                 length_unit="mrad" if rotary else "mm")
    condition(out)
    if highpass is not None:
        undo_highpass(out, highpass)
    return out


def cumulative_trapezoid(v, dt) -> np.ndarray:
    """The integral of ``v`` from the first sample to each, by the trapezoid
    rule over the steps ``dt`` (one step, or the n - 1 steps); 0 at the
    first sample (:func:`.segment.travel` is the drive's)."""
    v = np.asarray(v, float)
    return np.r_[0.0, np.cumsum(0.5 * (v[1:] + v[:-1]) * dt)]


def _check_highpass(tau) -> None:
    if tau is not None and not (math.isfinite(tau) and tau > 0):
        _fail(f"--highpass {tau:g}: the high-pass time constant must be a positive number of seconds")


def undo_highpass(rec: Record, tau: float) -> None:
    """Undo, in place, a first-order high-pass of time constant ``tau`` (s)
    on the friction channel x: an AC-coupled sensor (a piezoelectric force
    cell's charge amplifier) records y with y' = x' - y / tau, so that a
    steady force sinks towards zero and each stick's ramp sags; the force is
    x = y + (1 / tau) * (the integral of y from the record's start)
    (trapezoid, on the record's times), with a note.  The constant of the
    integration, the decay that had built up before the record started, is
    not known: x keeps the record's own level at its start (a constant
    offset, which moves no effect's evidence).  After spikes and hum are
    taken out (:func:`condition`): a spike integrated would be a step."""
    _check_highpass(tau)
    y = rec.x
    if tau < 5.0 * rec.dt:
        _fail(f"--highpass {tau:g}: shorter than 5 sampling intervals ({rec.dt:.3g} s): such a high-pass leaves "
              f"nothing of the stick-slip to recover")
    rec.x = y + cumulative_trapezoid(y, np.diff(rec.t)) / tau
    rec.highpass = float(tau)
    span = float(rec.t[-1] - rec.t[0])
    rec.notes.append(f"the friction channel's high-pass (an AC-coupled sensor, time constant {tau:g} s, "
                     f"{span / tau:.3g} of it over the record) undone: x = the recorded x + its integral from the "
                     f"record's start / {tau:g} s (the level at the start kept as recorded)")


#: a channel sits at its extreme value on at least this fraction of its samples (and 10) to be questioned
LIMIT_SHARE = 0.002


def _at_limit(v) -> str | None:
    """Whether a channel sits at its largest (or smallest) value for longer
    than it takes to pass through the band just inside it: a clipped sensor
    (flat tops, three samples long or more, where the signal would go on)
    rather than a quantised reading (whose top level holds about as long
    as the levels under it; one of fewer than 50 levels is not judged).
    Returns words saying so, or None."""
    n = v.size
    lo, hi = np.percentile(v, [2, 98])
    band = 0.02 * float(hi - lo)
    if not band > 0:
        return None
    levels = np.unique(v[(v >= lo) & (v <= hi)]).size     # a reading coarse against its span is not judged
    for end, sign in ((float(np.max(v)), 1.0), (float(np.min(v)), -1.0)):
        at = v == end
        k = int(np.count_nonzero(at))
        if k < max(10, LIMIT_SHARE * n):
            continue
        inside = int(np.count_nonzero((sign * (end - v) > 0) & (sign * (end - v) <= band)))
        runs = int(np.count_nonzero(np.diff(at.astype(np.int8)) == 1)) + int(at[0])
        if k > 2 * inside and runs >= 2 and k >= 3 * runs and levels >= 50:
            return (f"sits at its {'largest' if sign > 0 else 'smallest'} value, {end:.6g}, on {k} samples in {runs} "
                    f"stretches")
    return None


#: a displacement column that follows the drive's travel with a slope within this range is the slider's
#: position: it moves with the drive less the spring's extension, which stays within a few drops
SLIDER_TRAVEL = (0.7, 1.3)
#: ... its residual about that line within this fraction of the drive's own spread
SLIDER_SPREAD = 0.5
#: ... or, on a short stroke (the extension's swing at each reversal a good part of it: a slope down to
#: SLIDER_SLOPE_MIN), when it stands still while the drive moves: over most of the drive's steps (the
#: median) it moves less than this fraction of them (a slider that sticks; an extension rises with the drive)
SLIDER_STILL = 0.3
SLIDER_SLOPE_MIN = 0.3
#: ... and never when x moves over most of the drive's steps by this fraction of them or more (an extension
#: whose level climbs with the drive as fast as a slider's position would: it rises at least at the drive's
#: speed in every stick; a slider's, read through mains hum, stands still to about half its steps)
SLIDER_MOVING = 0.75


def _extension_of_slider(x, vd, dt: float, pos, name: str, notes: list, lone: bool = False) -> tuple:
    """The spring's extension from a displacement column that is the
    slider's position (a laser on the slider, named x or ``laser``): it
    follows the drive's travel (one way, or back and forth on a
    reciprocating stage) with a slope near 1 (:data:`SLIDER_TRAVEL`) and a
    residual small beside the travel (:data:`SLIDER_SPREAD`) while it does
    not rise with the drive over most of its steps (:data:`SLIDER_MOVING`),
    or, on short strokes, with a smaller slope while it stands still over
    most of the drive's steps (:data:`SLIDER_STILL`: a slider that sticks,
    where an extension rises and falls every cycle about a level, rising
    with the drive while the slider sticks); the extension is the drive's travel
    less it, said in ``notes``: (extension, True).  Any other column is
    returned as it is: (x, False)."""
    drive = pos - pos[0] if pos is not None else cumulative_trapezoid(vd, dt)
    sd = float(np.std(drive))
    if not sd > 0:
        return x, False
    slope, icpt = np.polyfit(drive, x, 1)
    if not SLIDER_SLOPE_MIN <= slope <= SLIDER_TRAVEL[1]:
        return x, False
    spread = float(np.std(x - (icpt + slope * drive)))
    # over steps in which the drive moves ten times x's noise: x's move over the drive's, median (a slider
    # that sticks stands still over most of them; an extension rises with the drive, at least as fast)
    step = float(np.median(np.abs(np.diff(drive))))
    k = int(min(max(math.ceil(10.0 * noise_level(x) / step), 1) if step > 0 else x.size, x.size // 50))
    still = math.inf
    if k >= 1:
        dd, dx = drive[k:] - drive[:-k], x[k:] - x[:-k]
        moving = np.abs(dd) > 0.5 * np.median(np.abs(dd))
        if np.count_nonzero(moving) > 20:
            still = float(np.median(np.abs(dx[moving]) / np.abs(dd[moving])))
    follows = still < SLIDER_STILL or (SLIDER_TRAVEL[0] <= slope and spread <= SLIDER_SPREAD * sd
                                       and still < SLIDER_MOVING)
    if not follows:
        return x, False
    notes.append(f"column {name} follows the drive's travel (slope {slope:.2f}): the slider's position, not the "
                 f"spring's extension (which rises and falls every cycle about a level); the extension is read as "
                 f"the drive's travel less it, from 0 at the first sample (the friction level is then relative "
                 f"to that sample's)" + ("; the record's only position, beside --v0" if lone else ""))
    return drive - (x - x[0]), True


def _moving(vd):
    """The drive's direction where it moves clearly (+1, -1; 0 where it stands or creeps: under a quarter of
    its speed on the fastest tenth of the samples, a dwell's differentiated noise)."""
    thr = 0.25 * float(np.quantile(np.abs(vd), 0.9))
    return np.where(np.abs(vd) > thr, np.sign(vd), 0.0) if thr > 0 else np.zeros(vd.size)


#: the roles' names in the messages
_ROLE_WORDS = {"t": "the time", "x": "the spring's extension", "y": "a normal reading", "v0": "the drive velocity",
               "F": "the friction force", "mu": "a friction coefficient", "N": "the normal force",
               "position": "the drive's position"}


def _as_read(roles, cols) -> str:
    """How each column of the header was read, for a refusal's message: " (read: Time as the time, Fx as the
    friction force; not read: Y, Z)"; empty for a table of no columns."""
    used = {c[0]: r for r, c in cols.items()}
    read = [f"{n} as {_ROLE_WORDS.get(used[n], used[n])}" for n, _, _ in roles if n in used]
    unread = [n for n, _, _ in roles if n not in used and n.strip()]
    parts = ([f"read: {', '.join(read)}"] if read else []) + ([f"not read: {', '.join(unread)}"] if unread else [])
    return f" ({'; '.join(parts)})"[:400] if parts else ""


def _both_ways(m) -> bool:
    """Whether the drive's directions ``m`` (:func:`_moving`) go each way on a tenth of the samples or more."""
    return min(np.count_nonzero(m > 0), np.count_nonzero(m < 0)) >= 0.1 * m.size


def _zero_between_directions(x, vd, notes: list, why: str | None = None) -> tuple:
    """An extension read from two positions (the stage's less the
    slider's) on a drive that goes both ways: its zero, which the positions'
    origins do not give, set midway between its median levels in the two
    directions (the friction as large either way), and said; (x, True).  On
    a drive one way, (x, False) as it is.  ``why`` says why the zero is
    not in the record (by default: two positions' origins)."""
    m = _moving(vd)
    if not _both_ways(m):
        return x, False
    mid = 0.5 * (float(np.median(x[m > 0])) + float(np.median(x[m < 0])))
    why = why or "the drive goes both ways and the extension's zero is not in the positions"
    notes.append(f"{why}: set midway between its levels in the two directions ({mid:.4g} mm from the record's "
                 f"zero); the two directions' friction levels cannot then be told apart (direction_asymmetry is "
                 f"not read)")
    return x - mid, True


#: at a reversal an unsigned friction (|F|, |mu|) falls to within this share of the smaller of the two
#: directions' levels before it rises again; a signed one off its zero passes from one level to the other
UNSIGNED_DIP = 0.25
#: the share of the reversals that must show that dip for the record to be read as unsigned
UNSIGNED_SHARE = 0.75


def _one_sided(x, vd, notes: list) -> tuple:
    """A friction that keeps its sign on a drive that goes both ways (a
    friction opposes the motion: it changes side when the drive reverses).
    Where it dips to about zero at each reversal (UNSIGNED_DIP at
    UNSIGNED_SHARE of them) it was written unsigned (|F|, an unsigned
    coefficient): signed by the drive's direction, changing at each dip's
    lowest point (where the spring passes through its zero), and said;
    (x, False).  Otherwise it is a signed force off its zero (a sensor's
    offset): :func:`_zero_between_directions`, (x, True).  A record whose
    friction changes side with the drive, or whose drive goes one way, is
    returned as it is, (x, False)."""
    mv = _moving(vd)
    if not _both_ways(mv):
        return x, False
    lf, lb = float(np.median(x[mv > 0])), float(np.median(x[mv < 0]))
    if lf * lb <= 0:
        return x, False
    g = math.copysign(1.0, lf)
    a = g * x                                   # the magnitude, positive both ways
    level = min(abs(lf), abs(lb))
    moving = np.flatnonzero(mv != 0)
    turns = np.flatnonzero(np.diff(mv[moving]) != 0)
    if turns.size == 0:
        return x, False
    # each reversal's window: from the old direction's last clear move (the spring, stuck through a dwell,
    # unloads once the drive comes back) to halfway on to the next reversal
    last = [int(moving[k]) for k in turns]
    ends = [(p + int(moving[k + 1])) // 2 for p, k in zip(last[1:], turns[1:])] + [x.size]
    dips = []
    for lo, hi in zip(last, ends):
        i = lo + int(np.argmin(a[lo:hi]))
        dips.append((i, float(a[i]) < UNSIGNED_DIP * level))
    if np.mean([d for _, d in dips]) >= UNSIGNED_SHARE:
        sign = np.empty(x.size)
        cur, start = float(mv[moving[0]]), 0
        for i, _ in dips:
            sign[start:i] = cur
            cur, start = -cur, i
        sign[start:] = cur
        notes.append(f"the friction keeps its sign though the drive reverses ({len(dips)} times) and falls to about "
                     f"zero at each reversal: written unsigned (|F| or an unsigned coefficient); signed by the "
                     f"drive's direction, changing where it passes through zero")
        return a * sign, False
    return _zero_between_directions(x, vd, notes, "the friction keeps its sign though the drive reverses, and "
                                                  "passes from one level to the other at each reversal (a force "
                                                  "opposes the motion either way): a sensor's offset; its zero")


#: a length column beside a force is the spring's extension (x = F / k, two readings of one spring) only
#: when their correlation is at least this, and, with the stiffness given, its swing is within this
#: factor of F / k's; a stage's position is neither (a reciprocating stage's with dwells correlates 0.8
#: with the friction, which keeps its sign through each dwell)
FOLLOWS_FORCE = 0.9
FOLLOWS_SWING = 3.0


def _follows(x, F, stiffness=None) -> bool:
    """Whether the length ``x`` (mm) follows the force ``F`` (N) as the
    spring's extension does (FOLLOWS_FORCE, FOLLOWS_SWING; ``stiffness`` in
    N/m or None; finite samples only)."""
    ok = np.isfinite(x) & np.isfinite(F)
    if np.count_nonzero(ok) < 20 or not (np.ptp(x[ok]) > 0 and np.ptp(F[ok]) > 0):
        return False
    if stiffness:
        r = float(np.ptp(x[ok])) / (1e3 * float(np.ptp(F[ok])) / stiffness)
        if not 1.0 / FOLLOWS_SWING <= r <= FOLLOWS_SWING:
            return False
    return abs(float(np.corrcoef(x[ok], F[ok])[0, 1])) >= FOLLOWS_FORCE


def _friction_among_normals(roles, tab, cols, units) -> str | None:
    """A record with no friction column but two read as normal forces, one of
    them the friction by its name: a force named with its unit as the last
    part ("F_N" beside "Fn_N": F in N), or a plain "Load" or "Force" beside
    one named normal (a testing machine's "Load" beside its "Normal Load");
    or one so named ("F_N") and no extension: the record's one force.
    Moves it to F (``cols``, ``units`` in place) and says so; None when
    there is no such pair."""
    if {"F", "mu"} & cols.keys():
        return None
    normals = [(n, u) for n, r, u in roles if r == "N"]
    if not normals or len(normals) < 2 and "x" in cols:
        return None

    def friction_unit(n, u):
        if not u and "_" in n:
            stem, suf = n.rsplit("_", 1)
            if _unit_key(suf) in _FORCE and _role(stem, suf) == "F":
                return suf                   # "F_N": F in newtons
        if n.strip().lower() in ("load", "force") and any("normal" in _words(m) for m, _ in normals if m != n):
            return u                         # "Load" beside "Normal Load"
        return None

    hits = [(n, friction_unit(n, u)) for n, u in normals]
    hits = [h for h in hits if h[1] is not None]
    if len(hits) != 1:
        return None
    name, unit = hits[0]
    cols["F"], units["F"] = (name, tab.columns[name]), unit
    other = next(((m, u) for m, u in normals if m != name), None)
    if other is None:
        # "F_N" alone: the record's one force, named F with its unit, is the friction (a record has one)
        cols.pop("N"), units.pop("N")
        return f"column {name} is the record's one force, F in {unit}: read as the friction force"
    cols["N"], units["N"] = (other[0], tab.columns[other[0]]), other[1]
    return f"column {name} is the friction force and {other[0]} the normal one (both named as forces)"


def _stage_beside_force(roles, tab, cols, units, stiffness=None) -> str | None:
    """A force record's drive position in a length column read as something
    else: a displacement that does not follow the force (it is not the
    spring's extension, F / k: a testing machine's "Extension", an "Axial
    Displacement", a stage's "x" beside "Ff"), or a bare axis letter ("Y
    (mm)", a tribometer's stage axis) beside a normal force or coefficient.
    Moves it to ``position`` (in place) and says so; None when there is
    none.  ``stiffness`` (N/m), when given, is used to tell them apart
    (:func:`_follows`)."""
    F = tab.columns[cols["F"][0]] * _FORCE.get(_unit_key(units["F"]), 1.0)
    scaled = lambda n, u: tab.columns[n] * _LENGTH.get(_unit_key(u), 1.0)
    if "x" in cols and not _follows(scaled(cols["x"][0], units["x"]), F, stiffness):
        cols["position"], units["position"] = cols.pop("x"), units.pop("x")
        return (f"column {cols['position'][0]} does not follow the force {cols['F'][0]} (the spring's extension "
                f"would): read as the drive's position")
    if "N" not in cols and "mu" not in cols:
        return None
    axes = [(n, u) for n, r, u in roles if r in ("x", "y") and n.strip().lower() in ("x", "y")
            and _unit_key(u) in _LENGTH and u and not _follows(scaled(n, u), F, stiffness)]
    if not axes:
        return None
    name, unit = max(axes, key=lambda a: float(np.nanmax(tab.columns[a[0]]) - np.nanmin(tab.columns[a[0]])))
    if not np.nanmax(tab.columns[name]) > np.nanmin(tab.columns[name]):
        return None
    for role in ("x", "y"):
        if role in cols and cols[role][0] == name:
            cols.pop(role), units.pop(role)
    cols["position"], units["position"] = (name, tab.columns[name]), unit
    return f"column {name} (a stage axis in {unit}, beside the forces) is read as the drive's position"


#: a force column of no known name is read as the friction force only when it swings by more than this share of
#: its median (1st to 99th percentile): a normal load held constant does not
LONE_FORCE_SWING = 0.02
#: the words of a column that holds no quantity (a comment, a counter, an index)
_NOT_A_QUANTITY = {"comment", "comments", "note", "notes", "remark", "no", "nr", "index", "idx", "sample", "point",
                   "count", "counter", "cycle", "cycles", "lap", "laps", "step", "segment", "status", "flag", "marker",
                   "event", "trigger"}


def _one_way(x) -> bool:
    """Whether a column moves one way only: lightly smoothed (a hundredth of
    the record), its total variation is within a quarter of its net change
    (a drive's travel; a spring's extension in stick-slip rises and falls
    every cycle)."""
    n = x.size
    if n < 20:
        return False
    w = max(1, n // 100)
    xs = np.convolve(x, np.ones(w) / w, mode="valid")
    net = abs(float(xs[-1] - xs[0]))
    return net > 0 and float(np.sum(np.abs(np.diff(xs)))) <= 1.25 * net


def _stamps_quantised(t, between: bool = False):
    """Time stamps written coarser than the sampling (1 ms stamps at 2 kHz,
    whole seconds at 100 Hz; 1 ms stamps every 1.245 ms): they repeat or
    step by whole numbers of their step, never go back, and stay within one
    stamp step of a straight line in the row number.  Returns the evenly
    spaced times that line gives and the step, or None when the stamps are
    not that (gaps, a clock that stops).  With ``between`` (stamps that
    never repeat) the mean step must also lie clearly between two whole
    numbers of stamp steps (1.245 ms on 1 ms stamps): a whole number (a
    row dropped here and there from evenly stamped samples) is gaps."""
    d = np.diff(t)
    pos = d[d > 0]
    if pos.size < 2 or np.any(d < 0):
        return None
    # the stamps' step: the least step, or the least difference of two steps (0.1 ms stamps every 1.76 ms
    # step by 1.7 and 1.8 ms)
    u = np.unique(np.round(pos, 12))
    q = float(min(u[0], np.min(np.diff(u)))) if u.size > 1 else float(u[0])
    i = np.arange(t.size, dtype=float)
    slope, icpt = np.polyfit(i, t, 1)
    res = t - (icpt + slope * i)
    if not (slope > 0 and float(np.max(np.abs(res))) <= 1.01 * q and np.all(np.abs(pos / q - np.round(pos / q)) < 0.01)):
        return None
    if between and abs(slope / q - round(slope / q)) < 0.02:
        return None
    return icpt + slope * i, q


def record_from_arrays(t, x, v0, y=None, *, y_is_force=False, source="arrays", highpass=None) -> Record:
    """A record from arrays: t (s), x (mm), v0 (mm/s: a number or an array per
    sample), optional normal channel y.  Resampled and conditioned like a file
    (``highpass``: as :func:`read_record`'s)."""
    t = np.asarray(t, float)
    x = np.asarray(x, float)
    if t.shape != x.shape or t.ndim != 1 or t.size < MIN_SAMPLES:
        _fail(f"t and x must be 1-D arrays of equal length >= {MIN_SAMPLES}")
    arrays = [t, x] + ([np.asarray(y, float)] if y is not None else [])
    if not all(np.all(np.isfinite(a)) for a in arrays):
        _fail("t, x and y must be finite")
    if np.any(np.diff(t) <= 0):
        _fail("t must increase")
    notes = []
    vcol = None if np.ndim(v0) == 0 else np.asarray(v0, float)
    if vcol is None:
        _check_v0(float(v0))
    rec = _regularise(source, t, {"x": x, "y": None if y is None else np.asarray(y, float), "v0": vcol,
                                  "pos": None}, notes)
    vd = rec["v0"] if vcol is not None else np.full_like(rec["t"], float(v0))
    out = Record(t=rec["t"], x=rec["x"], vd=vd, y=rec["y"], y_is_force=y_is_force, drive_recorded=vcol is not None,
                 source=source, notes=notes)
    condition(out)
    if highpass is not None:
        undo_highpass(out, highpass)
    return out


#: the sampling intervals a friction record may have (s): 1 GHz to one sample an hour
DT_RANGE = (1e-9, 3600.0)


#: a gap of more than this many sampling intervals is not interpolated across: the record is cut there
#: and its longest part without such a gap is analysed (a straight line across a pause in the logging
#: would be read as a stick or a slip that never happened)
GAP_CUT = 10


def _regularise(path, t, chans, notes) -> dict:
    """The channels on an even grid at the median interval (linear
    interpolation), with a note when the record was uneven or had gaps; the
    longest part without a gap of more than GAP_CUT intervals when it has
    such gaps."""
    d = np.diff(t)
    dt = float(np.median(d))
    if not dt > 0 or not math.isfinite(dt):
        _fail(f"{path}: column t: no usable sampling interval")
    cut = np.flatnonzero(d > GAP_CUT * dt)
    if cut.size:
        starts, ends = np.r_[0, cut + 1], np.r_[cut + 1, t.size]
        k = int(np.argmax(ends - starts))
        a, b = int(starts[k]), int(ends[k])
        notes.append(f"{cut.size} gap{'s' if cut.size > 1 else ''} of more than {GAP_CUT} sampling intervals in "
                     f"the time column (the longest {float(np.max(d[cut])):.4g} s): not interpolated across; the "
                     f"longest part without one is analysed (t = {t[a]:.6g} to {t[b - 1]:.6g} s, {b - a} of "
                     f"{t.size} samples)")
        if b - a < MIN_SAMPLES:
            _fail(f"{path}: column t: gaps of more than {GAP_CUT} sampling intervals leave no part of "
                  f"{MIN_SAMPLES} samples or more to analyse")
        t = t[a:b]
        chans = {name: None if v is None else v[a:b] for name, v in chans.items()}
        d = np.diff(t)
        dt = float(np.median(d))
    if not DT_RANGE[0] <= dt <= DT_RANGE[1]:
        _fail(f"{path}: column t: a sampling interval of {dt:g} s is outside {DT_RANGE[0]:g} to {DT_RANGE[1]:g} s: "
              f"check the time column's unit (seconds)")
    span = float(t[-1] - t[0])
    if span / dt > MAX_SAMPLES:
        _fail(f"{path}: column t: {span:g} s at {dt:g} s would be {span / dt:.3g} samples, more than "
              f"{MAX_SAMPLES}")
    # even within 1 %: the grid of the record's mean interval (times written to few digits round the intervals
    # apart, 0.00172 and 0.00173 s, and any one of them is off the record's clock by up to a rounding step:
    # mains hum fitted on one interval's grid and removed on the written times parts from it over the record)
    out = {"t": t[0] + (span / (t.size - 1)) * np.arange(t.size), **chans}
    if np.max(d) > 1.01 * dt or np.min(d) < 0.99 * dt:
        # spikes out first, on the samples as read: interpolated onto the grid, a spike between two grid
        # points becomes two raised samples, no longer isolated
        for k in ("x", "y"):
            if chans.get(k) is not None:
                chans[k] = _despiked(chans[k], k, notes, " (before resampling)")
        gaps = int(np.count_nonzero(d > 1.5 * dt))
        tu = t[0] + dt * np.arange(int(math.floor(span / dt + 1e-9)) + 1)
        out = {"t": tu}
        for k, v in chans.items():
            out[k] = None if v is None else np.interp(tu, t, v)
        notes.append(f"uneven sampling ({d.min():.4g} to {d.max():.4g} s; {gaps} gaps longer than 1.5 intervals): "
                     f"resampled linearly onto {dt:.4g} s")
    return out


# ------------------------------------------------------------------ conditioning

def noise_level(x) -> float:
    """The white-noise level of a trace (its units): the median absolute
    second difference over 0.6745 sqrt(6) (robust to slips and spikes)."""
    if x.size < 5:
        return 0.0
    d2 = np.diff(x, 2)
    return float(np.median(np.abs(d2 - np.median(d2))) / 0.6745 / math.sqrt(6.0))


def quantum(x) -> float:
    """The step of a reading quantised coarser than its noise (an ADC's or
    an encoder's count, a value printed to few digits), 0 when there is none
    to model: the smallest step between successive samples (its 5th
    percentile), when at least 90 % of the samples lie on its grid (within
    2 % of a step) and at least a fifth of the successive samples repeat
    their value (noise above the step would move nearly every sample off
    it: the step then does not matter)."""
    x = np.asarray(x, float)
    if x.size < 20:
        return 0.0
    d = np.abs(np.diff(x))
    scale = float(np.max(np.abs(x))) or 1.0
    step = d > 1e-9 * scale
    if not np.any(step) or np.count_nonzero(~step) < 0.2 * d.size:
        return 0.0
    q = float(np.percentile(d[step], 5))
    if not q > 0:
        return 0.0
    r = (x - x[0]) / q
    return q if np.mean(np.abs(r - np.round(r)) < 0.02) >= 0.9 else 0.0


#: the longest run of outlying samples :func:`despike` replaces (a spike that a
#: sensor's filter or a coarse grid spreads over neighbouring samples)
SPIKE_RUN = 3


def despike(x, k: float = 8.0, run: int = SPIKE_RUN):
    """Spikes: a run of one to ``run`` samples that stands out from the line
    joining the samples on either side of it, all in the same direction, by
    more than k noise levels, while those two samples agree with each other
    (they differ by less than half the smallest excursion: a slip, a step,
    is not a spike), and by more than the step from each of those samples
    to the one beyond it, twice that for a run of two or more (a narrow
    trough that the signal enters and leaves as steeply as it is deep, a
    slip's overshoot or a second mode ringing, and on a coarse grid a
    breakaway's peak or a slip's trough beside a step of the drop, is not a
    spike).  The run is
    replaced by that line; a spike in the first or the last sample by the
    line through the two samples beside it.  Returns the cleaned copy and the
    count of samples replaced.  The noise level is at least a quantised
    reading's rounding, q / sqrt(12): on a grid coarser than its noise the
    second differences are mostly 0 and their median said no noise, which
    turned the search off (a 0.02 N step with three spikes of several drops:
    none removed, found by a black-box audit)."""
    s = max(noise_level(x), quantum(x) / math.sqrt(12.0))
    if x.size < run + 4 or s <= 0:
        return x, 0
    y = x.copy()
    changed = np.zeros(y.size, bool)
    for _ in range(3):
        found = 0
        for L in range(run, 0, -1):             # the longest first: a run is not taken apart
            n = y.size - L - 1                  # runs y[i+1 .. i+L] between y[i] and y[i+L+1]
            left, right = y[:n], y[L + 1:L + 1 + n]
            exc = np.empty((L, n))
            for j in range(L):
                exc[j] = y[1 + j:1 + j + n] - (left + (right - left) * (j + 1) / (L + 1))
            lo = np.min(np.abs(exc), axis=0)
            same = np.all(exc > 0, axis=0) | np.all(exc < 0, axis=0)
            ok = same & (lo > k * s) & (np.abs(right - left) < 0.5 * lo)
            # a run must also stand out from how fast the signal moves beside it: a narrow trough (a slip's
            # overshoot, a second mode ringing) is entered and left as steeply as it is deep; and a single
            # sample by more than the step beside it: on a coarse grid (10-15 samples a natural period) a
            # breakaway's peak, between the last sample of the stick and the first of the drop, and a
            # slip's trough stand out from the line joining their neighbours as a spike does (before: cut,
            # 20 of them on a record of 32 slips), yet one of those neighbours is a step of the drop
            d = np.abs(np.diff(y))
            before = np.r_[np.inf, d[:n - 1]]               # |y[i] - y[i-1]|
            after = np.r_[d[L + 1:L + 1 + n - 1], np.inf]    # |y[i+L+2] - y[i+L+1]|
            ok &= lo > (2.0 if L > 1 else 1.0) * np.maximum(before, after)
            hit = np.flatnonzero(ok)
            for i in hit:
                if not np.all(np.abs(y[i + 1:i + L + 1] - (y[i] + (y[i + L + 1] - y[i]) * np.arange(1, L + 1)
                                                           / (L + 1))) > k * s):
                    continue                    # changed by an overlapping run already replaced
                y[i + 1:i + L + 1] = y[i] + (y[i + L + 1] - y[i]) * np.arange(1, L + 1) / (L + 1)
                changed[i + 1:i + L + 1] = True
                found += L
        if not found:
            break
    # the first and the last sample have a neighbour on one side only: a spike there stands out from the
    # line through the next two samples, which agree with each other
    for i, j1, j2 in ((0, 1, 2), (y.size - 1, y.size - 2, y.size - 3)):
        e = y[i] - (2.0 * y[j1] - y[j2])
        if abs(e) > k * s and abs(y[j1] - y[j2]) < 0.5 * abs(e):
            y[i] = 2.0 * y[j1] - y[j2]
            changed[i] = True
    return y, int(np.count_nonzero(changed))


def _despiked(x, name: str, notes: list, when: str = ""):
    """:func:`despike` with a note of the spikes replaced in channel ``name``."""
    y, nsp = despike(x)
    if nsp:
        notes.append(f"spikes in {name}: {nsp} samples (isolated or in runs of up to {SPIKE_RUN}) replaced by the line "
                     f"between their neighbours{when}")
    return y


def _hum_lines(x, dt, rate=None):
    """Mains lines (50/60 Hz and harmonics below Nyquist) that stand far
    above the spectrum beside them: [(mains frequency, harmonic, (frequency,
    amplitude, a, b))].  The line
    must peak within a bin (and the grid's 0.4 % tolerance) of the mains
    frequency: the shoulder of a line beside it (a harmonic of the
    stick-slip, a natural frequency near 50 or 60 Hz) is the record's own.
    ``rate``: the drive's typical speed in x's units per second (x only).
    A line that carries most of the record's variance, with the amplitude
    of a sawtooth rising at that speed at its frequency (the stick-slip's
    fundamental, ``rate / (pi f)`` within a factor of 4), is the record's own:
    hum is a disturbance on the record, not most of it."""
    n = x.size
    T = n * dt
    if T * 50 < 20:
        return []
    s = x - np.mean(x)
    w = np.hanning(n)
    S = np.abs(np.fft.rfft(s * w))
    found = []
    nyq = 0.5 / dt
    tt = np.arange(n) * dt
    # the record's own periodicity (the strongest line below 45 Hz: the stick-slip, a reciprocating stroke),
    # refined within its bin; a mains line at one of its harmonics (within half a bin and 2 % of a bin per
    # harmonic, while that stays under a quarter of their spacing), no stronger than a sawtooth's harmonic
    # would be (2 A1 / h) and with the series beside it, is the record's own
    k1 = 2 + int(np.argmax(S[2:max(int(45.0 * T), 3)])) if int(45.0 * T) > 3 else 0
    f1 = a1 = 0.0
    if 2 < k1 < S.size - 1:
        y0, y1, y2 = np.log(S[k1 - 1:k1 + 2] + 1e-300)
        den = y0 - 2 * y1 + y2
        f1 = (k1 + (0.5 * (y0 - y2) / den if den < 0 else 0.0)) / T
        a1 = float(S[k1])

    def fit(kk):
        # the line near bin kk refined in frequency and fitted by least squares, weighted by the window:
        # unweighted, a strong line a few bins away (a stick-slip at 50.7 Hz beside 60 Hz hum on a 0.45 s
        # record) leaks into the fit by the record's sinc (60.41 Hz fitted, 60.0 true), and what is
        # subtracted leaves a beat in every stick
        best = None
        for ff in (kk + np.linspace(-1.0, 1.0, 41)) / T:
            c = np.cos(2 * math.pi * ff * tt)
            sn = np.sin(2 * math.pi * ff * tt)
            wc, ws = w * c, w * sn
            m11, m12, m22 = float(np.dot(wc, c)), float(np.dot(wc, sn)), float(np.dot(ws, sn))
            r1, r2 = float(np.dot(wc, s)), float(np.dot(ws, s))
            det = m11 * m22 - m12 * m12
            if not det > 0:
                continue
            a = (m22 * r1 - m12 * r2) / det
            b = (m11 * r2 - m12 * r1) / det
            if best is None or a * a + b * b > best[1] ** 2:
                best = (ff, math.hypot(a, b), a, b)
        return best

    # a stick-slip faster than 45 Hz: the strongest line of all, when it carries most of the record's
    # variance with the amplitude of a sawtooth rising at the drive's speed at its frequency (rate / (pi f),
    # within a factor of 4), is the record's own periodicity even at a mains frequency (a short record at
    # 50.7 Hz: within half a bin of 50); hum is a disturbance on a record, not most of it
    fund = False
    kt = 2 + int(np.argmax(S[2:])) if S.size > 4 else 0
    amp = 4.0 * float(S[kt]) / n if kt else 0.0          # the window's coherent gain is 1/2: a first estimate
    ms = float(np.mean(s * s))                            # the record's variance (s is x less its mean)
    if rate and kt > max(k1, 2) and kt < S.size - 1 and amp ** 2 > 0.5 * ms \
            and 0.2 <= amp * math.pi * kt / T / rate <= 5.0:
        top = fit(kt)
        if top is not None and top[1] ** 2 / 2.0 > 0.5 * ms \
                and 0.25 <= top[1] * math.pi * top[0] / rate <= 4.0:
            f1, a1, fund = top[0], float(S[kt]), True
    for base in (50.0, 60.0):
        for h in (1, 2, 3):
            fh = base * h
            if fh > 0.95 * nyq:
                continue
            k = int(round(fh * T))
            lo, hi = max(k - 40, 1), min(k + 41, S.size)
            side = np.r_[S[lo:max(k - 3, lo)], S[min(k + 4, hi):hi]]
            if side.size < 10:
                continue
            # a line of its own at the mains frequency: a local maximum within a bin and the grid's tolerance
            m = 1 + int(min(0.004 * fh * T, 4.0))
            own = [j for j in range(max(k - m, 1), min(k + m, S.size - 2) + 1) if S[j] >= S[j - 1] and S[j] >= S[j + 1]]
            if not own:
                continue
            kk = max(own, key=lambda j: S[j])
            peak = float(S[kk])
            if peak > 30.0 * float(np.median(side)):
                best = fit(kk)
                if best is None:
                    continue
                hh = round(best[0] / f1) if f1 > 0 else 0
                tol = (0.5 + 0.02 * hh) / T
                own = hh >= 2 and tol < 0.25 * f1 and abs(best[0] - hh * f1) <= tol and peak <= 2.0 * a1 / hh
                if own:
                    # a harmonic comes with its series: a line at h +- 1 or h +- 2 (a square wave's odd ones) at
                    # least a third of this one; hum on a harmonic stands out of it
                    near = [float(np.max(S[max(int(round(j * f1 * T)) - 1, 1):int(round(j * f1 * T)) + 2]))
                            for j in (hh - 2, hh - 1, hh + 1, hh + 2) if j >= 1 and round(j * f1 * T) + 2 < S.size]
                    own = bool(near) and max(near) >= peak / 3.0
                own = own or (fund and hh == 1 and abs(best[0] - f1) <= tol)
                if abs(best[0] - fh) <= 0.004 * fh + 0.5 / T and not own:     # the line is at the mains frequency
                    found.append((base, h, best))
    return found


def _mains(lines) -> float | None:
    """The one mains frequency of a record, from the hum lines found in its
    channels (:func:`_hum_lines`, pooled): a grid runs at 50 or at 60 Hz,
    never both, so the lines of the other family are the record's own (a
    mode near 100 or 150 Hz).  The family whose fundamental was found,
    then the one with more lines, then the one whose lines lie closer to
    its exact harmonics (relative, the mean of |f / (base h) - 1|: a grid
    holds its frequency, a line of the record's own at 99.83 Hz is not a
    50 Hz grid's); None when none was found."""
    if not lines:
        return None
    score = {base: (any(h == 1 for b, h, _ in lines if b == base), sum(1 for b, _, _ in lines if b == base),
                    -float(np.mean([abs(ln[0] / (b * h) - 1.0) for b, h, ln in lines if b == base])))
             for base in {b for b, _, _ in lines}}
    return max(sorted(score), key=lambda b: score[b])


def condition(rec: Record) -> None:
    """Spikes and mains hum out of x (and y), in place, with notes; a
    channel at its sensor's limit is warned of (:func:`_at_limit`).  The hum
    removed is of one mains frequency, the record's (:func:`_mains`)."""
    hum = {}
    for name in ("x", "y"):
        v = getattr(rec, name)
        if v is None:
            continue
        what = _at_limit(v)
        if what:
            unit = "x, mm" if name == "x" else ("N" if rec.y_is_force else "y, mm")
            rec.warnings.append(f"the {'friction' if name == 'x' else 'normal'} channel ({unit}) {what}: a sensor or "
                                f"amplifier at its limit? The clipped part is read as it was recorded")
        v = _despiked(v, name, rec.notes)
        setattr(rec, name, v)
        rate = float(np.median(np.abs(rec.vd))) if name == "x" and rec.vd is not None else None
        hum[name] = _hum_lines(v, rec.dt, rate)
    mains = _mains([line for lines in hum.values() for line in lines])
    tt = rec.t - rec.t[0]
    for name, lines in hum.items():
        v = getattr(rec, name)
        for base, _, (ff, amp, a, b) in lines:
            if base != mains:
                continue
            v = v - a * np.cos(2 * math.pi * ff * tt) - b * np.sin(2 * math.pi * ff * tt)
            rec.hum_hz = tuple(sorted(set(rec.hum_hz) | {float(ff)}))
            rec.notes.append(f"mains hum at {ff:.2f} Hz in {name} (amplitude {amp:.3g}) removed")
        setattr(rec, name, v)
    other = sorted({ff for lines in hum.values() for base, _, (ff, _, _, _) in lines if base != mains})
    if other:
        rec.notes.append(f"lines at {', '.join(f'{ff:.2f}' for ff in other)} Hz sit near {110 - mains:g} Hz mains "
                         f"harmonics, but the record's hum is at {mains:g} Hz: read as the record's own")


def check_fn(rec: Record, fn: float, what: str, fix: str) -> None:
    """A natural frequency the record can be read with: at least 4 natural
    periods long and 5 samples per period; else an error naming ``what``
    (the option or card that gave it) and what to ``fix``."""
    span = float(rec.t[-1] - rec.t[0])
    if fn * span < 4:
        _fail(f"{what}: the record ({span:.4g} s) spans fewer than 4 natural periods; check {fix} (and the time "
              f"column's unit)")
    if fn * rec.dt > 0.2:
        _fail(f"{what}: the record has only {1 / (fn * rec.dt):.3g} samples per natural period; at least 5 are "
              f"needed")


def record_from_trc_deck(path, v0: float | None) -> tuple[Record, float]:
    """A thesis-style TRC deck (App. 7) as a record: the calibrated readings
    T, X, XN (s, mm, mm; XN becomes y) resampled linearly onto an even grid
    at the median reading interval.  Returns the record and the natural
    frequency the deck gives (OMNH, rad/s, in Hz)."""
    from lieng.programs import read_deck

    deck = read_deck(path, program="trc")
    t, x, xn = deck.calibrated()
    if np.any(np.diff(t) <= 0):
        _fail(f"{path}: the readings' times do not increase (NT): cannot be resampled")
    if v0 is None:
        _fail(f"{path}: a TRC deck does not give the drive velocity: --v0 is needed")
    v0 = _with_units(None, v0, None, [])[1]
    _check_v0(v0)
    notes = []
    y = xn if np.any(xn != 0) else None
    rec = _regularise(path, t, {"x": x, "y": y, "v0": None, "pos": None}, notes)
    if rec["t"].size < MIN_SAMPLES:
        _fail(f"{path}: {rec['t'].size} samples after resampling: too short for stick-slip analysis")
    omnh = abs(deck.omnh)
    fn = omnh / (2 * math.pi) if math.isfinite(omnh) and omnh > 0 else None
    out = Record(t=rec["t"], x=rec["x"], vd=np.full_like(rec["t"], float(v0)), y=rec["y"], source=str(path),
                 notes=notes, fn_hint=fn)
    return out, fn
