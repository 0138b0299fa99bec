"""Tables as labs write them: the variants of header, units, separators and
missing samples that loggers and spreadsheets produce are read to the same
numbers as a plain ``t [s],F [N]`` file (``lieng.io.table.read_table`` and
``lieng.diagnose.read_record``)."""

from __future__ import annotations

import numpy as np
import pytest

from lieng.diagnose import read_record
from lieng.errors import LiengInputError

T = np.round(np.arange(200) * 1e-3, 6)
F = np.round(0.5 + 0.1 * np.sin(2 * np.pi * 7.0 * T) + 0.02 * (np.arange(200) % 17) / 17, 6)
K = 2000.0  # N/m


def _rows(fmt, n=200):
    return "".join(fmt(T[i], F[i]) for i in range(n))


PLAIN = "t [s],F [N]\n" + _rows(lambda a, b: f"{a},{b}\n")
VARIANTS = {
    "parentheses": "Time (s),Friction force (N)\n" + _rows(lambda a, b: f"{a},{b}\n"),
    "quantity/unit (ISO 80000)": "time/s,force/N\n" + _rows(lambda a, b: f"{a},{b}\n"),
    "unit as the name's suffix": "time_s,force_N\n" + _rows(lambda a, b: f"{a},{b}\n"),
    "unit row under the header": "time,force\ns,N\n" + _rows(lambda a, b: f"{a},{b}\n"),
    "comment lines before the header": "# rig A\n% operator B\ntime [s],force [N]\n" + _rows(lambda a, b: f"{a},{b}\n"),
    "quoted header": '"time [s]","force [N]"\n' + _rows(lambda a, b: f"{a},{b}\n"),
    "decimal comma, semicolons": "time [s];force [N]\n" + _rows(lambda a, b: f"{a};{b}\n".replace(".", ",")),
    "decimal comma, TABs": "time [s]\tforce [N]\n" + _rows(lambda a, b: f"{a}\t{b}\n".replace(".", ",")),
    "BOM and CRLF": "\ufefft [s],F [N]\r\n" + _rows(lambda a, b: f"{a},{b}\r\n"),
    "a separator at the end of each line": "t [s],F [N],\n" + _rows(lambda a, b: f"{a},{b},\n"),
    "Fx (tribometer axes)": "Time [s],Fx [N]\n" + _rows(lambda a, b: f"{a},{b}\n"),
    "an abbreviated friction force, whitespace": "Time_s Ffric_N Fn_N\n" + _rows(lambda a, b: f"{a} {b} 20.0\n"),
    "time in ms": "t [ms],F [mN]\n" + _rows(lambda a, b: f"{1000 * a:.3f},{1000 * b:.4f}\n"),
    "a nanotribometer's nN": "t [s],F [nN]\n" + _rows(lambda a, b: f"{a},{1e9 * b:.1f}\n"),
    "a Greek mu for micro (U+03BC)": "t [s],F [\u03bcN]\n" + _rows(lambda a, b: f"{a},{1e6 * b:.1f}\n"),
    "an instrument's metadata above the header": "Instrument: UMT-2\nOperator: A. B.\nSample rate,1000\n\n"
                                                 "t [s],F [N]\n" + _rows(lambda a, b: f"{a},{b}\n"),
    "metadata, then a unit row under the header": "Test\tstick-slip\nTime\tForce\ns\tN\n"
                                                  + _rows(lambda a, b: f"{a}\t{b}\n"),
    "whitespace, a comment, then a unit row under the header": "# rig A, sampled at 1 kHz\ntime F\ns N\n"
                                                               + _rows(lambda a, b: f"{a} {b}\n"),
    "whitespace, a unit row whose unit is a column's name": "# rig A\ntime F N\ns mN N\n"
                                                            + _rows(lambda a, b: f"{a} {1000 * b:.3f} 20.0\n"),
    "a status column of words, under a metadata line with a comma": "UMT-2 export, test 12\nt [s]\tF [N]\tstatus\n"
        + _rows(lambda a, b: f"{a}\t{b}\t" + ("run" if a < 0.1 else "") + "\n"),
    "units as the names' last part, time in ms": "Time_ms,Force_mN\n" + _rows(lambda a, b: f"{1000 * a:.3f},{1000 * b:.4f}\n"),
    "msec and gram-force": "Time (msec),Lateral Force (gf)\n" + _rows(lambda a, b: f"{1000 * a:.3f},{float(b) / 9.80665e-3!r}\n"),
    "a tangential load is the friction force": "Time [s],Tangential load [N]\n" + _rows(lambda a, b: f"{a},{b}\n"),
    "a logger's date-time stamps": "Timestamp,F [N]\n" + _rows(lambda a, b: f"2024-03-01 10:22:{1 + a:06.3f},{b}\n"),
    "ISO date-times with a T": "Date_Time;F [N]\n" + _rows(lambda a, b: f"2024-03-01T23:59:{58 + a:06.3f};{b}\n"),
    "day-first date-times": "Date/Time,F [N]\n" + _rows(lambda a, b: f"01/03/2024 10:22:{1 + a:06.3f},{b}\n"),
    "German date-times": "Zeit;F [N]\n" + _rows(lambda a, b: f"01.03.2024 9:22:{1 + a:06.3f};{b}\n".replace(".", ",")
                                              .replace(",", ".", 2)),
    "the time of day alone": "Time,F [N]\n" + _rows(lambda a, b: f"10:22:{1 + a:06.3f},{b}\n"),
    "the time of day through midnight": "Time,F [N]\n" + _rows(
        lambda a, b: f"{'23:59:59.9' if a < 0.1 else '00:00:00.0'}{int(round(1000 * a)) % 100:02d},{b}\n"),
    "a drive position logged on every tenth row": "t [s],F [N],position [mm]\n" + "".join(
        f"{T[i]},{F[i]}," + (f"{T[i]:.4f}" if i % 10 == 0 else "") + "\n" for i in range(200)),
    "a testing machine's pull test (its one force 'Load', the crosshead's 'Extension')":
        '"Time (s)","Extension (mm)","Load (N)"\n' + _rows(lambda a, b: f'"{a}","{a:.4f}","{b}"\n'),
    "a load cell is a force transducer": "Time [s],Load Cell [N]\n" + _rows(lambda a, b: f"{a},{b}\n"),
    "a catman export (a title, metadata, a channel name with a number in it, a unit row)":
        "catman Professional ASCII export\nFile: C:\\data\\clamp3.bin\nComment: dry steel\n\n"
        "Time  1 - default sample rate\tFriction force\tActuator\ns\tN\tmm\n"
        + _rows(lambda a, b: f"{a}\t{b}\t{a:.4f}\n"),
    "Spanish names": "Tiempo [s],Fuerza de fricci\u00f3n [N]\n" + _rows(lambda a, b: f"{a},{b}\n"),
    "Italian names, a decimal comma": "Tempo [s];Forza tangenziale [N]\n" + _rows(lambda a, b: f"{a};{b}\n"
                                                                                   .replace(".", ",")),
    "Portuguese names": "Tempo (s),For\u00e7a de atrito (N)\n" + _rows(lambda a, b: f"{a},{b}\n"),
    "semicolons, a decimal comma and a unit row under the header": "Time;Friction force\ns;N\n"
        + _rows(lambda a, b: f"{a};{b}\n".replace(".", ",")),
    "semicolons, a decimal comma, a unit row and a drive": "Time;Friction force;Actuator position\ns;N;mm\n"
        + _rows(lambda a, b: f"{a};{b};{a:.4f}\n".replace(".", ",")),
    "German date-times under 'Datum/Zeit' (one name, not a name over its unit)": "Datum/Zeit;F [N]\n" + _rows(
        lambda a, b: f"01.03.2024 09:22:{1 + a:06.3f};{b}\n".replace(".", ",").replace(",", ".", 2)),
    "an American date-time with AM/PM": "Date/Time,F [N]\n" + _rows(lambda a, b: f"3/1/2024 1:22:{1 + a:06.3f} PM,{b}\n"),
    "Origin's three header rows (names, units, comments)": "Time,Friction force\ns,N\n,run 3\n"
        + _rows(lambda a, b: f"{a},{b}\n"),
    "a fixed-width export, its names and units in two comment lines": "#         t           F\n#       [s]         [N]\n"
        + _rows(lambda a, b: f"{a:16.8E}{b:16.8E}\n"),
    "a comment header of names with units, under a comment line of column notes": "% sample rate 1000 Hz\n"
        "% columns: 1 Zeit (s), 2 Load Cell (N)\n% Zeit[s]  Load_Cell[N]\n" + _rows(lambda a, b: f"  {a:.6f}  {b}\n"),
    "an oscilloscope's metadata (a 'Label,FRICTION' line is no row of units) above its header":
        "Model,MDO3034\nVertical Units,N\nLabel,FRICTION\n\nTIME (s),CH1 Friction (N)\n"
        + _rows(lambda a, b: f"{a},{b}\n"),
    "a force in N as the name's last part, beside the normal one (F_N, Fn_N)": "t_s,F_N,Fn_N\n"
        + _rows(lambda a, b: f"{a},{b},20.0\n"),
    "a testing machine's 'Load' beside its 'Normal Load'": '"Time","Load","Normal Load"\n"(s)","(N)","(N)"\n'
        + _rows(lambda a, b: f'"{a}","{b}","20.0"\n'),
    "digit grouping by thousands in quoted cells, a decimal point (an English spreadsheet's export)":
        '"t [s]","F [uN]"\n' + _rows(lambda a, b: f'"{a}","{1e6 * b:,.1f}"\n'),
    "digit grouping by thousands, a decimal comma (a German spreadsheet's export)":
        "t [s];F [uN]\n" + _rows(lambda a, b: f"{a};".replace(".", ",")
                                 + f"{1e6 * b:,.1f}".replace(",", " ").replace(".", ",").replace(" ", ".") + "\n"),
    "a capstan's tensions: the spring's (the tight side's) the friction force, the tail's (the slack side's) "
    "the load": "Time [s];Spring tension [N];Tail tension [N]\n" + _rows(lambda a, b: f"{a};{b};7.5\n".replace(".", ",")),
    "a yarn tester's output and input tensions in cN": "Time [s],Output tension [cN],Input tension [cN]\n"
        + _rows(lambda a, b: f"{a},{100 * b:.4f},750.0\n"),
    "Chinese names and units (时间, 摩擦力 in 牛顿, 正压力)": "时间(秒),摩擦力(牛顿),正压力(牛顿)\n"
        + _rows(lambda a, b: f"{a},{b},10.0\n"),
    "Japanese names (時間, 摩擦力, 垂直荷重)": "時間[s],摩擦力[N],垂直荷重[N]\n" + _rows(lambda a, b: f"{a},{b},10.0\n"),
    "Dutch names": "Tijd (s);Wrijvingskracht (N);Normaalkracht (N)\n" + _rows(lambda a, b: f"{a};{b};10\n".replace(".", ",")),
    "Polish names": "Czas [s],Siła tarcia [N],Siła nacisku [N]\n" + _rows(lambda a, b: f"{a},{b},10.0\n"),
    "a German test machine's Prüfzeit": "Prüfzeit [s];Standardkraft [N]\n" + _rows(lambda a, b: f"{a};{b}\n".replace(".", ",")),
    "a film tester's force in grams": "Time (s),Force (g)\n" + _rows(lambda a, b: f"{a},{float(b) / 9.80665e-3!r}\n"),
    "W, the tribologist's normal load, beside Ft": "t (s),Ft (N),W (N)\n" + _rows(lambda a, b: f"{a},{b},10.0\n"),
    "a Bluehill channel's qualifier in parentheses, with a row of units": '"Time","Load","Tensile strain (Extension)"\n'
        '"(s)","(N)","(%)"\n' + _rows(lambda a, b: f'"{a}","{b}","0.0"\n'),
    "a logger's year-first date-times with slashes": "Date&Time,F [N]\n"
        + _rows(lambda a, b: f"2024/03/01 10:22:{1 + a:06.3f},{b}\n"),
    "a force in lb (a pound read as a pound-force on a force column)": "t [s],F [lb]\n"
        + _rows(lambda a, b: f"{a},{float(b) / 4.4482216152605!r}\n"),
    "an LVDT on the slider beside the force (the slider's position, not the extension)":
        "Time (s)\tFt (N)\tLVDT slider (mm)\tActuator (mm)\n"
        + _rows(lambda a, b: f"{a}\t{b}\t{3 + a - b / K * 1e3:.7f}\t{a:.4f}\n"),
}


