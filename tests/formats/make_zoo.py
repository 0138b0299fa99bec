"""Write a zoo of stick-slip record files in many export styles + truth.json.

Written by a helper session that had not read lieng's code (stop 68), to test
whether ``lieng diagnose`` reads records as real laboratory software exports
them: LabVIEW .lvm, German Excel CSV, metadata blocks, unit rows, clock and
date-time stamps, sample indices with a stated rate, COF with a load, kN, gf,
kgf, inches, rotary torque and angle, DAQ channel names, quoted cells with
digit grouping, footers, missing cells, .npz/.mat/.xlsx, and the real records
of ``../shared/data`` cut or converted.  ``truth.json`` holds each file's
description, the options a user would pass, the true slip drop (mm of spring
extension, or mrad) and what the author expected: ``read``, ``refuse`` or
either.

Run: python tests/formats/make_zoo.py OUTDIR [DATA]   (DATA: the shared data
folder, default ../shared/data beside the repository)
"""
import json, os, sys, io, zipfile, datetime, shutil
import numpy as np
import scipy.io as sio
from scipy.ndimage import uniform_filter1d
from scipy.signal import find_peaks

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from sim import simulate, truth_drops

OUT = os.path.abspath(sys.argv[1]) if len(sys.argv) > 1 else os.path.join(HERE, "files")
if os.path.isdir(OUT):
    shutil.rmtree(OUT)
os.makedirs(OUT)
DATA = sys.argv[2] if len(sys.argv) > 2 else os.path.join(HERE, "..", "..", "..", "shared", "data")
G = 9.80665

truth = {}


def path(name):
    return os.path.join(OUT, name)


def add(name, desc, opts, drop_N=None, k=None, drop_mm=None, nslips=None, fn=None, v0=None,
        expect="read", note=""):
    if drop_mm is None and drop_N is not None and k is not None:
        drop_mm = drop_N / k * 1000.0
    truth[name] = dict(format=desc, options=opts, drop_N=drop_N, stiffness_N_m=k, drop_mm=drop_mm,
                       n_slips=nslips, fn_hz=fn, v0_mm_s=v0, expect=expect, note=note)


# ---------------------------------------------------------------- simulations
SETS = {
    # bench rig, 0.5 kg slider, 2 N/mm spring, 1 mm/s, 10 N load, 500 Hz
    "S1": dict(m=0.5, k=2000.0, v0=1.0e-3, N=10.0, mus=0.40, muk=0.30, zeta=0.02, fs=500.0, ncyc=25, seed=1),
    # stiffer rig, 5 N/mm, 0.5 mm/s, 20 N, 1 kHz
    "S2": dict(m=0.2, k=5000.0, v0=0.5e-3, N=20.0, mus=0.35, muk=0.28, zeta=0.03, fs=1000.0, ncyc=20, seed=2),
    # small rig, 0.5 N/mm, 0.2 mm/s, 1 N load, 400 Hz
    "S4": dict(m=0.05, k=500.0, v0=0.2e-3, N=1.0, mus=0.50, muk=0.40, zeta=0.02, fs=400.0, ncyc=15, seed=4),
    # rotary: J=2e-3 kg m2, 5 N.m/rad, 2 deg/s, friction torque 0.5/0.4 N.m  (N=1 so mu = torque)
    "S3": dict(m=2e-3, k=5.0, v0=np.deg2rad(2.0), N=1.0, mus=0.50, muk=0.40, zeta=0.02, fs=300.0, ncyc=18, seed=3),
}
SIM = {}
for key, p in SETS.items():
    t, F, x, pos, drive, Fc = simulate(**p)
    dN, ns = truth_drops(t, Fc)
    fn = np.sqrt(p["k"] / p["m"]) / (2 * np.pi)
    SIM[key] = dict(t=t, F=F, x=x, drive=drive, dN=dN, ns=ns, fn=fn, p=p,
                    v0=p["v0"] * 1000.0)
    print(key, "n=%d drop=%.4g N slips=%d fn=%.3f Hz" % (len(t), dN, ns, fn))


def simtruth(key, name, desc, opts, expect="read", note="", drop_mm=None, v0=None):
    s = SIM[key]
    add(name, desc, opts, drop_N=s["dN"], k=s["p"]["k"], nslips=s["ns"], fn=s["fn"],
        v0=s["v0"] if v0 is None else v0, expect=expect, note=note, drop_mm=drop_mm)


