"""The status codes of the compiled core: one table, the same as fortran/status.f90.

Every routine of the Fortran core returns one of these codes (0 = success);
each code means one thing in every routine.  The wrappers turn a non-zero
code into a :class:`lieng.errors.LiengInputError` with a message that names
the card, column or option at fault; :func:`name` gives a code's name for
the messages of the codes no input can produce.  ``tests/test_status.py``
checks this table against the Fortran module.
"""

from __future__ import annotations

__all__ = ["OK", "INFINITE_SLOPE", "NO_NEGATIVE_SLOPE", "CENTRE_UNDEFINED", "SINGULAR_POINT", "DT_UNDEFINED",
           "BAD_SIZE", "ARCOS_DOMAIN", "OMEGA_ZERO", "TIMDIS_RANGE", "NO_RETURN", "TRC_FEW_POINTS", "TRC_NO_EL",
           "TRC_DEGENERATE_FIT", "TRC_ZERO_DT", "BAD_ARGUMENT", "NONFINITE_STATE", "CODES", "name"]

OK = 0                  #: success
INFINITE_SLOPE = 1      #: XCHL(J) = XCHL(J+1): infinite slope
NO_NEGATIVE_SLOPE = 2   #: no negative-slope point (FORMAT 1175)
CENTRE_UNDEFINED = 3    #: the centre search divides by zero
SINGULAR_POINT = 4      #: P coincides with S (XK = 0 and Y = 0)
DT_UNDEFINED = 5        #: 2*Y - DY = 0 in the DT formula
BAD_SIZE = 6            #: an array size out of range
ARCOS_DOMAIN = 7        #: MLIEN: |VO/AMPV0| > 1 or AMPV0 = 0
OMEGA_ZERO = 8          #: MLIEN: OMEGA = 0
TIMDIS_RANGE = 9        #: TIMDIS finds no point of the characteristic at the velocity
NO_RETURN = 10          #: a return map's trajectory did not come back to the abscissa
TRC_FEW_POINTS = 11     #: TRC: fewer than 10 points
TRC_NO_EL = 12          #: TRC: no + to - sign change of VLN (EL undefined)
TRC_DEGENERATE_FIT = 13  #: TRC: a BELFIT group with fewer than 3 distinct abscissae
TRC_ZERO_DT = 14        #: TRC: two readings at the same time
BAD_ARGUMENT = 15       #: slider and 2-DoF models: an argument out of range
NONFINITE_STATE = 16    #: slider and 2-DoF models: the state became non-finite

#: code -> name (the Fortran parameter without its ``st_`` prefix)
CODES = {v: k.lower() for k, v in globals().items() if k.isupper() and isinstance(v, int) and k != "CODES"}


def name(code) -> str:
    """The name of a status code (``"unknown status N"`` for a code not in the table)."""
    return CODES.get(int(code), f"unknown status {int(code)}")
