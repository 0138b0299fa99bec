"""One error type (issue #16 item 2): the API's errors and warnings name the argument they are about in
``fields``; the deck and CSV layers name the same fields by card and columns, or by file, with
``lieng.errors.located`` (no location travels through the API's signatures)."""

import inspect
import pickle
import warnings

import numpy as np
import pytest

import lieng
from lieng.errors import CentreUndefined, LiengInputError, LiengInputWarning, located
from lieng.programs import read_deck
from lieng.programs.lieng1 import run_deck

from conftest import CARDS

Y9 = np.linspace(10, -10, 9)


def test_the_api_takes_no_location():
    for fn in (lieng.lieng1, lieng.mlien, lieng.trc, lieng.centre_of_symmetry):
        assert not [p for p in inspect.signature(fn).parameters if p.startswith("_") or p == "locate"], fn


def test_an_api_error_names_its_argument():
    x = np.array([-3.0, -1, np.nan, 3, 1, -1])
    with pytest.raises(LiengInputError) as e:
        lieng.lieng1(x, np.linspace(10, -10, 6), 1, 0, 0.01, npts=10)
    assert e.value.fields == ("xchl[2]",)
    assert e.value.detail == "nan is not a finite number"
    assert str(e.value) == "xchl[2]: nan is not a finite number"


def test_located_names_the_fields_again_and_keeps_the_class():
    with pytest.raises(CentreUndefined) as e:
        with located(lambda f: f"deck: {f.upper()}"):
            lieng.centre_of_symmetry(0.3 * Y9, Y9)
    assert str(e.value).startswith("deck: YCHL[0]..deck: YCHL[8]: there is not a negative slope point")
    assert e.value.fields == ("ychl[0]", "ychl[8]")


def test_an_error_without_fields_is_given_as_it_is():
    err = LiengInputError("ntraj and npts must be integers")
    assert err.located(lambda f: "nowhere") is err


def test_a_warning_is_named_by_the_deck_too():
    t = np.arange(300) * 1e-3
    x = np.sin(2 * np.pi * np.arange(300) / 60)
    x[15] = x[14]
    with pytest.warns(LiengInputWarning) as api:
        lieng.trc(t, x, omnh=100)
    assert str(api[0].message).startswith("trc: XX is undefined")
    with pytest.warns(LiengInputWarning) as rec:
        with located(lambda f: "q.csv"):
            lieng.trc(t, x, omnh=100)
    assert str(rec[0].message).startswith("q.csv: XX is undefined")
    assert rec[0].filename == api[0].filename == __file__


def test_a_deck_names_card_and_columns(tmp_path):
    deck = read_deck(CARDS / "mlien_a9_7.dat", "mlien")
    deck.ampv0 = 0.001
    with pytest.raises(LiengInputError) as e:
        deck.run(npts=10)
    assert str(e.value).startswith(f"{deck.source}: card 2, columns 16-25 (AMPV0, F10.2): PHI = ARCOS(VO/AMPV0)")
    assert e.value.fields == ("ampv0",)
    assert deck.where("xinp, yinp") == f"{deck.source}: card 2, columns 26-45 (XINP, YINP)"
    assert deck.where("xchl[6]") == f"{deck.source}: card 4, columns 11-20 (XCHL(7), F10.2)"


def test_a_lieng1_deck_without_a_negative_slope_is_an_error_where_the_api_warns(tmp_path):
    deck = read_deck(CARDS / "lieng1_demo.dat", "lieng1")
    deck.n = 9
    deck.xchl[:9], deck.ychl[:9] = 0.3 * Y9, Y9
    with pytest.raises(CentreUndefined, match=r"card 44, columns 1-10 \(YCHL\(1\), F10.2\)\.\."):
        run_deck(deck, ntraj=1, npts=10)
    with pytest.warns(LiengInputWarning, match=r"^ychl\[0\]\.\.ychl\[8\]: there is not a negative slope"):
        res = lieng.lieng1(0.3 * Y9, Y9, 1, 0, 0.01, ntraj=1, npts=10)
    assert np.isnan(res.xmdl)


def test_errors_pickle_with_their_message_and_fields():
    err = LiengInputError("DTHETA = 0 must be positive", fields=("dtheta",)).located(lambda f: "d.dat: card 3")
    back = pickle.loads(pickle.dumps(err))
    assert str(back) == str(err) == "d.dat: card 3: DTHETA = 0 must be positive"
    assert type(back) is LiengInputError
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(LiengInputWarning, match="^w.dat: x"):
            with located(lambda f: "w.dat"):
                warnings.warn(LiengInputWarning("x", fields=("a",)))