rng = np.random.default_rng(7)
S1, S2, S3, S4 = SIM["S1"], SIM["S2"], SIM["S3"], SIM["S4"]


def w(name, text, encoding="utf-8", newline="\n", bom=False):
    with open(path(name), "w", encoding=("utf-8-sig" if bom else encoding), newline=newline) as f:
        f.write(text)


def normal_load(s, rel=0.003):
    return s["p"]["N"] * (1 + rel * rng.standard_normal(len(s["t"])))


# 1 plain csv t,x (mm)
t, x = S1["t"], S1["x"] * 1000
w("s1_plain_tx.csv", "t,x\n" + "".join("%.4f,%.6f\n" % r for r in zip(t, x)))
simtruth("S1", "s1_plain_tx.csv", "plain CSV t,x (s, mm) as the help describes", ["--v0", "1"])

# 2 LabVIEW lvm, X column, two channels (friction force, drive position), one header per file
s = S2
n = len(s["t"])
hdr = ("LabVIEW Measurement\t\nWriter_Version\t2\nReader_Version\t2\nSeparator\tTab\nDecimal_Separator\t.\n"
       "Multiple_Headers\tNo\nX_Columns\tOne\nTime_Pref\tRelative\nOperator\ttribolab\n"
       "Date\t2025/03/04\nTime\t14:22:05.5123456789\n***End_of_Header***\t\n\n"
       "Channels\t2\t\t\nSamples\t%d\t%d\t\nDate\t2025/03/04\t2025/03/04\t\nTime\t14:22:05.5123456789\t14:22:05.5123456789\t\n"
       "Y_Unit_Label\tN\tmm\t\nX_Dimension\tTime\tTime\t\nX0\t0.0000000000000000E+0\t0.0000000000000000E+0\t\n"
       "Delta_X\t%.6f\t%.6f\t\n***End_of_Header***\t\t\t\nX_Value\tFriction Force\tDrive Position\tComment\n"
       % (n, n, 1 / s["p"]["fs"], 1 / s["p"]["fs"]))
body = "".join("%.6f\t%.6f\t%.6f\n" % (a, b, c) for a, b, c in zip(s["t"], s["F"], s["drive"] * 1000 + 12.5))
w("s2_labview_xcol.lvm", hdr + body, newline="\r\n")
simtruth("S2", "s2_labview_xcol.lvm", "LabVIEW .lvm (Writer 2), X_Value column, 'Friction Force' N + 'Drive Position' mm, CRLF",
         ["--stiffness", "5000"])

# 3 LabVIEW lvm without X column, DAQ channel names (Dev1/ai0 = force in N), Delta_X only
s = S1
hdr = ("LabVIEW Measurement\t\nWriter_Version\t2\nReader_Version\t2\nSeparator\tTab\nDecimal_Separator\t.\n"
       "Multiple_Headers\tNo\nX_Columns\tNo\nTime_Pref\tAbsolute\nOperator\tlab\n"
       "Date\t2025/03/04\nTime\t09:10:11.25\n***End_of_Header***\t\n\n"
       "Channels\t1\t\nSamples\t%d\t\nDate\t2025/03/04\t\nTime\t09:10:11.25\t\n"
       "Y_Unit_Label\tN\t\nX_Dimension\tTime\t\nX0\t3.7800000000000000E+9\t\n"
       "Delta_X\t%.6f\t\n***End_of_Header***\t\t\nDev1/ai0\tComment\n" % (len(s["t"]), 1 / s["p"]["fs"]))
w("s1_labview_noX_dev1ai0.lvm", hdr + "".join("%.6f\n" % v for v in s["F"]))
simtruth("S1", "s1_labview_noX_dev1ai0.lvm",
         ".lvm, X_Columns No (only Delta_X), channel 'Dev1/ai0' with Y_Unit_Label N, absolute X0",
         ["--v0", "1", "--stiffness", "2000"], note="the only channel is the force (unit N in header)")

# 4 Excel (German) CSV: BOM, ';', decimal comma, CRLF, units after slash, extra drive-position column
s = S1
lines = ["Zeit/s;Reibkraft/N;Normalkraft/N;Weg/mm"]
for a, b, c, d in zip(s["t"], s["F"], normal_load(s), s["drive"] * 1000):
    lines.append(("%.4f;%.5f;%.4f;%.5f" % (a, b, c, d)).replace(".", ","))