def _lvm(multi=False, dec="."):
    """A LabVIEW measurement file (.lvm, writer version 2) as LabVIEW's
    Write To Measurement File writes it: a file header and a channel header,
    each ended by ***End_of_Header***, the channels' units in Y_Unit_Label,
    one X_Value column (or one per channel with X_Columns Multi), a trailing
    empty Comment column."""
    n = 2 if multi else 1
    head = ("LabVIEW Measurement\t\nWriter_Version\t2\nReader_Version\t2\nSeparator\tTab\n"
            f"Decimal_Separator\t{dec}\nMulti_Headings\tNo\nX_Columns\t{'Multi' if multi else 'One'}\n"
            "Time_Pref\tRelative\nOperator\tlab\nDate\t2026/11/27\nTime\t10:00:00.000\n***End_of_Header***\t\n\t\n"
            f"Channels\t{n}\t\nSamples\t200\t{'200' if multi else ''}\t\nY_Unit_Label\tN\t{'mm' if multi else ''}\t\n"
            "X_Dimension\tTime\tTime\t\nX0\t0.0000000000000000E+0\t0.0000000000000000E+0\t\n"
            "Delta_X\t0.001000\t0.001000\t\n***End_of_Header***\t\t\t\n")
    if multi:
        return head + "X_Value\tFriction\tX_Value\tStage\tComment\n" + _rows(
            lambda a, b: f"{a:.6f}\t{b}\t{a:.6f}\t{a:.6f}\n".replace(".", dec))
    return head + "X_Value\tFriction\tComment\n" + _rows(lambda a, b: f"{a:.6f}\t{b}\n".replace(".", dec))


def _lvm_segments(k=4):
    """A LabVIEW measurement file written a segment at a time (a channel
    header before each segment's rows, LabVIEW's default in a loop), its
    X_Value continuing from segment to segment."""
    whole = _lvm()
    head, rows = whole.split("X_Value\tFriction\tComment\n")
    block = head[head.index("Channels"):]
    body = rows.splitlines(keepends=True)
    n = len(body) // k
    out = head + "X_Value\tFriction\tComment\n" + "".join(body[:n])
    for j in range(1, k):
        out += block + "X_Value\tFriction\tComment\n" + "".join(body[j * n:(j + 1) * n if j < k - 1 else len(body)])
    return out


VARIANTS.update({"a LabVIEW measurement file (.lvm)": _lvm(),
                 "a LabVIEW measurement file written a segment at a time": _lvm_segments(),
                 "a LabVIEW measurement file, an X column per channel": _lvm(multi=True),
                 "a LabVIEW measurement file with a decimal comma": _lvm(dec=",")})


def _read(tmp_path, name, text):
    p = tmp_path / name
    p.write_bytes(text.encode("utf-8"))
    return read_record(p, v0=1.0, stiffness=K)


@pytest.mark.parametrize("what", sorted(VARIANTS))
def test_a_variant_reads_as_the_plain_file(tmp_path, what):
    ref = _read(tmp_path, "plain.csv", PLAIN)
    r = _read(tmp_path, "variant.csv", VARIANTS[what])
    assert r.t.size == ref.t.size
    np.testing.assert_allclose(r.t, ref.t, rtol=0, atol=1e-12)
    np.testing.assert_allclose(r.x, ref.x, rtol=1e-9, atol=1e-12)
    assert r.x[0] == pytest.approx(F[0] / K * 1e3)


def test_an_instruments_metadata_above_the_header_is_passed_over_and_said(tmp_path):
    r = _read(tmp_path, "pre.csv", VARIANTS["an instrument's metadata above the header"])
    assert any(n.startswith("3 lines of text above the header passed over") for n in r.notes)
    rows = PLAIN.splitlines(keepends=True)
    rows[1] = f"{T[0]},oops\n"                 # a word in the first data row is a bad row, not a header
    with pytest.raises(LiengInputError, match=r"line 2, column F: 'oops' is not a number"):
        _read(tmp_path, "bad1.csv", "".join(rows))


@pytest.mark.parametrize("cell", ["NaN", "", "nan", "NA"])
def test_a_missing_sample_is_left_out_and_said(tmp_path, cell):
    rows = PLAIN.splitlines(keepends=True)
    rows[51] = f"{T[50]},{cell}\n"
    r = _read(tmp_path, "gap.csv", "".join(rows))
    assert r.t.size == 200 and any("missing value" in n and "resampled" in n for n in r.notes)
    assert np.all(np.isfinite(r.x))
    # the missing sample is interpolated from its neighbours
    assert r.x[50] == pytest.approx(0.5 * (F[49] + F[51]) / K * 1e3, rel=1e-6)


def test_a_record_that_is_mostly_missing_is_refused(tmp_path):
    rows = PLAIN.splitlines(keepends=True)
    for i in range(1, 60):
        rows[i] = f"{T[i - 1]},NaN\n"
    with pytest.raises(LiengInputError, match="rows miss a value"):
        _read(tmp_path, "holes.csv", "".join(rows))


def test_a_word_where_a_number_belongs_is_still_named(tmp_path):
    rows = PLAIN.splitlines(keepends=True)
    rows[10] = f"{T[9]},oops\n"
    with pytest.raises(LiengInputError, match=r"line 11, column F: 'oops' is not a number"):
        _read(tmp_path, "bad.csv", "".join(rows))


def test_a_record_without_a_time_column_reads_with_its_sampling_rate(tmp_path):
    """Loggers that write the samples alone: with --rate the rows are evenly
    spaced samples (the same record as with its time column), said in the
    notes; without it the missing column and the option are named; with a
    time column --rate is ignored and said."""
    ref = _read(tmp_path, "plain.csv", PLAIN)
    p = tmp_path / "samples.csv"
    p.write_text("F [N]\n" + "".join(f"{b}\n" for b in F))
    r = read_record(p, v0=1.0, stiffness=K, rate=1000.0)
    np.testing.assert_allclose(r.t, ref.t, rtol=0, atol=1e-12)
    np.testing.assert_allclose(r.x, ref.x, rtol=1e-12)
    assert any("--rate 1000 Hz" in n for n in r.notes)
    with pytest.raises(LiengInputError, match="no time column .* give --rate"):
        read_record(p, v0=1.0, stiffness=K)
    with pytest.raises(LiengInputError, match="--rate 0: the sampling rate"):
        read_record(p, v0=1.0, stiffness=K, rate=0.0)
    q = tmp_path / "plain.csv"
    assert any("--rate ignored" in n for n in read_record(q, v0=1.0, stiffness=K, rate=50.0).notes)



@pytest.mark.parametrize("meta", ["# Sample rate: 1000 Hz\n", "Sample rate: 1 kHz\nOperator: A. N. Other\n",
                                  "Delta_X\t0.001\n", "# Sampling interval = 1 ms\n",
                                  "Sampling frequency (Hz);1000\n", "Scan rate,1000 S/s\n"])
def test_a_record_without_a_time_column_reads_the_rate_its_metadata_states(tmp_path, meta):
    """A one-channel logger's export: no time column, the sampling rate (or
    the interval) among the metadata lines above the header, which may be
    text or comments: read as with --rate (the same record), said with the
    line that states it; --rate overrides it; a rate written "1,000" (a
    thousands separator or a decimal comma?) is not guessed, and the
    refusal names its line."""
    ref = _read(tmp_path, "plain.csv", PLAIN)
    p = tmp_path / "samples.txt"
    p.write_text(meta + "F [N]\n" + "".join(f"{b}\n" for b in F))
    r = read_record(p, v0=1.0, stiffness=K)
    np.testing.assert_allclose(r.t, ref.t, rtol=0, atol=1e-12)
    np.testing.assert_allclose(r.x, ref.x, rtol=1e-12)
    assert any("that line 1 states" in n and "1000 Hz" in n for n in r.notes), r.notes
    r2 = read_record(p, v0=1.0, stiffness=K, rate=500.0)
    assert r2.dt == pytest.approx(2e-3) and any("--rate 500 Hz" in n for n in r2.notes)
    p.write_text("Sample rate: 1,000 Hz\nF [N]\n" + "".join(f"{b}\n" for b in F))
    with pytest.raises(LiengInputError, match=r"line 1 \('Sample rate: 1,000 Hz'\) states a rate that is not read: "
                                              r"it can be read two ways.*give --rate"):
        read_record(p, v0=1.0, stiffness=K)


def test_a_column_of_no_role_neither_refuses_nor_drops_rows(tmp_path):
    """A temperature column left empty, a comment column of words, a
    humidity column with gaps: none of them is read, so none refuses the
    record or drops a force sample (the empty column refused all 200 rows as
    missing; found by the black-box audit)."""
    ref = _read(tmp_path, "plain.csv", PLAIN)
    text = "t [s],F [N],Temperature [C],Comment,Humidity [%]\n" + "".join(
        f"{T[i]},{F[i]},,{'ok' if i % 2 else 'check grip'},{'' if i % 7 == 0 else 41.5}\n" for i in range(200))
    r = _read(tmp_path, "extra.csv", text)
    assert r.t.size == ref.t.size and not any("missing" in n for n in r.notes)
    np.testing.assert_allclose(r.x, ref.x, rtol=1e-12)


