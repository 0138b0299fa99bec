!> The status codes of every compiled routine: one table for the Fortran
!> core and the Python wrappers (python/lieng/status.py holds the same table
!> with its messages; tests/test_status.py checks that the two agree).
!> 0 is success; every other code means one thing everywhere.
module status_codes
   implicit none
   private

   !> Success.
   integer, parameter, public :: st_ok = 0
   !> XCHL(J) = XCHL(J+1): infinite slope ("CONTROL STATEMENT DOES NOT EXIST").
   integer, parameter, public :: st_infinite_slope = 1
   !> No negative-slope point among SLOPE(1..K-1) (FORMAT 1175).
   integer, parameter, public :: st_no_negative_slope = 2
   !> Equal-slope interpolation divides by zero (BB = 0 at statement 210/220).
   integer, parameter, public :: st_centre_undefined = 3
   !> The point P coincides with S (XK = 0 and Y = 0): the singular point.
   integer, parameter, public :: st_singular_point = 4
   !> 2*Y - DY = 0 in the DT formula: the time increment is undefined.
   integer, parameter, public :: st_dt_undefined = 5
   !> An array size out of range (N < 2, NPTS < 1, ...).
   integer, parameter, public :: st_bad_size = 6
   !> MLIEN: |VO/AMPV0| > 1 or AMPV0 = 0 (ARCOS out of its domain).
   integer, parameter, public :: st_arcos_domain = 7
   !> MLIEN: OMEGA = 0 (T(1) = PHI/OMEGA undefined).
   integer, parameter, public :: st_omega_zero = 8
   !> MLIEN: TIMDIS finds no point of the characteristic at velocity DIFF.
   integer, parameter, public :: st_timdis_range = 9
   !> Return maps: the trajectory did not come back to the abscissa within
   !> the time limit (it settles on the equilibrium, e.g. a stable node).
   integer, parameter, public :: st_no_return = 10
   !> TRC: fewer than 10 points (BELFIT needs two runs of 2M - 1 = 9).
   integer, parameter, public :: st_trc_few_points = 11
   !> TRC: no + to - sign change of VLN: the origin EL is undefined.
   integer, parameter, public :: st_trc_no_el = 12
   !> TRC: a BELFIT group has fewer than 3 distinct abscissae.
   integer, parameter, public :: st_trc_degenerate_fit = 13
   !> TRC: two readings at the same time: the velocity is undefined.
   integer, parameter, public :: st_trc_zero_dt = 14
   !> Slider and 2-DoF models: an argument out of range.
   integer, parameter, public :: st_bad_argument = 15
   !> Slider and 2-DoF models: the state became non-finite.
   integer, parameter, public :: st_nonfinite_state = 16
end module status_codes