w("s1_excel_de_bom_semicolon.csv", "\r\n".join(lines) + "\r\n", bom=True, newline="")
simtruth("S1", "s1_excel_de_bom_semicolon.csv",
         "Excel-DE CSV: UTF-8 BOM, ';', decimal comma, CRLF, 'Zeit/s;Reibkraft/N;Normalkraft/N;Weg/mm'",
         ["--stiffness", "2000"])

# 5 long free-text metadata block before the table
s = S1
meta = """Tribometer XY-200 test report
Operator: J. Smith
Date: 04.03.2025 14:22
Sample: PTFE block on polished steel, 10x10 mm
Normal load: 10 N
Spring stiffness: 2 N/mm
Sliding speed: 1 mm/s
Temperature: 23.1 C, RH 41 %
Notes: run-in 3 strokes before recording, lubricant none; see lab book p. 42.
Calibration file: cal_2025-02-11.cfg

"""
tab = "Time (s)\tFriction Force (N)\n" + "".join("%.4f\t%.5f\n" % r for r in zip(s["t"], s["F"]))
w("s1_metadata_block.txt", meta + tab)
simtruth("S1", "s1_metadata_block.txt", "free-text metadata block (no '#') then TAB table 'Time (s)','Friction Force (N)'",
         ["--v0", "1", "--stiffness", "2000"])

# 6 units in a separate second row, forces in mN
s = S1
lines = ["Time,Friction,Normal load", "s,mN,N"]
lines += ["%.4f,%.2f,%.4f" % r for r in zip(s["t"], s["F"] * 1e3, normal_load(s))]
w("s1_unitsrow_mN.csv", "\n".join(lines) + "\n")
simtruth("S1", "s1_unitsrow_mN.csv", "CSV, units in a 2nd row (s, mN, N)", ["--v0", "1", "--stiffness", "2000"])

# 7 clock time HH:MM:SS.fff
s = S1
t0 = datetime.datetime(2025, 3, 4, 14, 59, 58, 500000)
lines = ["Time,Force [N]"]
for a, b in zip(s["t"], s["F"]):
    tt = t0 + datetime.timedelta(seconds=float(a))
    lines.append("%s,%.5f" % (tt.strftime("%H:%M:%S.%f")[:-3], b))
w("s1_clock_time.csv", "\n".join(lines) + "\n")
simtruth("S1", "s1_clock_time.csv", "CSV, time as clock HH:MM:SS.fff (crosses 15:00:00)",
         ["--v0", "1", "--stiffness", "2000"])

# 8 ISO date-time stamps, S2, tab
s = S2
t0 = datetime.datetime(2025, 3, 4, 23, 59, 50)
lines = ["Timestamp\tFriction force [N]\tNormal force [N]"]
for a, b, c in zip(s["t"], s["F"], normal_load(s)):
    tt = t0 + datetime.timedelta(seconds=float(a))
    lines.append("%s\t%.5f\t%.4f" % (tt.strftime("%Y-%m-%d %H:%M:%S.%f")[:-3], b, c))
w("s2_datetime_stamps.txt", "\n".join(lines) + "\n")
simtruth("S2", "s2_datetime_stamps.txt", "TAB, 'YYYY-MM-DD HH:MM:SS.fff' stamps crossing midnight",
         ["--v0", "0.5", "--stiffness", "5000"])

# 9 sample index only, rate in header
s = S1
lines = ["# DAQ export", "# Sample rate: 500 Hz", "Sample,Force [N]"]
lines += ["%d,%.5f" % (i, b) for i, b in enumerate(s["F"])]
w("s1_index_rate.csv", "\n".join(lines) + "\n")
simtruth("S1", "s1_index_rate.csv", "CSV, 'Sample' index column + force, rate only in a # header",
         ["--rate", "500", "--v0", "1", "--stiffness", "2000"])

# 10 COF + normal load column
s = S1
Nl = normal_load(s)
lines = ["Time [s],COF,Normal Load [N]"]
lines += ["%.4f,%.5f,%.4f" % (a, b / c, c) for a, b, c in zip(s["t"], s["F"], Nl)]
w("s1_cof_with_load.csv", "\n".join(lines) + "\n")
simtruth("S1", "s1_cof_with_load.csv", "CSV, COF column + 'Normal Load [N]'", ["--v0", "1", "--stiffness", "2000"])