LONG_T = np.round(np.arange(5000) * 1e-3, 6).tolist()
LONG_F = np.round(0.5 + 0.1 * np.sin(2 * np.pi * 7.0 * np.array(LONG_T)), 6).tolist()


@pytest.mark.parametrize("sep,dec", [(",", "."), ("\t", ","), (" ", "."), (";", ",")])
def test_a_long_plain_table_reads_as_row_by_row(tmp_path, sep, dec, monkeypatch):
    """Long plain blocks are parsed at once by NumPy; the numbers, line numbers
    and units are those of the row-by-row reader (which the fast path is
    switched off to compare with)."""
    import lieng.io.table as table

    body = "".join(f"{a!r}{sep}{b!r}\n".replace(".", dec) if dec == "," else f"{a!r}{sep}{b!r}\n"
                   for a, b in zip(LONG_T, LONG_F))
    p = tmp_path / "long.txt"
    p.write_text(f"t [s]{sep}F [N]\n" + body.replace("\n", "\n\n", 3))
    fast = table.read_table(p, "t,F", missing="drop")
    monkeypatch.setattr(table, "_plain_block", lambda *a, **k: None)
    slow = table.read_table(p, "t,F", missing="drop")
    assert fast.names == slow.names and fast.units == slow.units and np.array_equal(fast.lines, slow.lines)
    for n in fast.names:
        assert np.array_equal(fast.columns[n], slow.columns[n])
    assert np.array_equal(fast.columns["F [N]" if "F [N]" in fast.names else fast.names[1]], LONG_F)


@pytest.mark.parametrize("bad,msg", [("abc", "line 4003, column"), ("inf", "not a finite number"),
                                     ("\u22122", None), ("1_0", "line 4003")])
def test_a_long_table_with_one_bad_cell_names_its_line(tmp_path, bad, msg):
    rows = [f"{a!r},{b!r}" for a, b in zip(LONG_T, LONG_F)]
    rows[4001] = f"{LONG_T[4001]!r},{bad}"
    p = tmp_path / "long.csv"
    p.write_text("t [s],F [N]\n" + "\n".join(rows) + "\n")
    from lieng.io.table import read_table

    if msg is None:                       # a typeset minus sign is a number
        assert read_table(p, "t,F").columns[read_table(p, "t,F").names[1]][4001] == -2.0
        return
    with pytest.raises(LiengInputError, match=msg):
        read_table(p, "t,F")


@pytest.mark.parametrize("stamp,rate", [(1e-3, 2000.0), (1.0, 100.0)])
def test_time_stamps_coarser_than_the_sampling_are_spread_evenly(tmp_path, stamp, rate):
    """A logger writing 1 ms stamps at 2 kHz (or whole seconds at 100 Hz):
    the stamps repeat; the samples are evenly spaced over the stamps' span
    (not refused as a time that repeats), and said so."""
    n = 3000
    tt = np.arange(n) / rate
    ff = 0.5 + 0.1 * np.sin(2 * np.pi * 3.0 * tt * 100 / rate)
    p = tmp_path / "stamps.csv"
    p.write_text("t [s],F [N]\n" + "".join(f"{np.floor(a / stamp) * stamp:.4f},{b:.6f}\n" for a, b in zip(tt, ff)))
    r = read_record(p, v0=1.0, stiffness=K)
    assert r.t.size == n
    np.testing.assert_allclose(np.diff(r.t), 1.0 / rate, rtol=0.02)
    assert any("time stamps repeat" in m for m in r.notes)


def test_a_time_that_stops_is_still_refused(tmp_path):
    """Repeats that are not a coarse stamp (the clock stands still for a
    stretch) name the line."""
    tt = np.arange(2000) * 1e-3
    tt[500:900] = tt[500]
    p = tmp_path / "stops.csv"
    p.write_text("t [s],F [N]\n" + "".join(f"{a:.4f},{0.5 + 0.1 * np.sin(40 * a):.6f}\n" for a in tt))
    with pytest.raises(LiengInputError, match="time repeats"):
        read_record(p, v0=1.0, stiffness=K)


def test_a_row_written_twice_is_dropped_and_said(tmp_path):
    """A logger that writes a row twice (the same time and the same reading
    in every column) gives the record without the copies, and a note names
    the first (this was refused: "time repeats", found by a black-box
    audit); a repeated time with another reading is no copy (a coarse stamp,
    or refused: :func:`test_a_time_that_stops_is_still_refused`)."""
    ref = _read(tmp_path, "plain.csv", PLAIN)
    rows = PLAIN.splitlines(keepends=True)
    dup = rows[:51] + [rows[50]] + rows[51:121] + [rows[120]] + rows[121:]
    p = tmp_path / "dup.csv"
    p.write_text("".join(dup))
    r = read_record(p, v0=1.0, stiffness=K)
    np.testing.assert_array_equal(r.x, ref.x)
    np.testing.assert_array_equal(r.t, ref.t)
    assert any("2 rows repeat the row before exactly" in n and "line 52" in n for n in r.notes), r.notes
    a, b = rows[50].rstrip("\n").split(",")
    q = tmp_path / "conflict.csv"
    q.write_text("".join(rows[:51] + [f"{a},{float(b) + 0.01}\n"] + rows[51:]))
    assert not any("repeat the row before exactly" in n for n in read_record(q, v0=1.0, stiffness=K).notes)


@pytest.mark.parametrize("kind", ["mat", "mat-row-vectors", "npz"])
def test_named_arrays_read_as_the_plain_file(tmp_path, kind):
    """A MATLAB file (as scipy.io.savemat writes v5) or a NumPy archive of
    named vectors reads as the table with those names; a variable of another
    length is passed over and said."""
    ref = _read(tmp_path, "plain.csv", PLAIN)
    p = tmp_path / ("rec.npz" if kind == "npz" else "rec.mat")
    data = {"t": T, "F": F, "k_spring": np.array([K])}
    if kind == "npz":
        np.savez(p, **data)
    else:
        import scipy.io

        scipy.io.savemat(p, data, oned_as="row" if kind == "mat-row-vectors" else "column")
    r = read_record(p, v0=1.0, stiffness=K)
    np.testing.assert_array_equal(r.t, ref.t)
    np.testing.assert_array_equal(r.x, ref.x)
    assert any("k_spring" in n and "passed over" in n for n in r.notes)


def test_an_array_files_missing_values_and_short_vectors_read_as_a_tables_do(tmp_path):
    """A NumPy archive with NaN in a vector leaves those samples out and
    says so, as a text table with empty cells does (it was refused); one
    whose force is shorter than its time names the force as passed over
    where it says no force was found (it said "no ... column in the
    header", of a file with no header; both found by a black-box audit)."""
    Fn = F.copy()
    Fn[[40, 41, 120]] = np.nan
    p = tmp_path / "nan.npz"
    np.savez(p, t=T, F=Fn)
    q = tmp_path / "nan.csv"
    q.write_text("t [s],F [N]\n" + "".join(f"{a},{'' if np.isnan(b) else b}\n" for a, b in zip(T, Fn)))
    r, ref = read_record(p, v0=1.0, stiffness=K), read_record(q, v0=1.0, stiffness=K)
    np.testing.assert_allclose(r.x, ref.x, rtol=1e-12)
    assert any("3 rows with a missing value" in n for n in r.notes)
    s = tmp_path / "short.npz"
    np.savez(s, t=T, F=F[:150])
    with pytest.raises(LiengInputError, match="among the variables .variable F passed over"):
        read_record(s, v0=1.0, stiffness=K)


@pytest.mark.parametrize("content,msg", [(b"MATLAB 7.3 MAT-file, Platform: GLNXA64" + bytes(200), "v7.3"),
                                         (b"not a mat file at all" * 10, "not a readable MATLAB file")])
def test_an_unreadable_mat_file_is_named(tmp_path, content, msg):
    p = tmp_path / "rec.mat"
    p.write_bytes(content)
    with pytest.raises(LiengInputError, match=msg):
        read_record(p, v0=1.0, stiffness=K)


def test_a_mat_file_of_a_matrix_alone_is_refused(tmp_path):
    import scipy.io

    p = tmp_path / "rec.mat"
    scipy.io.savemat(p, {"data": np.column_stack([T, F])})
    with pytest.raises(LiengInputError, match="no numeric vector"):
        read_record(p, v0=1.0, stiffness=K)


def test_a_displacement_beside_the_force_that_moves_one_way_is_the_drive(tmp_path):
    """A tribometer export with the stage's travel as `x [um]` beside the
    friction force: x only goes one way, so it is the drive's position (a
    black-box audit found it read as the spring's extension, the force
    ignored); a spring extension beside a force is still the extension."""
    v = 0.5                                        # mm/s
    pos_um = 1e3 * v * T
    p = tmp_path / "fx.csv"
    p.write_text("t [s],F [N],x [um]\n" + "".join(f"{a},{b},{c:.4f}\n" for a, b, c in zip(T, F, pos_um)))
    r = read_record(p, stiffness=K)
    np.testing.assert_allclose(r.x, F / K * 1e3, rtol=1e-9)
    assert np.median(r.vd) == pytest.approx(v, rel=0.02)
    assert any("moves one way" in n for n in r.notes)
    q = tmp_path / "fx2.csv"
    q.write_text("t [s],F [N],x [mm]\n" + "".join(f"{a},{b},{b / K * 1e3}\n" for a, b in zip(T, F)))
    r = read_record(q, v0=v, stiffness=K)
    assert not any("moves one way" in n for n in r.notes)


def _xlsx(path, rows, shared_strings=True):
    """A minimal Office Open XML workbook written by hand (zip + XML, as a
    spreadsheet saves one): header cells as shared strings (or inline), the
    numbers as stored, the worksheet reached through the workbook's
    relationships."""
    import zipfile

    strings = []

    def cell(ref, v):
        if isinstance(v, str):
            if shared_strings:
                strings.append(v)
                return f'<c r="{ref}" t="s"><v>{len(strings) - 1}</v></c>'
            return f'<c r="{ref}" t="inlineStr"><is><t>{v}</t></is></c>'
        return f'<c r="{ref}"><v>{v!r}</v></c>'

    body = "".join(f'<row r="{i + 1}">' + "".join(cell(f"{chr(65 + j)}{i + 1}", v) for j, v in enumerate(r)
                                                 if v is not None) + "</row>" for i, r in enumerate(rows))
    m = 'xmlns="http://schemas.openxmlformats.org/spreadsheetml/2006/main"'
    rel = 'xmlns:r="http://schemas.openxmlformats.org/officeDocument/2006/relationships"'
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("xl/workbook.xml", f'<workbook {m} {rel}><sheets><sheet name="Data" sheetId="1" r:id="rId7"/>'
                                      f'</sheets></workbook>')
        z.writestr("xl/_rels/workbook.xml.rels", '<Relationships xmlns="http://schemas.openxmlformats.org/package/'
                   '2006/relationships"><Relationship Id="rId7" Type="worksheet" Target="worksheets/data.xml"/>'
                   '</Relationships>')
        z.writestr("xl/worksheets/data.xml", f"<worksheet {m}><sheetData>{body}</sheetData></worksheet>")
        if shared_strings:
            z.writestr("xl/sharedStrings.xml", f"<sst {m}>" + "".join(f"<si><t>{s}</t></si>" for s in strings)
                       + "</sst>")


@pytest.mark.parametrize("shared", [True, False])
def test_a_spreadsheet_workbook_reads_as_the_plain_file(tmp_path, shared):
    """An .xlsx export (a tribometer's software, a spreadsheet): its first
    worksheet, with an instrument's line above the header and a blank cell
    in a comment column, reads to the same numbers as the CSV."""
    ref = _read(tmp_path, "plain.csv", PLAIN)
    rows = [["UMT-2 export, test 12"], ["t [s]", "F [N]", "comment"]]
    rows += [[float(T[i]), float(F[i]), "ok" if i % 50 == 0 else None] for i in range(200)]
    p = tmp_path / "run.xlsx"
    _xlsx(p, rows, shared)
    r = read_record(p, v0=1.0, stiffness=K)
    np.testing.assert_allclose(r.t, ref.t, rtol=0, atol=1e-12)
    np.testing.assert_allclose(r.x, ref.x, rtol=1e-12, atol=1e-15)
    assert any("workbook" in n for n in r.notes)
    bad = tmp_path / "bad.xlsx"
    bad.write_bytes(b"PK\x03\x04 not really a workbook")
    with pytest.raises(LiengInputError, match=r"bad.xlsx: not a readable .xlsx workbook"):
        read_record(bad, v0=1.0, stiffness=K)


@pytest.mark.parametrize("head, scale", [("position [in]", 1 / 25.4), ("stage_position_mil", 1 / 0.0254),
                                         ("speed [in/s]", None), ("drive_um_s", None),
                                         ("Velocity_um_per_s", None)])
def test_an_american_or_suffixed_drive_unit_is_read(tmp_path, head, scale):
    """A drive in inches (in, mil, in/s) or with its unit as the name's last
    parts ("drive_um_s", "Velocity_um_per_s": was read as a time in s)
    reads to the same drive velocity (0.5 mm/s)."""
    if scale is None:
        v = 0.5 / 25.4 if "in/s" in head else 500.0
        rows = _rows(lambda a, b: f"{a},{b},{v!r}\n")
    else:
        rows = _rows(lambda a, b: f"{a},{b},{float(0.5 * a * scale)!r}\n")
    p = tmp_path / "drive.csv"
    p.write_text(f"t [s],F [N],{head}\n" + rows)
    r = read_record(p, stiffness=K)
    assert r.drive_recorded and float(np.median(r.vd)) == pytest.approx(0.5, rel=1e-6)


def test_a_normal_channel_in_a_length_is_the_normal_reading(tmp_path):
    """A normal channel written in a length ("Clamp gauge [mm]": a strain
    gauge or LVDT on the clamp, an affine reading of the load) is the
    normal reading y, not a normal force whose unit is refused."""
    p = tmp_path / "r.csv"
    p.write_text("Time [s],x [mm],Clamp gauge [mm]\n" + _rows(lambda a, b: f"{a},{b},{2.5 + 0.1 * b}\n"))
    r = read_record(p, v0=1.0)
    assert r.y is not None and not r.y_is_force
    np.testing.assert_allclose(r.y, 2.5 + 0.1 * F, rtol=1e-9)


@pytest.mark.parametrize("head, scale", [("Apply pressure [kPa]", 1e3), ("Anpressdruck [bar]", 1e5),
                                         ("Pression (MPa)", 1e6), ("Cylinder pressure", 1.0)])
def test_a_pressure_on_the_contact_is_the_normal_reading(tmp_path, head, scale):
    """A pressure column ("Apply pressure [kPa]": a pneumatic piston's, a
    wet-clutch bench's; ``Anpressdruck``, ``Pression``) with no column named
    for the load is the normal load's reading, and said (a blind generator's
    records had it left unread: "not read: column Apply pressure").  A
    column named for the load comes first, and two pressures are left
    unread."""
    p = tmp_path / "r.csv"
    p.write_text(f"Time [s],F [N],{head},Oil temp [degC]\n" + _rows(lambda a, b: f"{a},{b},{700 + 5 * b},60\n"))
    r = read_record(p, v0=1.0, stiffness=K)
    assert r.y is not None and r.y_is_force
    np.testing.assert_allclose(r.y, (700 + 5 * F) * scale, rtol=1e-9)
    assert any("read as the normal load's reading: a pressure" in n for n in r.notes)
    p.write_text("Time [s],F [N],Air pressure [bar],Normal force [N]\n" + _rows(lambda a, b: f"{a},{b},6.0,{20 + b}\n"))
    np.testing.assert_allclose(read_record(p, v0=1.0, stiffness=K).y, 20 + F, rtol=1e-9)
    p.write_text("Time [s],F [N],Pressure A [kPa],Pressure B [kPa]\n" + _rows(lambda a, b: f"{a},{b},6.0,{20 + b}\n"))
    assert read_record(p, v0=1.0, stiffness=K).y is None


def test_a_six_axis_sensors_export_reads_the_friction_on_the_axis_the_rig_slides_along(tmp_path):
    """An ATI six-axis force/torque sensor's export: a status word in hex
    ('0x00000000') and two counters ('RDT Sequence', 'F/T Sequence') before
    Fx, Fy, Fz, Tx, Ty, Tz and the time, the units in the names or in a
    metadata block above.  It had been refused ("column Time: unit
    '0.000000'": the first data row, a word in it, taken for a row of
    units; and 'F/T Sequence' read as a force in the unit 'T Sequence').
    On a rig that slides along y the friction is Fy, Fx holding crosstalk:
    the tangential channel that swings the more is read, and said."""
    rng = np.random.default_rng(1)
    fx = 0.01 * rng.standard_normal(200)
    rows = "".join(f"0x00000000,{i + 1},{5000 + 2 * i},{fx[i]:.6f},{F[i]},{-2.0 - 0.1 * F[i]:.6f},0.001,0.002,"
                   f"0.0003,{T[i]}\n" for i in range(200))
    named = tmp_path / "ati.csv"
    named.write_text("Status (hex),RDT Sequence,F/T Sequence,Fx (N),Fy (N),Fz (N),Tx (N-m),Ty (N-m),Tz (N-m),"
                     "Time (s)\n" + rows)
    meta = tmp_path / "ati_meta.csv"
    meta.write_text("Final Calibration Name:,FT65318\nForce Units:,N\nTorque Units:,N-m\nTime Units:,s\n"
                    "Status (hex),RDT Sequence,F/T Sequence,Fx,Fy,Fz,Tx,Ty,Tz,Time\n" + rows)
    ref = _read(tmp_path, "plain.csv", PLAIN)
    for p in (named, meta):
        r = read_record(p, v0=1.0, stiffness=K)
        np.testing.assert_allclose(r.x, ref.x, rtol=1e-9)
        np.testing.assert_allclose(r.y, 2.0 + 0.1 * F, rtol=1e-5)
        assert any(n.startswith("column Fy read as the friction") for n in r.notes), r.notes
    # sliding along x, the friction stays Fx
    named.write_text("Time (s),Fx (N),Fy (N),Fz (N)\n" + "".join(f"{T[i]},{F[i]},{fx[i]:.6f},-2.0\n" for i in range(200)))
    r = read_record(named, v0=1.0, stiffness=K)
    np.testing.assert_allclose(r.x, ref.x, rtol=1e-9)
    assert not any("read as the friction" in n for n in r.notes)


@pytest.mark.parametrize("name", ["v_drive", "v_stage [mm/s]", "Stage [mm/s]"])
def test_a_drive_velocity_named_for_the_stage_is_the_drive(tmp_path, name):
    """A column named for the stage or the drive whose unit (or ``v``) says
    it is a velocity ("v_drive" in a MATLAB file, "v_stage [mm/s]") is the
    drive velocity, not a position whose unit is refused (found on an
    independent generator's records)."""
    p = tmp_path / "r.csv"
    p.write_text(f"t [s],F [N],{name}\n" + _rows(lambda a, b: f"{a},{b},2.5\n"))
    r = read_record(p, stiffness=K)
    assert r.drive_recorded and np.allclose(r.vd, 2.5)


@pytest.mark.parametrize("name", ["x_drive (um)", "Drive [um]", "s_stage [um]"])
def test_a_length_named_for_the_drive_is_its_position(tmp_path, name):
    """A length column named for the drive or the stage ("x_drive (um)" in
    a crank tribometer's export, "Drive [um]") is the drive's position, not
    a spring's extension nor a velocity whose unit is refused (found on an
    independent generator's records: 36 of 48 refused)."""
    p = tmp_path / "r.csv"
    p.write_text(f"t [s],F [N],{name}\n" + _rows(lambda a, b: f"{a},{b},{2500.0 * a:.6f}\n"))
    r = read_record(p, stiffness=K)
    assert r.drive_recorded and np.allclose(r.vd[5:-5], 2.5, rtol=1e-3)


# a rotary rig (a torsion spring turned by a motor, a rheometer's tribology cell, a clutch): a friction torque,
# angles; read as a linear record is, the twist in mrad where a linear record's extension is in mm
ROTARY = {
    "torque in N·m, a rheometer's unit row with an empty cell": (
        "Point No.\tTime\tTorque\n\t[s]\t[N·m]\n" + "".join(f"{i + 1}\t{T[i]}\t{F[i]}\n" for i in range(200)), 1.0),
    "torque in N m": ("Time [s],Torque [N m]\n" + _rows(lambda a, b: f"{a},{b}\n"), 1.0),
    "torque in mNm": ("Time [s],Moment [mNm]\n" + _rows(lambda a, b: f"{a},{1e3 * b:.6g}\n"), 1.0),
    "torque in N·mm, an oscilloscope's CH1": ("TIME (s),CH1 Torque (N·mm)\n" + _rows(lambda a, b: f"{a},{1e3 * b:.6g}\n"),
                                               1.0),
    "torque in lbf·in": ("t [s],Torque [lbf·in]\n" + _rows(lambda a, b: f"{a},{float(b) / 0.1129848290!r}\n"), 1.0),
}