# 11 COF only, load only in metadata
s = S1
lines = ["Test: pin-on-flat", "Load: 10 N", "", "Time [s],mu"]
lines += ["%.4f,%.5f" % (a, b / 10.0) for a, b in zip(s["t"], s["F"])]
w("s1_mu_only_load_in_header.csv", "\n".join(lines) + "\n")
simtruth("S1", "s1_mu_only_load_in_header.csv", "CSV, 'mu' only, load (10 N) only in free-text header",
         ["--v0", "1", "--stiffness", "2000"], expect="read-or-refuse",
         note="no N column and no option for the load: true force = mu*10 N; reading mu as N would give drop 10x too small")

# 12 kN
s = S1
lines = ["Time [s],Force [kN],Position [mm]"]
lines += ["%.4f,%.8f,%.5f" % (a, b / 1000, c) for a, b, c in zip(s["t"], s["F"], s["drive"] * 1000 + 100)]
w("s1_force_kN_position.csv", "\n".join(lines) + "\n")
simtruth("S1", "s1_force_kN_position.csv", "CSV, 'Force [kN]' + drive 'Position [mm]'", ["--stiffness", "2000"])

# 13 uN force, um drive displacement, TAB
s = S4
lines = ["Time [s]\tNormal [uN]\tPosition [um]\tFriction [uN]"]
lines += ["%.4f\t%.1f\t%.3f\t%.1f" % (a, c * 1e6, d * 1e6, b * 1e6)
          for a, b, c, d in zip(s["t"], s["F"], normal_load(s), s["drive"])]
w("s4_uN_um_tab.txt", "\n".join(lines) + "\n")
simtruth("S4", "s4_uN_um_tab.txt", "TAB, tribometer style: Normal [uN], Position [um], Friction [uN]",
         ["--stiffness", "500"])

# 14 gf
s = S4
lines = ["Time (s),Tangential force (gf)"]
lines += ["%.4f,%.3f" % (a, b / G * 1000) for a, b in zip(s["t"], s["F"])]
w("s4_force_gf.csv", "\n".join(lines) + "\n")
simtruth("S4", "s4_force_gf.csv", "CSV, force in gram-force (gf)", ["--v0", "0.2", "--stiffness", "500"])

# 15 kgf
lines = ["Time (s),Load (kgf),Friction (kgf)"]
lines += ["%.4f,%.5f,%.6f" % (a, c / G, b / G) for a, b, c in zip(s["t"], s["F"], normal_load(s))]
w("s4_force_kgf.csv", "\n".join(lines) + "\n")
simtruth("S4", "s4_force_kgf.csv", "CSV, Load and Friction in kgf (load column first)",
         ["--v0", "0.2", "--stiffness", "500"])

# 16 inches: spring extension in inches
lines = ["Time (s),Extension (in)"]
lines += ["%.4f,%.7f" % (a, b / 0.0254) for a, b in zip(s["t"], s["x"])]
w("s4_extension_inch.csv", "\n".join(lines) + "\n")
simtruth("S4", "s4_extension_inch.csv", "CSV, spring extension in inches", ["--v0", "0.2"])

# 17 rotary torque + angle (deg)
s = S3
lines = ["Time (s),Torque (N·m),Angle (deg)"]
lines += ["%.4f,%.6f,%.5f" % (a, b, np.rad2deg(d)) for a, b, d in zip(s["t"], s["F"], s["drive"])]
w("s3_rotary_torque_angle_deg.csv", "\n".join(lines) + "\n", encoding="utf-8")
add("s3_rotary_torque_angle_deg.csv", "rotary: Torque (N·m) + drive Angle (deg)", ["--stiffness", "5 N·m/rad"],
    drop_N=s["dN"], k=5.0, drop_mm=1000 * s["dN"] / 5.0, nslips=s["ns"], fn=s["fn"], v0=2.0,
    note="drop_mm holds the twist drop in mrad (the tool's units.x for rotary records) = %.4g deg; drop torque %.4g N·m; v0 2 deg/s" % (np.rad2deg(s["dN"] / 5.0), s["dN"]))