@pytest.mark.parametrize("what", sorted(ROTARY))
def test_a_torque_record_reads_as_a_force_record(tmp_path, what):
    """A friction torque T (N·m) over a torsional stiffness k (N·m/rad) is
    the twist T / k, held in mrad as a force over N/m is held in mm: the
    same numbers as the plain force record's x, the drive --v0 in rad/s
    (mrad/s within), the unit said (``length_unit``) and in a note."""
    ref = _read(tmp_path, "plain.csv", PLAIN)
    p = tmp_path / "torque.txt"
    text, _ = ROTARY[what]
    p.write_bytes(text.encode("utf-8"))
    r = read_record(p, v0=1e-3, stiffness=K)
    assert r.length_unit == "mrad" and ref.length_unit == "mm"
    np.testing.assert_allclose(r.x, ref.x, rtol=1e-9)
    np.testing.assert_allclose(r.vd, ref.vd, rtol=1e-12)
    assert any("rotary record" in n and f"N·m/rad" in n for n in r.notes)


def test_a_twist_in_degrees_and_the_motors_angle_are_the_extension_and_the_drive(tmp_path):
    """A torsion spring's twist logged as an angle ("Spring deflection[deg]")
    is the extension x, and the motor's angle the drive's position, both in
    mrad (1 deg = pi/0.18 mrad); a bare --v0 would be in the record's angle
    unit per second (deg/s); a "Drive speed [rpm]" column is the drive."""
    tw = 0.3 + 0.05 * np.sin(2 * np.pi * 7.0 * T)            # deg
    mot = 2.0 * T                                           # deg: 2 deg/s
    body = "".join(f"{i + 1},{T[i]},{tw[i]:.9g},{mot[i]:.9g},36.{i % 10}\n" for i in range(200))
    p = tmp_path / "logger.csv"
    p.write_text('"No.","Time[s]","Spring deflection[deg]","Motor angle[deg]","Oil temp[degC]"\n' + body)
    r = read_record(p)
    np.testing.assert_allclose(r.x, tw * np.pi / 0.18, rtol=1e-6)
    assert np.median(r.vd) == pytest.approx(2.0 * np.pi / 0.18, rel=1e-6)
    assert r.length_unit == "mrad" and any("N·m/deg" in n and "deg/s" in n for n in r.notes)
    # the drive as an angular speed in rpm, and with no drive column a bare --v0 in deg/s
    q = tmp_path / "rpm.csv"
    q.write_text("Time [s],Twist [deg],Drive speed [rpm]\n" + "".join(f"{T[i]},{tw[i]:.9g},0.5\n" for i in range(200)))
    assert np.median(read_record(q).vd) == pytest.approx(0.5 * 2e3 * np.pi / 60, rel=1e-12)
    s = tmp_path / "bare.csv"
    s.write_text("Time [s],Twist [deg]\n" + "".join(f"{T[i]},{tw[i]:.9g}\n" for i in range(200)))
    assert np.median(read_record(s, v0=2.0).vd) == pytest.approx(2.0 * np.pi / 0.18, rel=1e-12)


def test_a_torque_beside_a_speed_in_rpm_reads_with_a_stiffness_given_in_its_unit(tmp_path):
    """A friction torque beside the motor's speed in rpm (or 1/min), with no
    angle column: the speed names no angle, so the record's angle unit is
    the revolution it counts; a --stiffness given with its unit (N·m/rad)
    is read through it (this raised KeyError 'rpm', found by a black-box
    audit), and the twist is T / k whatever the unit's spelling."""
    for head in ("Speed [rpm]", "Motor speed [1/min]"):
        p = tmp_path / "rpm.csv"
        p.write_text(f"Time (s),Torque (N·m),{head}\n" + "".join(f"{T[i]},{F[i]},0.5\n" for i in range(200)))
        r = read_record(p, stiffness=(2.5, "N·m/rad"))
        np.testing.assert_allclose(r.x, F / 2.5 * 1e3, rtol=1e-9)          # mrad
        assert np.median(r.vd) == pytest.approx(0.5 * 2e3 * np.pi / 60, rel=1e-12)
        assert any("N·m/rev" in n for n in r.notes)


def test_a_rotary_records_units_read_as_the_last_part_of_its_names(tmp_path):
    """A rotary record whose units are the last part of its columns' names
    ("torque_Nm", "speed_rpm", "speed_deg_s", "twist_deg", "drive_angle_deg")
    reads as the same record with its units in brackets does (the suffixes
    were a linear record's only: "speed_deg_s" was read as a time in s, the
    angles were not read and the drive's position came out NaN)."""
    def same(a, b):
        ra, rb = read_record(a, stiffness=2.5), read_record(b, stiffness=2.5)
        np.testing.assert_allclose(rb.x, ra.x, rtol=1e-12)
        np.testing.assert_allclose(rb.vd, ra.vd, rtol=1e-12)
        assert np.all(np.isfinite(rb.vd)) and ra.notes[-1].split(";")[-1] == rb.notes[-1].split(";")[-1]
    rows = "".join(f"{T[i]},{F[i]},{30 + 0.2 * i}\n" for i in range(200))
    for bracket, suffix in (("Speed [rpm]", "speed_rpm"), ("Motor speed [deg/s]", "motor_speed_deg_s")):
        a, b = tmp_path / "a.csv", tmp_path / "b.csv"
        a.write_text(f"Time [s],Torque [N·m],{bracket}\n" + rows)
        b.write_text(f"time_s,torque_Nm,{suffix}\n" + rows)
        same(a, b)
    a, b = tmp_path / "c.csv", tmp_path / "d.csv"
    twist = "".join(f"{1e3 * T[i]},{F[i]},{2 * T[i]}\n" for i in range(200))
    a.write_text("Time [ms],Spring deflection [deg],Drive angle [deg]\n" + twist)
    b.write_text("time_ms,spring_deflection_deg,drive_angle_deg\n" + twist)
    same(a, b)


def test_nm_is_a_nanometre_and_Nm_a_newton_metre(tmp_path):
    """Units are read as written: "x [nm]" is a displacement in nanometres,
    "Torque [Nm]" a torque (its N a capital), and a force record with a
    disc's angle beside it stays linear (the angle not read)."""
    p = tmp_path / "nm.csv"
    p.write_text("t [s],x [nm],v0 [nm/s]\n" + "".join(f"{T[i]},{1e6 * F[i]:.9g},1000\n" for i in range(200)))
    r = read_record(p)
    assert r.length_unit == "mm"
    np.testing.assert_allclose(r.x, F, rtol=1e-9)
    q = tmp_path / "disc.csv"
    q.write_text("t [s],F [N],Angle [deg]\n" + "".join(f"{T[i]},{F[i]},{3 * i}\n" for i in range(200)))
    r = read_record(q, v0=1.0, stiffness=K)
    assert r.length_unit == "mm" and any("angle" in n and "not read" in n for n in r.notes)


def test_a_rotary_records_bad_options_name_its_units(tmp_path):
    """A --v0 or --stiffness out of range on a rotary record is refused in
    the record's own units (deg/s, N·m/deg), not a linear record's."""
    p = tmp_path / "twist.csv"
    p.write_text("Time [s],Torque [N·m],Motor angle [deg]\n" + "".join(f"{T[i]},{F[i]},{2 * T[i]}\n" for i in range(200)))
    with pytest.raises(LiengInputError, match=r"--stiffness -1: .* \(N·m/deg\)"):
        read_record(p, stiffness=-1.0)
    q = tmp_path / "torque.csv"
    q.write_text("Time [s],Torque [N·m]\n" + _rows(lambda a, b: f"{a},{b}\n"))
    with pytest.raises(LiengInputError, match=r"--v0 1e\+09: .* rad/s"):
        read_record(q, v0=1e9, stiffness=1.0)


def test_options_with_their_units_read_as_the_bare_numbers(tmp_path):
    """--stiffness and --v0 given with a unit ((number, unit), as the CLI
    passes '2.5 N/mm') read the record as the bare numbers in its own
    units do: N/m and mm/s for a linear record, N·m per its angle unit and
    that unit per second for a rotary one (here rad: 0.05 N·m/rad is
    0.05 pi/180 N·m/deg), each said in a note."""
    p = tmp_path / "lin.csv"
    p.write_text(PLAIN)
    a = read_record(p, v0=0.5, stiffness=K)
    b = read_record(p, v0=(500.0, "um/s"), stiffness=(K / 1e3, "N/mm"))
    np.testing.assert_allclose(b.x, a.x, rtol=1e-12)
    np.testing.assert_allclose(b.vd, a.vd, rtol=1e-12)
    assert "--stiffness 2 N/mm: 2000 N/m" in b.notes and "--v0 500 um/s: 0.5 mm/s" in b.notes
    q = tmp_path / "rot.csv"
    q.write_text("Time [s],Torque [N·m]\n" + _rows(lambda a, b: f"{a},{b}\n"))
    c = read_record(q, v0=0.5, stiffness=0.05)
    d = read_record(q, v0=(0.5 * 180 / np.pi, "deg/s"), stiffness=(0.05 * np.pi / 180, "N·m/deg"))
    np.testing.assert_allclose(d.x, c.x, rtol=1e-12)
    np.testing.assert_allclose(d.vd, c.vd, rtol=1e-12)
    with pytest.raises(LiengInputError, match="--v0 1 mm/s: a rotary record's drive is an angular speed"):
        read_record(q, v0=(1.0, "mm/s"), stiffness=0.05)


def test_a_seals_squeeze_is_the_normal_reading_and_a_column_not_read_is_said(tmp_path):
    """A seal rig's "squeeze [mm]" (the lip's compression, an affine reading
    of its radial load) is the normal reading y, as "Normal deflection [mm]"
    is; a squeeze film's thickness is the lubricant's, not a load, and a
    column no role is read from (a temperature, a comment) is named in a
    note, not dropped in silence (pneumatic_seal's squeeze was)."""
    y = 0.3 + 0.01 * np.sin(T)
    p = tmp_path / "seal.csv"
    p.write_text("t [s];x [mm];squeeze [mm];oil temperature [degC]\n"
                 + "".join(f"{T[i]};{F[i]};{y[i]};{40 + i / 100}\n" for i in range(200)))
    r = read_record(p, v0=1.0)
    np.testing.assert_allclose(r.y, y, rtol=1e-9)
    assert any(n.startswith("not read: column oil temperature") for n in r.notes)
    q = tmp_path / "film.csv"
    q.write_text("t [s],x [mm],squeeze film thickness [um]\n"
                 + "".join(f"{T[i]},{F[i]},{1 + y[i]}\n" for i in range(200)))
    r = read_record(q, v0=1.0)
    assert r.y is None and any("not read" in n and "squeeze film thickness" in n for n in r.notes)


def _reciprocating(n=4000, dt=1e-3, k=K, level=0.3):
    """A reciprocating rig with dwells (1 mm/s each way for 0.8 s, 0.2 s
    dwells) dragging a Coulomb slider on a spring: the stage's position
    (mm) and the spring's force (N), which ramps through zero after each
    reversal and keeps its level through the dwell."""
    t = np.arange(n) * dt
    ph = t % 2.0
    v = np.where(ph < 0.8, 1.0, np.where(ph < 1.0, 0.0, np.where(ph < 1.8, -1.0, 0.0)))
    pos = np.r_[0.0, np.cumsum(v[:-1]) * dt]
    s, f = 0.0, np.empty(n)
    for i in range(n):
        f[i] = k * (pos[i] - s) * 1e-3
        if abs(f[i]) > level:
            f[i] = np.copysign(level, f[i])
            s = pos[i] - f[i] / k * 1e3
    return t, pos, f + 1e-4 * np.sin(np.arange(n))


def test_a_tribometers_stage_axis_testing_machines_displacement_and_a_stroke_are_the_drive(tmp_path):
    """A stage axis named by its letter ("Y (mm)" beside "Fx", "Fz": a UMT
    export), an "Axial Displacement" beside an "Axial Force" and a
    "Stroke" (an SRV's) are the drive's position, though the axis letter
    and the displacement read as lengths of other roles: the stage goes
    back and forth, so it is not the spring's extension (which follows the
    force), and the forces are read (a stress test of unseen exports had
    them refused: "no drive column")."""
    t, pos, f = _reciprocating()
    ref = read_record(_write(tmp_path, "ref.csv", "t [s],F [N],position [mm]", t, f, pos), stiffness=K)
    heads = {"umt.csv": "Time (sec),Fx (N),Fz (N),COF,Y (mm),Z (mm)",
             "mts.csv": "Time (s),Axial Force (N),Normal Force (N),Axial Displacement (mm)",
             "srv.csv": "Time [s],Friction force [N],Load [N],Stroke [mm]",
             "mat.csv": "t,Ff,Fn,x"}
    for name, head in heads.items():
        cols = {"umt.csv": (t, f, 20.0 + 0 * t, f / 20.0, pos, -2.0 + 0 * t), "mts.csv": (t, f, 20.0 + 0 * t, pos),
                "srv.csv": (t, f, 20.0 + 0 * t, pos), "mat.csv": (t, f, 20.0 + 0 * t, pos)}[name]
        r = read_record(_write(tmp_path, name, head, *cols), stiffness=K)
        np.testing.assert_allclose(r.x, ref.x, atol=1e-9, err_msg=name)
        np.testing.assert_allclose(r.vd, ref.vd, atol=1e-9, err_msg=name)
        assert r.y is not None and np.mean(r.y) == pytest.approx(20.0), name
    # the spring's extension itself beside the force (x = F / k) stays the extension
    r = read_record(_write(tmp_path, "ext.csv", "t [s],F [N],x [mm],position [mm]", t, f, f / K * 1e3, pos), stiffness=K)
    assert not any("drive's position" in n for n in r.notes)


def _write(tmp_path, name, head, *cols):
    p = tmp_path / name
    p.write_text(head + "\n" + "".join(",".join(f"{float(c[i])!r}" for c in cols) + "\n" for i in range(len(cols[0]))))
    return p


def test_an_unsigned_friction_on_a_reversing_drive_is_signed_and_an_offset_one_loses_its_zero(tmp_path):
    """A friction opposes the motion, so it changes side when the drive
    reverses.  One written unsigned (|F|, an unsigned coefficient: a stress
    test of unseen exports had it read as a friction that drifts and
    differs by direction) falls to zero at each reversal: it is signed by
    the drive's direction from each of those zeros and reads as the signed
    record.  One that keeps its sign without falling to zero is a sensor's
    offset: its zero is set between the two directions' levels and the
    direction asymmetry is not read."""
    t, pos, f = _reciprocating()
    ref = read_record(_write(tmp_path, "ref.csv", "t [s],F [N],position [mm]", t, f, pos), stiffness=K)
    r = read_record(_write(tmp_path, "abs.csv", "t [s],F [N],position [mm]", t, np.abs(f), pos), stiffness=K)
    assert any("written unsigned" in n for n in r.notes) and not r.zero_unknown
    close = np.abs(ref.x) > 0.01 * np.max(np.abs(ref.x))       # (the noise about each zero has lost its sign)
    np.testing.assert_allclose(r.x[close], ref.x[close], atol=1e-9)
    r = read_record(_write(tmp_path, "off.csv", "t [s],F [N],position [mm]", t, f + 1.0, pos), stiffness=K)
    assert r.zero_unknown and any("offset" in n for n in r.notes)
    np.testing.assert_allclose(r.x - ref.x, np.median(r.x - ref.x), atol=1e-6)
    assert not any("unsigned" in n or "offset" in n for n in ref.notes) and not ref.zero_unknown


def test_stamps_coarser_than_a_sampling_between_one_and_two_of_their_steps_are_spread_evenly(tmp_path):
    """1 ms stamps on samples 1.245 ms apart step by 1 and 2 ms: evenly
    spaced over the stamps' span (they had been resampled onto 1 ms as
    uneven sampling); a row dropped from evenly stamped samples is still a
    gap, resampled across."""
    n, dt = 3000, 1.245e-3
    tt = np.arange(n) * dt
    p = tmp_path / "ms.csv"
    p.write_text("t [s],F [N]\n" + "".join(f"{np.round(a, 3):.3f},{0.5 + 0.1 * np.sin(7 * a):.6f}\n" for a in tt))
    r = read_record(p, v0=1.0, stiffness=K)
    assert r.t.size == n and np.diff(r.t) == pytest.approx(dt, rel=1e-3)
    assert any("step unevenly" in m for m in r.notes)


def test_a_stiffness_in_any_force_over_any_length(tmp_path):
    """--stiffness in gram- or kilogram-force per mm (a spring calibrated
    with weights), or any force unit over any length unit."""
    p = tmp_path / "f.csv"
    p.write_text(PLAIN)
    for unit, k in (("gf/mm", 9.80665), ("kgf/mm", 9806.65), ("daN/mm", 1e4), ("kgf/cm", 980.665)):
        r = read_record(p, v0=1.0, stiffness=(1.0, unit))
        assert r.stiffness == pytest.approx(k), unit
    with pytest.raises(LiengInputError, match="force over a length"):
        read_record(p, v0=1.0, stiffness=(1.0, "N/s"))


def test_fnorm_beside_the_friction_force_is_the_normal_force(tmp_path):
    """A unitless `Fnorm` alone is a coefficient (the friction normalised);
    beside the friction force it is the normal force (the README's own
    array names: `t`, `F`, `Fnorm`)."""
    p = tmp_path / "f.npz"
    np.savez(p, t=T, F=F, Fnorm=np.full(T.size, 20.0))
    r = read_record(p, v0=1.0, stiffness=K)
    assert r.y_is_force and np.mean(r.y) == pytest.approx(20.0)


def test_a_refusal_says_how_each_column_was_read(tmp_path):
    """A record refused for a missing role names what each column was read
    as and which were not read (the stress test's refusals had hidden a
    column taken for another role, or passed over, behind "no drive
    column")."""
    p = tmp_path / "nodrive.csv"
    p.write_text("Time (s),Fx (N),Fz (N),Q (mm)\n" + "".join(f"{a},{b},10,{a}\n" for a, b in zip(T, F)))
    with pytest.raises(LiengInputError, match=r"no drive column .*read: Time as the time, Fx as the friction force, "
                                              r"Fz as the normal force; not read: Q\)"):
        read_record(p, stiffness=K)


def test_a_normal_force_written_negative_and_a_lone_F_N_are_read(tmp_path):
    """A load cell's z axis reads a compression negative (a UMT's `Fz`):
    the normal force is read as its magnitude, and said; a record's one
    force named `F_N` (F in N, not a normal force F_N) is the friction."""
    p = tmp_path / "fz.csv"
    p.write_text("Time (s),Fx (N),Fz (N)\n" + "".join(f"{a},{b},-20.0\n" for a, b in zip(T, F)))
    r = read_record(p, v0=1.0, stiffness=K)
    assert np.mean(r.y) == pytest.approx(20.0) and any("written negative" in n for n in r.notes)
    q = tmp_path / "fn.csv"
    q.write_text("t_s,F_N\n" + "".join(f"{a},{b}\n" for a, b in zip(T, F)))
    r = read_record(q, v0=1.0, stiffness=K)
    np.testing.assert_allclose(r.x, read_record(_write(tmp_path, "p.csv", "t [s],F [N]", T, F), v0=1.0,
                                                stiffness=K).x)


def test_a_position_that_jumps_is_a_reset_encoder_not_the_stages_travel(tmp_path):
    """A position column that jumps by tens of mm within a sample or two (a
    re-zeroed or wrapped encoder, a re-homed stage's counter) is not the
    stage's travel: the jumps are taken out and said, and the drive reads as
    without them (the stress test's canonical record jumped back three
    times by up to 148 mm and was cut into seven strokes)."""
    t, pos, f = _reciprocating()
    ref = read_record(_write(tmp_path, "ref.csv", "t [s],F [N],position [mm]", t, f, pos), stiffness=K)
    jumped = pos.copy()
    jumped[1500:] -= 50.0
    jumped[3100:] += 120.0
    r = read_record(_write(tmp_path, "jump.csv", "t [s],F [N],position [mm]", t, f, jumped), stiffness=K)
    assert any("jumps 2 times" in n for n in r.notes)
    np.testing.assert_allclose(r.vd, ref.vd, atol=0.05)
    assert not any("jumps" in n for n in ref.notes)


def _positions():
    """A stick-slip record as a video tracker sees it: the drive's (the pulled end's) position and the
    slider's, whose difference is the spring's extension (``lieng synth``'s effect-free record, mm)."""
    from lieng.analysis.synth import synthesize

    rec = synthesize("none", 0)
    assert rec.v0_col is None
    drive = 5.0 + rec.v0 * rec.t
    return rec, drive, drive - rec.x


def test_a_video_trackers_two_tracks_are_told_apart_by_their_motion(tmp_path):
    """Tracker's multi-track export ("#multi:", a row naming the tracks over
    repeated "x  y" columns, no units): the track that stands still while
    the other moves is the slider's, whichever comes first; the extension
    is the other's less it (the same numbers as the spring's), said."""
    rec, drive, slider = _positions()
    for first, second in ((drive, slider), (slider, drive)):
        p = tmp_path / "tracker.txt"
        p.write_text("#multi:\n\tmass A\t\tmass B\t\nt\tx\ty\tx\ty\n" + "".join(
            f"{a:.9g}\t{b:.9g}\t3.5\t{c:.9g}\t3.6\n" for a, b, c in zip(rec.t, first, second)))
        r = read_record(p)
        np.testing.assert_allclose(r.x - r.x[0], rec.x - rec.x[0], atol=1e-6)
        assert any("told apart by their motion" in n and "mass " in n for n in r.notes), r.notes