# 18 rotary torque only (rad)
lines = ["Time [s],Torque [N.m]"]
lines += ["%.4f,%.6f" % (a, b) for a, b in zip(s["t"], s["F"])]
w("s3_rotary_torque_only.csv", "\n".join(lines) + "\n")
add("s3_rotary_torque_only.csv", "rotary: Torque [N.m] only, drive speed given as deg/s",
    ["--v0", "2 deg/s", "--stiffness", "5 N·m/rad"],
    drop_N=s["dN"], k=5.0, drop_mm=1000 * s["dN"] / 5.0, nslips=s["ns"], fn=s["fn"], v0=np.deg2rad(2.0),
    note="drop_mm holds the twist drop in mrad (the tool's units.x) = %.4g rad" % (s["dN"] / 5.0))

# 19 DAQ channel names Dev1/ai0, Dev1/ai1 (force N, load N) -- meaning only the user knows
s = S1
lines = ["Time,Dev1/ai0,Dev1/ai1"]
lines += ["%.4f,%.5f,%.4f" % (a, b, c) for a, b, c in zip(s["t"], s["F"], normal_load(s))]
w("s1_daq_dev1_ai.csv", "\n".join(lines) + "\n")
simtruth("S1", "s1_daq_dev1_ai.csv", "CSV, DAQ names 'Time,Dev1/ai0,Dev1/ai1' (ai0 = friction N, ai1 = load N)",
         ["--v0", "1", "--stiffness", "2000"], expect="read-or-refuse",
         note="no unit and no meaning in header; no --help option to map columns")

# 20 Channel (V) names -- volts from the amplifier, 0.5 V/N
lines = ["Time (s),CH1 (V),CH2 (V)"]
lines += ["%.4f,%.5f,%.4f" % (a, b * 0.5, c * 0.1) for a, b, c in zip(s["t"], s["F"], normal_load(s))]
w("s1_channels_volts.csv", "\n".join(lines) + "\n")
simtruth("S1", "s1_channels_volts.csv", "CSV, 'CH1 (V),CH2 (V)' raw volts (CH1 = 0.5 V/N friction)",
         ["--v0", "1", "--stiffness", "2000"], expect="refuse",
         note="volts cannot be read as force without a calibration; a refusal should say what to do")

# 21 CRLF + trailing delimiters
lines = ["Time [s],Force [N],"]
lines += ["%.4f,%.5f," % (a, b) for a, b in zip(s["t"], s["F"])]
w("s1_crlf_trailing_delim.csv", "\r\n".join(lines) + "\r\n", newline="")
simtruth("S1", "s1_crlf_trailing_delim.csv", "CSV, CRLF, trailing delimiter on every row",
         ["--v0", "1", "--stiffness", "2000"])

# 22 thousands separators, quoted, time in ms, force in mN
lines = ['"Time [ms]","Friction [mN]","Normal [mN]"']
lines += ['"{:,.1f}","{:,.2f}","{:,.1f}"'.format(a * 1000, b * 1000, c * 1000)
          for a, b, c in zip(s["t"], s["F"], normal_load(s))]
w("s1_thousands_sep_ms_mN.csv", "\n".join(lines) + "\n")
simtruth("S1", "s1_thousands_sep_ms_mN.csv", "CSV, all fields quoted, thousands separators '12,345.0', ms and mN",
         ["--v0", "1", "--stiffness", "2000"])

# 23 footer with summary lines
lines = ["Time [s],Friction [N],Normal [N]"]
lines += ["%.4f,%.5f,%.4f" % (a, b, c) for a, b, c in zip(s["t"], s["F"], normal_load(s))]
lines += ["", "Summary", "Mean friction [N],%.4f" % s["F"].mean(), "Max friction [N],%.4f" % s["F"].max(),
          "Test duration [s],%.2f" % s["t"][-1], "End of test"]
w("s1_footer_summary.csv", "\n".join(lines) + "\n")
simtruth("S1", "s1_footer_summary.csv", "CSV with a summary footer after the data",
         ["--v0", "1", "--stiffness", "2000"])

# 24 NaN / empty cells
F = ["%.5f" % v for v in s["F"]]
Ns = ["%.4f" % v for v in normal_load(s)]
idx = rng.choice(len(F), 40, replace=False)
for j, i in enumerate(idx):
    if j % 3 == 0:
        F[i] = "NaN"
    elif j % 3 == 1:
        F[i] = ""
    else:
        Ns[i] = ""
lines = ["Time [s],Friction [N],Normal [N]"] + ["%.4f,%s,%s" % (a, b, c) for a, b, c in zip(s["t"], F, Ns)]
w("s1_nan_empty_cells.csv", "\n".join(lines) + "\n")
simtruth("S1", "s1_nan_empty_cells.csv", "CSV with 40 NaN/empty cells", ["--v0", "1", "--stiffness", "2000"])

# 25 reordered + extra columns
lines = ["Friction [N],Temperature [C],Time [s],Humidity [%],Trigger,Normal [N]"]
T = 23 + 0.01 * np.cumsum(rng.standard_normal(len(s["t"])))
lines += ["%.5f,%.2f,%.4f,%.1f,%d,%.4f" % (b, tc, a, 41.0 + 0.1 * np.sin(a), int(a > 2.0), c)
          for a, b, c, tc in zip(s["t"], s["F"], normal_load(s), T)]
w("s1_reordered_extra_cols.csv", "\n".join(lines) + "\n")
simtruth("S1", "s1_reordered_extra_cols.csv", "CSV, columns reordered (force first), + Temperature, Humidity, Trigger",
         ["--v0", "1", "--stiffness", "2000"])

# 26 tab-separated with quoted headers
lines = ['"Time [s]"\t"Friction Force [N]"\t"Normal Force [N]"']
lines += ["%.4f\t%.5f\t%.4f" % (a, b, c) for a, b, c in zip(s["t"], s["F"], normal_load(s))]
w("s1_tab_quoted_headers.txt", "\n".join(lines) + "\n")
simtruth("S1", "s1_tab_quoted_headers.txt", "TAB, quoted header names", ["--v0", "1", "--stiffness", "2000"])

# 27 whitespace fixed width, S2, units in parentheses glued, extension in mm
s = S2
lines = ["%12s%14s%14s" % ("Time(s)", "Ext(mm)", "Load(N)")]
lines += ["%12.4f%14.6f%14.4f" % (a, b * 1000, c) for a, b, c in zip(s["t"], s["x"], normal_load(s))]
w("s2_fixed_width.dat", "\n".join(lines) + "\n")
simtruth("S2", "s2_fixed_width.dat", "fixed-width whitespace, 'Time(s) Ext(mm) Load(N)' (spring extension)",
         ["--v0", "0.5"], note="Ext = spring extension in mm; name not t/x")

# 28 npz with other variable names
s = S1
np.savez(path("s1_other_names.npz"), time_s=s["t"], friction_force_N=s["F"], normal_force_N=normal_load(s),
         fs=np.array(500.0))
simtruth("S1", "s1_other_names.npz", ".npz with 'time_s', 'friction_force_N', 'normal_force_N', 'fs'",
         ["--v0", "1", "--stiffness", "2000"], expect="read-or-refuse")

# 29 mat with other variable names (column vectors, as MATLAB saves)
sio.savemat(path("s1_other_names.mat"), {"Time": s["t"][:, None], "Friction": s["F"][:, None],
                                         "Normal": normal_load(s)[:, None]})
simtruth("S1", "s1_other_names.mat", ".mat v5 with 'Time','Friction','Normal' (N x 1)",
         ["--v0", "1", "--stiffness", "2000"], expect="read-or-refuse")

# 30 mat holding one N x 3 matrix 'data' (very common)
sio.savemat(path("s2_matrix_data.mat"), {"data": np.c_[S2["t"], S2["F"], normal_load(S2)],
                                         "fs": 1000.0})
simtruth("S2", "s2_matrix_data.mat", ".mat v5 with a single N x 3 matrix 'data' [t F N]",
         ["--v0", "0.5", "--stiffness", "5000"], expect="read-or-refuse")

# 31 hand-made xlsx (openpyxl not installed here): 2 header rows, numbers
def col(i):
    return "ABCDEFGHIJ"[i]