def test_a_trackers_pixels_are_read_at_the_scale_its_metadata_states(tmp_path):
    """An OpenCV tracker's CSV: positions in pixels named for the block and
    the puller, the scale in a comment line ("# scale: 0.25 mm/px"); without
    the scale line the refusal names the column and what to add."""
    rec, drive, slider = _positions()
    body = "frame,time_s,block_x_px,puller_x_px\n" + "".join(
        f"{i},{a:.9g},{b / 0.25:.9g},{c / 0.25:.9g}\n" for i, (a, b, c) in enumerate(zip(rec.t, slider, drive)))
    p = tmp_path / "track.csv"
    p.write_text("# video: IMG_0001.MOV 240 fps\n# scale: 0.25 mm/px (a ruler in frame)\n" + body)
    r = read_record(p)
    np.testing.assert_allclose(r.x - r.x[0], rec.x - rec.x[0], atol=1e-6)
    assert any("0.25 mm per pixel" in n for n in r.notes), r.notes
    p.write_text(body)
    with pytest.raises(LiengInputError, match=r"column block_x_px: in pixels, and no line above the header states "
                                              r"the scale"):
        read_record(p)


def test_a_lone_position_beside_v0_is_the_sliders_whichever_way_its_axis_counts(tmp_path):
    """A phone app's or a laser's one position column and --v0: the
    slider's position (a drive column would make --v0 needless), the
    extension the drive's travel less it; an axis counting against the
    drive (a camera's image coordinates) is turned, and said."""
    rec, drive, slider = _positions()
    for sign in (1.0, -1.0):
        p = tmp_path / "phone.csv"
        p.write_text('"Time (s)","Position (m)"\n' + "".join(
            f"{a:.9g},{sign * b / 1000:.12g}\n" for a, b in zip(rec.t, slider)))
        r = read_record(p, v0=(rec.v0, "mm/s"))
        np.testing.assert_allclose(r.x - r.x[0], rec.x - rec.x[0], atol=1e-6)
        assert any("the record's only position, beside --v0" in n for n in r.notes), r.notes
        assert any("runs against --v0's direction" in n for n in r.notes) == (sign < 0)


def test_a_drill_string_rigs_columns_are_read_for_their_roles(tmp_path):
    """A torsional drill-string rig's export: the torque on bit (TOB) is the
    friction torque, the top drive's angle (phi_TD) the drive's, the weight
    on bit (WOB) the normal force, and the bit's speed, the slider's own, is
    not taken for the drive's (found by the drill_string generator, whose
    first contact refused 13 of 48 records)."""
    rec, drive, slider = _positions()       # read as mrad: the twist is the extension
    k = 2.0                                 # N·m/rad
    w = np.gradient(slider, rec.t) / 1000.0 * 60.0 / (2 * np.pi)      # rpm
    p = tmp_path / "drill.csv"
    p.write_text("Run,R002\nSample rate [Hz],1000\nTime [s],TOB [Nm],phi_TD [rev],Bit speed [rpm],WOB [kN]\n" + "".join(
        f"{a:.9g},{k * x / 1000:.9g},{d / 1000 / (2 * np.pi):.12g},{v:.6g},{1.5 + 0.001 * (i % 3):.4f}\n"
        for i, (a, x, d, v) in enumerate(zip(rec.t, rec.x, drive, w))))
    r = read_record(p, stiffness=(k, "N.m/rad"))
    np.testing.assert_allclose(r.x, rec.x, atol=1e-5)
    assert r.y is not None and r.y_is_force and r.vd is not None
    np.testing.assert_allclose(np.median(r.vd), rec.v0, rtol=0.02)
    assert any("Bit speed not read" in n for n in r.notes), r.notes


def test_a_trackers_one_track_without_a_unit_is_read_in_the_unit_its_travel_says(tmp_path):
    """Tracker's one-track table ("mass A" over "t  x  y", calibrated in m,
    no unit written) beside --v0 in mm/s: the track keeps up with the drive
    on average, so its travel says m, and it is the slider's position (its
    axis turned where it counts against the drive), each said; a plain
    extension without a unit (mm), which travels nowhere, keeps mm."""
    rec, drive, slider = _positions()
    for sign in (1.0, -1.0):
        p = tmp_path / "track.txt"
        p.write_text("mass A\nt\tx\ty\n" + "".join(f"{a:.9g}\t{sign * b / 1000:.12g}\t0.0312\n"
                                                  for a, b in zip(rec.t, slider)))
        r = read_record(p, v0=rec.v0)
        np.testing.assert_allclose(r.x - r.x[0], rec.x - rec.x[0], atol=1e-6)
        assert any("has no unit: its travel over the record" in n and "says m:" in n for n in r.notes), r.notes
    p = tmp_path / "plain.csv"
    p.write_text("t,x\n" + "".join(f"{a:.9g},{b:.9g}\n" for a, b in zip(rec.t, rec.x)))
    r = read_record(p, v0=rec.v0)
    np.testing.assert_allclose(r.x, rec.x, atol=1e-6)
    assert not any("has no unit" in n for n in r.notes)


def test_a_german_test_machines_compound_names_are_read_for_their_roles(tmp_path):
    """A strip-drawing tester's export from a German test machine
    (semicolons, decimal commas, ``Key;Value`` lines above the header):
    ``Standardkraft`` (the load cell's force, the pull) is the friction
    force, ``Klemmkraft`` the normal one, ``Traversenweg`` the crosshead's
    travel (the drive's position) and ``Traversengeschwindigkeit`` its
    speed, by the last part of each compound (found by the strip_draw
    generator, whose first contact refused 16 of 48 records)."""
    rec, drive, _ = _positions()
    k = 2000.0                                  # N/m: x (mm) = F / k * 1000
    dec = lambda v, f: format(v, f).replace(".", ",")
    for third, col in (("Traversenweg", drive), ("Traversengeschwindigkeit", np.full(rec.t.size, rec.v0))):
        p = tmp_path / "zug.csv"
        p.write_text("Prüfer;M. Muster\nProbe;DC04 0,8 mm\n"
                     f"Zeit;Standardkraft;Klemmkraft;{third}\ns;N;kN;{'mm' if third.endswith('weg') else 'mm/s'}\n"
                     + "".join(f"{dec(a, '.6f')};{dec(k * x / 1000, '.9g')};{dec(12.5, '.3f')};{dec(d, '.9g')}\n"
                               for a, x, d in zip(rec.t, rec.x, col)), encoding="cp1252")
        r = read_record(p, stiffness=k)
        np.testing.assert_allclose(r.x, rec.x, atol=1e-5)
        assert r.y is not None and r.y_is_force and r.drive_recorded
        np.testing.assert_allclose(np.median(r.vd), rec.v0, rtol=0.02)


def test_names_given_by_the_user_head_a_file_without_a_header_or_replace_a_daq_programs(tmp_path):
    """``--names`` (``read_record(names=...)``): a data-acquisition
    program's channel names (``Dev1/ai0``: one name, not a name over a
    unit), a table without a header (its first row is data), one column
    with ``--rate``, a MATLAB file's one matrix; without it each is refused
    in one line that names the columns as written and ``--names`` (found by
    a blind test of forty lab exports)."""
    import scipy.io

    ref = _read(tmp_path, "plain.csv", PLAIN)
    names = ["t [s]", "F [N]", "N [N]"]
    daq = tmp_path / "daq.csv"
    daq.write_text("Time,Dev1/ai0,Dev1/ai1\n" + _rows(lambda a, b: f"{a},{b},20.0\n"))
    with pytest.raises(LiengInputError, match=r"not read: Dev1/ai0, Dev1/ai1.*--names"):
        read_record(daq, v0=1.0, stiffness=K)
    bare = tmp_path / "bare.csv"
    bare.write_text(_rows(lambda a, b: f"{a},{b},20.0\n"))
    with pytest.raises(LiengInputError, match=r"3 columns of numbers and no header naming them.*--names"):
        read_record(bare, v0=1.0, stiffness=K)
    one = tmp_path / "one.txt"
    one.write_text(_rows(lambda a, b: f"{b}\n"))
    mat = tmp_path / "m.mat"
    scipy.io.savemat(mat, {"data": np.c_[T, F, np.full(T.size, 20.0)], "fs": 1000.0})
    for p, kw in ((daq, {}), (bare, {}), (one, {"rate": 1000.0, "names": ["F [N]"]}), (mat, {})):
        r = read_record(p, v0=1.0, stiffness=K, **{"names": names, **kw})
        assert r.t.size == ref.t.size, p.name
        np.testing.assert_allclose(r.t, ref.t, rtol=0, atol=1e-9)
        np.testing.assert_allclose(r.x, ref.x, rtol=1e-9, atol=1e-12)
    with pytest.raises(LiengInputError, match=r"--names: 2 names for the 3 columns"):
        read_record(daq, v0=1.0, stiffness=K, names=names[:2])