def write_xlsx(fn, rows):
    sheet = io.StringIO()
    sheet.write('<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n'
                '<worksheet xmlns="http://schemas.openxmlformats.org/spreadsheetml/2006/main"><sheetData>')
    for r, row in enumerate(rows, 1):
        sheet.write('<row r="%d">' % r)
        for c, v in enumerate(row):
            ref = "%s%d" % (col(c), r)
            if isinstance(v, str):
                sheet.write('<c r="%s" t="inlineStr"><is><t>%s</t></is></c>' % (ref, v))
            else:
                sheet.write('<c r="%s"><v>%r</v></c>' % (ref, float(v)))
        sheet.write("</row>")
    sheet.write("</sheetData></worksheet>")
    with zipfile.ZipFile(fn, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("[Content_Types].xml",
                   '<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">'
                   '<Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>'
                   '<Default Extension="xml" ContentType="application/xml"/>'
                   '<Override PartName="/xl/workbook.xml" ContentType="application/vnd.openxmlformats-officedocument.spreadsheetml.sheet.main+xml"/>'
                   '<Override PartName="/xl/worksheets/sheet1.xml" ContentType="application/vnd.openxmlformats-officedocument.spreadsheetml.worksheet+xml"/>'
                   '</Types>')
        z.writestr("_rels/.rels",
                   '<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">'
                   '<Relationship Id="rId1" Type="http://schemas.openxmlformats.org/officeDocument/2006/relationships/officeDocument" Target="xl/workbook.xml"/></Relationships>')
        z.writestr("xl/workbook.xml",
                   '<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n<workbook xmlns="http://schemas.openxmlformats.org/spreadsheetml/2006/main" '
                   'xmlns:r="http://schemas.openxmlformats.org/officeDocument/2006/relationships"><sheets>'
                   '<sheet name="Data" sheetId="1" r:id="rId1"/></sheets></workbook>')
        z.writestr("xl/_rels/workbook.xml.rels",
                   '<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">'
                   '<Relationship Id="rId1" Type="http://schemas.openxmlformats.org/officeDocument/2006/relationships/worksheet" Target="worksheets/sheet1.xml"/></Relationships>')
        z.writestr("xl/worksheets/sheet1.xml", sheet.getvalue())


s = S1
rows = [["Time", "Friction force", "Normal force"], ["s", "N", "N"]]
rows += [[a, b, c] for a, b, c in zip(s["t"], s["F"], normal_load(s))]
write_xlsx(path("s1_handmade.xlsx"), rows)
simtruth("S1", "s1_handmade.xlsx", ".xlsx (hand-written OOXML, inline strings, units row); openpyxl absent in venv",
         ["--v0", "1", "--stiffness", "2000"], expect="read-or-refuse",
         note="a refusal should say which package to install")

# 32 should refuse: no time column, no rate
s = S1
w("refuse_no_time_no_rate.csv", "Force [N]\n" + "".join("%.5f\n" % v for v in s["F"]))
simtruth("S1", "refuse_no_time_no_rate.csv", "CSV, only 'Force [N]', no time and no --rate",
         ["--v0", "1", "--stiffness", "2000"], expect="refuse")

# 33 should refuse: single bare column
w("refuse_single_column.txt", "".join("%.5f\n" % v for v in s["F"]))
simtruth("S1", "refuse_single_column.txt", "single bare numeric column, no header", ["--v0", "1"], expect="refuse")

# ---------------------------------------------------------------- real records
m, kc = 0.0307, 168.0
fn_c = np.sqrt(kc / m) / (2 * np.pi)


def colas(v):
    d = sio.loadmat(os.path.join(DATA, "colas2019", "k168Nm_v%d.mat" % v))
    return d["t"].ravel(), d["Fnorm"].ravel()


def colas_truth(t, Fn, prom=0.03):
    Fs = uniform_filter1d(Fn, 9)
    pk, _ = find_peaks(Fs, prominence=prom, distance=int(0.03 / 0.0005))
    drops = []
    for p in pk:
        seg = Fs[p:p + int(0.06 / 0.0005)]
        drops.append(Fs[p] - seg.min())
    drops = np.array(drops)
    return float(np.median(drops)) * m * G, len(pk), (np.percentile(drops, [25, 75]) * m * G / kc * 1000).round(4).tolist()


# 35 colas v42 cut to 100 s, t,x mm
t, Fn = colas(42)
sel = (t >= 100) & (t < 200)
x = Fn[sel] * m * G / kc * 1000
w("colas_v42_cut100s_tx.csv", "t [s],x [mm]\n" + "".join("%.4f,%.6f\n" % r for r in zip(t[sel], x)))
dN, ns, iqr = colas_truth(t[sel], Fn[sel])
add("colas_v42_cut100s_tx.csv", "real (Colas 2019, v=42 um/s), 100 s cut, converted to t,x mm",
    ["--v0", "0.042", "--fn", "%.3f" % fn_c], drop_N=dN, k=kc, nslips=ns, fn=fn_c, v0=0.042,
    note="real: slip sizes vary, IQR of drops %s mm; truth approximate" % iqr)

# 36 colas v1100, whitespace, t x
t, Fn = colas(1100)
x = Fn * m * G / kc * 1000
w("colas_v1100_tx_space.txt", "time x\n" + "".join("%.4f %.6f\n" % r for r in zip(t, x)))
dN, ns, iqr = colas_truth(t, Fn)
add("colas_v1100_tx_space.txt", "real (Colas 2019, v=1100 um/s), whitespace 'time x' (mm)", ["--v0", "1.1"],
    drop_N=dN, k=kc, nslips=ns, fn=fn_c, v0=1.1, note="real, irregular slips, IQR %s mm; truth approximate" % iqr)

# 37 colas v4300 as mu + N column (Fnorm = F/(mg) is a friction coefficient w.r.t. the weight)
t, Fn = colas(4300)
lines = ["Time [s],mu,N [N]"] + ["%.4f,%.6f,%.5f" % (a, b, m * G) for a, b in zip(t, Fn)]
w("colas_v4300_mu_N.csv", "\n".join(lines) + "\n")
dN, ns, iqr = colas_truth(t, Fn, prom=0.02)
add("colas_v4300_mu_N.csv", "real (Colas 2019, v=4300 um/s) as mu=Fnorm + N = m g column",
    ["--v0", "4.3", "--stiffness", "168"], drop_N=dN, k=kc, nslips=ns, fn=fn_c, v0=4.3,
    note="real, nearly sinusoidal oscillation (hardly stick-slip), IQR %s mm; truth approximate" % iqr)

# 38 colas v1100 original .mat (t, Fnorm) copied untouched
shutil.copy(os.path.join(DATA, "colas2019", "k168Nm_v1100.mat"), path("colas_v1100_original.mat"))
add("colas_v1100_original.mat", "real original .mat (t, Fnorm = F/(m g), dimensionless), untouched",
    ["--v0", "1.1", "--stiffness", "168"], drop_mm=truth["colas_v1100_tx_space.txt"]["drop_mm"],
    nslips=truth["colas_v1100_tx_space.txt"]["n_slips"], fn=fn_c, v0=1.1, expect="refuse",
    note="Fnorm has no unit the tool can know; reading it as N or mm is wrong; a refusal should say to convert")

# 39 colas v42 full, converted, npz t,x (751k samples, large)
t, Fn = colas(42)
np.savez(path("colas_v42_full_tx.npz"), t=t, x=Fn * m * G / kc * 1000)
dN, ns, iqr = colas_truth(t, Fn)
add("colas_v42_full_tx.npz", "real (Colas 2019, v=42 um/s), full 751k samples, .npz t,x (mm)",
    ["--v0", "0.042", "--fn", "%.3f" % fn_c], drop_N=dN, k=kc, nslips=ns, fn=fn_c, v0=0.042,
    note="large record; IQR %s mm" % iqr)

# 40 tribometer TAB file, untouched (reciprocating, not stick-slip)
shutil.copy(os.path.join(DATA, "frictionmodels_td2", "test_data_2.txt"), path("td2_tribometer_original.txt"))
add("td2_tribometer_original.txt", "real reciprocating micro-tribometer TAB file, untouched (uN, mm, 5 ms, gaps)",
    [], expect="refuse-or-no-stickslip",
    note="friction reverses with the stroke (+-2.5 N), dwells at the ends; no stick-slip slips; drive reverses")

# 41 tribometer, one forward stroke region cut, semicolon
a = np.loadtxt(os.path.join(DATA, "frictionmodels_td2", "test_data_2.txt"), skiprows=1)
sel = (a[:, 0] >= 20) & (a[:, 0] < 60)
lines = ["Time [s];Normal [uN];Position [mm];Friction [uN]"]
lines += ["%g;%g;%g;%g" % tuple(r) for r in a[sel]]
w("td2_tribometer_cut_20_60s.csv", "\n".join(lines) + "\n")
add("td2_tribometer_cut_20_60s.csv", "real tribometer, 20-60 s cut, ';'", ["--stiffness", "2 N/mm"],
    expect="refuse-or-no-stickslip", note="reciprocating; not stick-slip")

with open(os.path.join(OUT, "truth.json"), "w") as f:
    json.dump(truth, f, indent=1)
print(len(truth), "files")