def test_a_lone_column_of_numbers_is_no_card_deck(tmp_path, capsys):
    """A file of one bare column of numbers is refused as a table without a
    header (exit 2, one line naming --names), not read as a TRC deck whose
    card 4 fails; with ``--names`` and ``--rate`` it is read."""
    from lieng.cli import main

    p = tmp_path / "force.txt"
    p.write_text(_rows(lambda a, b: f"{b}\n"))
    assert main(["diagnose", str(p), "--v0", "1", "--stiffness", str(K), "-o", str(tmp_path / "o1")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "1 column of numbers and no header naming it" in err and "--names" in err
    assert not (tmp_path / "o1").exists()


def test_ext_is_the_springs_extension_beside_a_normal_load(tmp_path):
    """``Time(s) Ext(mm) Load(N)``, fixed width: ``Ext`` is the spring's
    extension and ``Load`` the normal load beside it (read as the pull of a
    testing machine, with ``Ext`` unread, it had made a confident
    ``no_stick_slip`` of a record of 21 slips)."""
    p = tmp_path / "fw.dat"
    p.write_text("   Time(s)     Ext(mm)     Load(N)\n" + _rows(lambda a, b: f"{a:10.4f}{1e3 * b / K:12.7f}{20.0:12.3f}\n"))
    r = read_record(p, v0=1.0)
    np.testing.assert_allclose(r.x, 1e3 * F / K, atol=1e-6)
    assert r.y is not None and np.allclose(r.y, 20.0)


def test_a_coefficient_times_the_normal_load_the_user_gives(tmp_path):
    """``--normal-load`` (``read_record(normal_load=...)``): a friction
    coefficient without a normal-force column (a dead weight's slider, as
    colas2019's ``Fnorm`` = F / (m g)) times the load given, in N or with
    its unit, reads as the force record; beside a normal-force column it is
    refused, naming the column; on a force record it is said and not used."""
    ref = _read(tmp_path, "plain.csv", PLAIN)
    load = 2.5                                          # N
    p = tmp_path / "mu.csv"
    p.write_text("t [s],mu\n" + _rows(lambda a, b: f"{a},{float(b) / load!r}\n"))
    with pytest.raises(LiengInputError, match=r"no normal force column.*--normal-load"):
        read_record(p, v0=1.0, stiffness=K)
    for given in (load, (load / 9.80665e-3, "gf")):
        r = read_record(p, v0=1.0, stiffness=K, normal_load=given)
        np.testing.assert_allclose(r.x, ref.x, rtol=1e-9, atol=1e-12)
    both = tmp_path / "both.csv"
    both.write_text("t [s],mu,N [N]\n" + _rows(lambda a, b: f"{a},{float(b) / load!r},{load}\n"))
    with pytest.raises(LiengInputError, match=r"--normal-load: .* records the normal force \(column N\)"):
        read_record(both, v0=1.0, stiffness=K, normal_load=load)
    plain = tmp_path / "f.csv"
    plain.write_text(PLAIN)
    r = read_record(plain, v0=1.0, stiffness=K, normal_load=load)
    np.testing.assert_allclose(r.x, ref.x)
    assert any(n.startswith("--normal-load 2.5 N: not used") for n in r.notes)
    with pytest.raises(LiengInputError, match=r"--normal-load -1: the normal load is a positive force"):
        read_record(p, v0=1.0, stiffness=K, normal_load=-1.0)


def test_a_records_one_force_of_no_known_name_is_the_friction_force(tmp_path):
    """A LabVIEW file whose one channel is named by the data-acquisition
    program (``Dev1/ai0``) with its unit in ``Y_Unit_Label``: the record's
    one force column whose name says nothing is read as the friction force,
    and said; two such columns are refused, naming both and ``--names``."""
    ref = _read(tmp_path, "plain.csv", PLAIN)
    lvm = _lvm().replace("X_Value\tFriction\tComment", "X_Value\tDev1/ai0\tComment")
    r = _read(tmp_path, "daq.lvm", lvm)
    np.testing.assert_allclose(r.x, ref.x, rtol=1e-9, atol=1e-12)
    assert any(n.startswith("column Dev1/ai0 (N), the record's one force") for n in r.notes)
    two = tmp_path / "two.csv"
    two.write_text("t [s],Dev1/ai0 [N],Dev1/ai1 [N]\n" + _rows(lambda a, b: f"{a},{b},20.0\n"))
    with pytest.raises(LiengInputError, match=r"not read: Dev1/ai0, Dev1/ai1.*--names"):
        read_record(two, v0=1.0, stiffness=K)


def test_a_normal_force_of_zero_throughout_is_not_read_and_said(tmp_path):
    """A normal-force column of zeros (a channel not connected) loads
    nothing: it is left out, and said (it had been accepted silently)."""
    ref = _read(tmp_path, "plain.csv", PLAIN)
    r = _read(tmp_path, "n0.csv", "t [s],F [N],N [N]\n" + _rows(lambda a, b: f"{a},{b},0\n"))
    np.testing.assert_allclose(r.x, ref.x)
    assert r.y is None and any("zero throughout" in n for n in r.notes)


def test_a_japanese_export_in_shift_jis(tmp_path):
    """A Japanese testing machine's export in Shift-JIS (cp932: 時間,
    試験力) is decoded as such; a German Windows-1252 export (ü, µ, °) is
    still read as Windows-1252."""
    ref = _read(tmp_path, "plain.csv", PLAIN)
    p = tmp_path / "ja.csv"
    p.write_bytes(("時間 (s),試験力 (N)\n" + _rows(lambda a, b: f"{a},{b}\n")).encode("cp932"))
    r = read_record(p, v0=1.0, stiffness=K)
    np.testing.assert_allclose(r.x, ref.x, rtol=1e-9, atol=1e-12)
    de = tmp_path / "de.csv"
    de.write_bytes(("Prüfzeit [s];Kraft [µN];Temperatur [°C]\n"
                    + _rows(lambda a, b: f"{a};{1e6 * b:.1f};21\n".replace(".", ","))).encode("cp1252"))
    np.testing.assert_allclose(read_record(de, v0=1.0, stiffness=K).x, ref.x, rtol=1e-9, atol=1e-12)


def test_what_a_blind_test_of_vendors_names_misread(tmp_path):
    """A rheometer's drive angle named as a deflection ('Deflection Angle',
    Anton Paar; 'Displacement (rad)', TA) turns one way: the drive's, not
    the spring's twist (read as the twist it had made a confident
    no_stick_slip); an unnamed force beside a column lieng cannot name
    (a coefficient in another language) or standing still (a normal load)
    is not taken for the friction; a position that never moves beside
    --v0 (an SRV's 'Stroke' setting) gives way to --v0; a data row of more
    values than the header has names is refused."""
    t = np.arange(4000) * 2e-3
    ang = 0.1 * t                                       # rad: the drive turns at 0.1 rad/s
    torque = 0.02 + 0.004 * ((0.1 * t) % 0.05) / 0.05   # N·m: a sawtooth
    p = tmp_path / "mcr.csv"
    p.write_text("Time [s]\tTorque [mN·m]\tNormal Force [N]\tDeflection Angle [mrad]\tRotational Speed [1/min]\n"
                 + "".join(f"{a:.4f}\t{1e3 * q:.6f}\t5.0\t{1e3 * g:.5f}\t{0.1 * 60 / (2 * np.pi):.6f}\n"
                           for a, q, g in zip(t, torque, ang)))
    r = read_record(p, stiffness=(0.2, "N·m/rad"))
    np.testing.assert_allclose(r.x, 1e3 * torque / 0.2, rtol=1e-6)      # the twist is the torque's, in mrad
    assert "Deflection Angle (mrad) as the drive's angle" in r.notes[0] or "as the drive's angular speed" in r.notes[0]
    bare = tmp_path / "bare.csv"
    bare.write_text("t [s],Koef,Dev1/ai0 [N]\n" + _rows(lambda a, b: f"{a},{float(b) / 10:.6f},10.0\n"))
    still = tmp_path / "still.csv"
    still.write_text("t [s],Dev1/ai0 [N]\n" + _rows(lambda a, b: f"{a},10.0\n"))
    for f in (bare, still):
        with pytest.raises(LiengInputError, match=r"not read: .*Dev1/ai0"):
            read_record(f, v0=1.0, stiffness=K)
    srv = tmp_path / "srv.csv"
    srv.write_text("Time [s];Friction force [N];Stroke [mm]\n" + _rows(lambda a, b: f"{a};{b};1\n".replace(".", ",")))
    r = read_record(srv, v0=1.0, stiffness=K)
    assert any(n.startswith("column Stroke never moves") for n in r.notes) and not r.drive_recorded
    ragged = tmp_path / "ragged.csv"
    ragged.write_text("t [s],F [N]\n" + _rows(lambda a, b: f"{a},{b},10.0\n"))
    with pytest.raises(LiengInputError, match=r"line 2: 3 values where the header names 2 columns"):
        read_record(ragged, v0=1.0, stiffness=K)


def test_a_one_letter_name_is_read_by_convention_only_in_its_roles_unit(tmp_path):
    """``W`` is the load and ``s``, ``d``, ``u`` the travel only in a force
    or a length: ``w [rad/s]`` is an angular speed, ``u [V]`` a raw channel
    (no role; before the convention they had none either)."""
    from lieng.diagnose.read import _column_role

    assert _column_role("W", "N")[0] == "N" and _column_role("s", "mm")[0] == "position"
    assert _column_role("w", "rad/s")[0] is None and _column_role("u", "V")[0] is None
    assert _column_role("s", "s")[0] == "t"


def test_a_loggers_runs_side_by_side_are_read_one_at_a_time(tmp_path):
    """A teaching lab's logger exports several runs side by side, each
    column tagged with its run (PASCO Capstone's ``Time (s) Run #1``,
    Vernier Logger Pro's and Graphical Analysis' ``Run 1: Time (s)`` and
    ``Latest: Force (N)``), the shorter run's cells left blank.  Without
    ``--run`` such a file is refused in one line that names its runs (it
    had read "rows miss a value"); with ``--run`` the run chosen is read as
    the same run alone in its own file."""
    ref = _read(tmp_path, "plain.csv", PLAIN)
    short = _read(tmp_path, "short.csv", "t [s],F [N]\n" + _rows(lambda a, b: f"{a},{b}\n", 120))
    rows = "".join(f"{T[i]},{F[i]}," + (f"{T[i]},{F[i]}" if i < 120 else ",") + "\n" for i in range(200))
    capstone = tmp_path / "capstone.csv"
    capstone.write_text("Time (s) Run #1,Force (N) Run #1,Time (s) Run #2,Force (N) Run #2\n" + rows)
    vernier = tmp_path / "vernier.txt"
    vernier.write_text("Latest: Time (s)\tLatest: Force (N)\tRun 1: Time (s)\tRun 1: Force (N)\n" +
                       rows.replace(",", "\t"))
    for p, labels in ((capstone, r"run 1, run 2"), (vernier, r"latest, run 1")):
        with pytest.raises(LiengInputError, match=rf"2 runs side by side \({labels}\): choose one with --run"):
            read_record(p, v0=1.0, stiffness=K)
    for p, run, want in ((capstone, 1, ref), (capstone, "Run #2", short), (vernier, "latest", ref),
                         (vernier, "1", short)):
        r = read_record(p, v0=1.0, stiffness=K, run=run)
        assert r.t.size == want.t.size, (p.name, run)
        np.testing.assert_allclose(r.x, want.x, rtol=1e-12, atol=0)
    with pytest.raises(LiengInputError, match=r"--run 3: not among the runs of .* \(run 1, run 2\)"):
        read_record(capstone, v0=1.0, stiffness=K, run=3)
    with pytest.raises(LiengInputError, match=r"--run 2: .* holds no such run"):
        read_record(tmp_path / "plain.csv", v0=1.0, stiffness=K, run=2)
    quoted = tmp_path / "quoted.csv"
    quoted.write_text('"Time (s) Run #1","Force (N) Run #1","Time (s) Run #2","Force (N) Run #2"\n' +
                      "".join(f'"{T[i]}","{1000 * F[i]:,.3f}","{T[i]}","{F[i]}"\n' for i in range(200)))
    r = read_record(quoted, v0=1.0, stiffness=K * 1000, run=1)     # (forces written x 1000, grouped: "1,234.5")
    np.testing.assert_allclose(r.x, ref.x, rtol=1e-6, atol=0)
