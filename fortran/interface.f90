! The f2py-visible surface of lieng: plain subroutines with explicit array
! sizes that call the modules of the static library (f2py does not wrap
! modules that use other modules).  Python: lieng._core.<name>.
! Sizes and ranges are checked by the Python layer before every call; the
! routines check them again and return status st_bad_size rather than
! touching memory out of range.

!> Slopes and centre of symmetry of a characteristic (PINPUT / CHALIN).
subroutine core_centre(n, xchl, ychl, slope, isel, lll, mmm, branch, xmdl, ymdl, status, where)
   use lienard_core, only: wp, centre_of_symmetry
   implicit none
   integer, intent(in) :: n                    !< number of points
   real(wp), intent(in) :: xchl(n)             !< abscissae
   real(wp), intent(in) :: ychl(n)             !< ordinates
   real(wp), intent(out) :: slope(n)           !< SLOPE(1..N-1), SLOPE(N) = 0
   integer, intent(out) :: isel                !< I, the negative slope with the largest value
   integer, intent(out) :: lll                 !< first segment of the negative-slope run
   integer, intent(out) :: mmm                 !< last segment of the run
   integer, intent(out) :: branch              !< -1, 0, +1: FORMAT 1007, 1006, 1008
   real(wp), intent(out) :: xmdl               !< XMDL
   real(wp), intent(out) :: ymdl               !< YMDL
   integer, intent(out) :: status              !< st_ok or an error code (status_codes)
   integer, intent(out) :: where               !< index the error refers to
   call centre_of_symmetry(n, xchl, ychl, slope, isel, lll, mmm, branch, xmdl, ymdl, status, where)
end subroutine core_centre

!> XB of the characteristic at each of M velocities (POINT 305-342).
subroutine core_xb(n, xchl, ychl, m, y, lookup, xb)
   use lienard_core, only: wp, xb_listing, xb_bisect
   implicit none
   integer, intent(in) :: n                    !< number of points
   real(wp), intent(in) :: xchl(n)             !< abscissae
   real(wp), intent(in) :: ychl(n)             !< ordinates
   integer, intent(in) :: m                    !< number of velocities
   real(wp), intent(in) :: y(m)                !< velocities
   integer, intent(in) :: lookup               !< 0 listing, 1 bisect, 2 fast
   real(wp), intent(out) :: xb(m)              !< XB at each velocity
   integer :: i
   do i = 1, m
      if (lookup /= 0) then
         xb(i) = xb_bisect(n, xchl, ychl, y(i))
      else
         xb(i) = xb_listing(n, xchl, ychl, y(i))
      end if
   end do
end subroutine core_xb

!> One POINT step from (x, y, t).
subroutine core_point(n, xchl, ychl, dtheta, x, y, t, lookup, xn, yn, tn, r, xb, xk, ds, dx, dy, dt, status)
   use lienard_core, only: wp, point_step
   implicit none
   integer, intent(in) :: n                    !< number of points
   real(wp), intent(in) :: xchl(n)             !< abscissae
   real(wp), intent(in) :: ychl(n)             !< ordinates
   real(wp), intent(in) :: dtheta              !< DTHETA
   real(wp), intent(in) :: x                   !< X(L)
   real(wp), intent(in) :: y                   !< Y(L)
   real(wp), intent(in) :: t                   !< T(L)
   integer, intent(in) :: lookup               !< 0 listing, 1 bisect, 2 fast
   real(wp), intent(out) :: xn                 !< X(L+1)
   real(wp), intent(out) :: yn                 !< Y(L+1)
   real(wp), intent(out) :: tn                 !< T(L+1)
   real(wp), intent(out) :: r                  !< R
   real(wp), intent(out) :: xb                 !< XB
   real(wp), intent(out) :: xk                 !< XK
   real(wp), intent(out) :: ds                 !< DS
   real(wp), intent(out) :: dx                 !< DX
   real(wp), intent(out) :: dy                 !< DY
   real(wp), intent(out) :: dt                 !< DT
   integer, intent(out) :: status              !< st_ok, st_singular_point or st_dt_undefined (status_codes)
   call point_step(n, xchl, ychl, dtheta, x, y, t, lookup, xn, yn, tn, r, xb, xk, ds, dx, dy, dt, status)
end subroutine core_point

!> The LIENG-1 phase portrait: NTRAJ trajectories of NPTS points.
subroutine core_lieng1(n, xchl, ychl, dtheta, xinp, yinp, xincr, yincr, ntraj, npts, lookup, &
                       x, y, t, status, where, itraj)
   use lienard_core, only: wp
   use lieng1, only: lieng1_portrait
   implicit none
   integer, intent(in) :: n                    !< number of points of the characteristic
   real(wp), intent(in) :: xchl(n)             !< abscissae
   real(wp), intent(in) :: ychl(n)             !< ordinates
   real(wp), intent(in) :: dtheta              !< DTHETA
   real(wp), intent(in) :: xinp                !< XINP
   real(wp), intent(in) :: yinp                !< YINP
   real(wp), intent(in) :: xincr               !< XINCR
   real(wp), intent(in) :: yincr               !< YINCR
   integer, intent(in) :: ntraj                !< number of trajectories
   integer, intent(in) :: npts                 !< points per trajectory
   integer, intent(in) :: lookup               !< 0 listing, 1 bisect, 2 fast
   real(wp), intent(out) :: x(npts, ntraj)     !< X
   real(wp), intent(out) :: y(npts, ntraj)     !< Y
   real(wp), intent(out) :: t(npts, ntraj)     !< T
   integer, intent(out) :: status              !< st_ok or the failing status (status_codes)
   integer, intent(out) :: where               !< L of the failure
   integer, intent(out) :: itraj               !< trajectory of the failure
   call lieng1_portrait(n, xchl, ychl, dtheta, xinp, yinp, xincr, yincr, ntraj, npts, lookup, &
                        x, y, t, status, where, itraj)
end subroutine core_lieng1

!> The time correction alone (DO 140), applied in place to T.
subroutine core_time_correction(npts, y, t)
   use lienard_core, only: wp
   use lieng1, only: time_correction
   implicit none
   integer, intent(in) :: npts                 !< number of points
   real(wp), intent(in) :: y(npts)             !< Y
   real(wp), intent(inout) :: t(npts)          !< T, corrected in place
   call time_correction(npts, y, t)
end subroutine core_time_correction

!> NSTEPS POINT steps from (x, y, t); only the last point is kept.
subroutine core_advance(n, xchl, ychl, dtheta, nsteps, lookup, x, y, t, status, where)
   use lienard_core, only: wp, point_advance
   implicit none
   integer, intent(in) :: n                    !< number of points
   real(wp), intent(in) :: xchl(n)             !< abscissae
   real(wp), intent(in) :: ychl(n)             !< ordinates
   real(wp), intent(in) :: dtheta              !< DTHETA
   integer, intent(in) :: nsteps               !< number of steps
   integer, intent(in) :: lookup               !< 0 listing, 1 bisect, 2 fast
   real(wp), intent(inout) :: x                !< X, advanced in place
   real(wp), intent(inout) :: y                !< Y, advanced in place
   real(wp), intent(inout) :: t                !< T, advanced in place
   integer, intent(out) :: status              !< st_ok or the failing status (status_codes)
   integer, intent(out) :: where               !< the failing step
   call point_advance(n, xchl, ychl, dtheta, nsteps, lookup, x, y, t, status, where)
end subroutine core_advance

!> The MLIEN run (App. 6).
subroutine core_mlien(n, xchl0, ychl0, dtheta, omega, ampv0, xinp, yinp, npts, trig, lookup, &
                      x, y, t, r, xmdl, ymdl, xchl, ychl, status, where)
   use lienard_core, only: wp
   use mlien, only: mlien_run
   implicit none
   integer, intent(in) :: n                    !< number of points of the characteristic
   real(wp), intent(in) :: xchl0(n)            !< abscissae as read
   real(wp), intent(in) :: ychl0(n)            !< ordinates as read
   real(wp), intent(in) :: dtheta              !< DTHETA
   real(wp), intent(in) :: omega               !< OMEGA
   real(wp), intent(in) :: ampv0               !< AMPV0
   real(wp), intent(in) :: xinp                !< XINP
   real(wp), intent(in) :: yinp                !< YINP
   integer, intent(in) :: npts                 !< points
   real(wp), intent(in) :: trig(4)             !< OMINTR, OMETRI, ATRI, BTRI
   integer, intent(in) :: lookup               !< 0 listing, 1 bisect, 2 fast
   real(wp), intent(out) :: x(npts)            !< X
   real(wp), intent(out) :: y(npts)            !< Y
   real(wp), intent(out) :: t(npts)            !< T
   real(wp), intent(out) :: r(npts)            !< R of each step
   real(wp), intent(out) :: xmdl(npts)         !< XMDL in force at each point
   real(wp), intent(out) :: ymdl(npts)         !< YMDL in force at each point
   real(wp), intent(out) :: xchl(n)            !< last position of the characteristic
   real(wp), intent(out) :: ychl(n)            !< its ordinates
   integer, intent(out) :: status              !< st_ok or an error code (status_codes)
   integer, intent(out) :: where               !< L of the failure
   call mlien_run(n, xchl0, ychl0, dtheta, omega, ampv0, xinp, yinp, npts, trig, lookup, &
                  x, y, t, r, xmdl, ymdl, xchl, ychl, status, where)
end subroutine core_mlien

!> One TIMDIS translation of a characteristic, in place.
subroutine core_timdis(n, xchl, ychl, vo, ampv0, omega, tl, diff, adiff, status)
   use lienard_core, only: wp
   use mlien, only: timdis
   implicit none
   integer, intent(in) :: n                    !< number of points
   real(wp), intent(inout) :: xchl(n)          !< abscissae, translated in place
   real(wp), intent(inout) :: ychl(n)          !< ordinates, translated in place
   real(wp), intent(in) :: vo                  !< VO
   real(wp), intent(in) :: ampv0               !< AMPV0
   real(wp), intent(in) :: omega               !< OMEGA
   real(wp), intent(in) :: tl                  !< T(L)
   real(wp), intent(out) :: diff               !< DIFF
   real(wp), intent(out) :: adiff              !< ADIFF
   integer, intent(out) :: status              !< st_ok or st_timdis_range (status_codes)
   call timdis(n, xchl, ychl, vo, ampv0, omega, tl, diff, adiff, status)
end subroutine core_timdis

!> The triggering offset of MLIEN's POINT at M times.
subroutine core_trigger(m, tn, omintr, ometri, atri, btri, xtri, ytri)
   use lienard_core, only: wp
   use mlien, only: trigger_offset
   implicit none
   integer, intent(in) :: m                    !< number of times
   real(wp), intent(in) :: tn(m)               !< T(L+1)
   real(wp), intent(in) :: omintr              !< OMINTR
   real(wp), intent(in) :: ometri              !< OMETRI
   real(wp), intent(in) :: atri                !< ATRI
   real(wp), intent(in) :: btri                !< BTRI
   real(wp), intent(out) :: xtri(m)            !< XTRI
   real(wp), intent(out) :: ytri(m)            !< YTRI
   integer :: i
   do i = 1, m
      call trigger_offset(tn(i), omintr, ometri, atri, btri, xtri(i), ytri(i))
   end do
end subroutine core_trigger

!> Return map on the abscissa: exact flow (mode 3) or the listing's POINT
!> step with DTHETA (modes 0-2, as lookup).
subroutine core_return_map(n, xchl, ychl, mode, dtheta, m, x0, tmax, maxsteps, xleft, xright, period, status)
   use lienard_core, only: wp
   use cycles, only: return_map_exact, return_map_faithful
   implicit none
   integer, intent(in) :: n                    !< number of points of the characteristic
   real(wp), intent(in) :: xchl(n)             !< abscissae
   real(wp), intent(in) :: ychl(n)             !< ordinates, strictly decreasing
   integer, intent(in) :: mode                 !< 0-2 faithful (POINT mode), 3 exact
   real(wp), intent(in) :: dtheta              !< DTHETA (faithful)
   integer, intent(in) :: m                    !< number of starting points
   real(wp), intent(in) :: x0(m)               !< starting abscissae
   real(wp), intent(in) :: tmax                !< time limit per half turn (exact)
   integer, intent(in) :: maxsteps             !< step limit per half turn (faithful)
   real(wp), intent(out) :: xleft(m)           !< left crossing
   real(wp), intent(out) :: xright(m)          !< right crossing, P(X0)
   real(wp), intent(out) :: period(m)          !< time of the revolution
   integer, intent(out) :: status(m)           !< st_ok, or st_no_return when the trajectory does not return
   if (mode == 3) then
      call return_map_exact(n, xchl, ychl, m, x0, tmax, xleft, xright, period, status)
   else
      call return_map_faithful(n, xchl, ychl, dtheta, mode, m, x0, maxsteps, xleft, xright, period, status)
   end if
end subroutine core_return_map

!> The exact flow from (x, y) to the next abscissa crossing in direction ydir.
subroutine core_flow_exact(n, xchl, ychl, ydir, tmax, x, y, t, status)
   use lienard_core, only: wp
   use cycles, only: flow_exact
   implicit none
   integer, intent(in) :: n                    !< number of points
   real(wp), intent(in) :: xchl(n)             !< abscissae
   real(wp), intent(in) :: ychl(n)             !< ordinates
   integer, intent(in) :: ydir                 !< -1 downward crossing, +1 upward
   real(wp), intent(in) :: tmax                !< time limit
   real(wp), intent(inout) :: x                !< X
   real(wp), intent(inout) :: y                !< Y
   real(wp), intent(inout) :: t                !< T
   integer, intent(out) :: status              !< st_ok or st_no_return (status_codes)
   call flow_exact(n, xchl, ychl, ydir, tmax, x, y, t, status)
end subroutine core_flow_exact

!> TRC: readings to time (s) and corrected displacements (mm).
subroutine core_trc_calibrate(nn, nt, nh, nhn, ho, hon, vel, sensf, sensn, an1, an2, t, x, xn)
   use lienard_core, only: wp
   use trc, only: trc_calibrate
   implicit none
   integer, intent(in) :: nn                   !< number of points
   integer, intent(in) :: nt(nn)               !< NT readings
   integer, intent(in) :: nh(nn)               !< NH readings
   integer, intent(in) :: nhn(nn)              !< NHN readings
   real(wp), intent(in) :: ho                  !< HO
   real(wp), intent(in) :: hon                 !< HON
   real(wp), intent(in) :: vel                 !< VEL, paper speed (mm/s)
   real(wp), intent(in) :: sensf               !< SENSF
   real(wp), intent(in) :: sensn               !< SENSN
   real(wp), intent(in) :: an1                 !< AN1
   real(wp), intent(in) :: an2                 !< AN2
   real(wp), intent(out) :: t(nn)              !< T (s)
   real(wp), intent(out) :: x(nn)              !< X (mm)
   real(wp), intent(out) :: xn(nn)             !< XN (mm)
   call trc_calibrate(nn, nt, nh, nhn, ho, hon, vel, sensf, sensn, an1, an2, t, x, xn)
end subroutine core_trc_calibrate

!> TRC: velocities, BELFIT, the reverse Lienard construction, EL and ELN.
subroutine core_trc_reduce(nn, t, x, xn, omnh, omnv, xs, v, vn, vln, vnln, am, xx, yy, xxn, yyn, &
                           xlnr, xnlnr, amt, amtn, el, eln, has_eln, iel, ieln, status, where, xx0, xxn0)
   use lienard_core, only: wp
   use trc, only: trc_reduce
   implicit none
   integer, intent(in) :: nn                   !< number of points
   real(wp), intent(in) :: t(nn)               !< T (s)
   real(wp), intent(in) :: x(nn)               !< X (mm)
   real(wp), intent(in) :: xn(nn)              !< XN (mm)
   real(wp), intent(in) :: omnh                !< OMNH (rad/s)
   real(wp), intent(in) :: omnv                !< OMNV (rad/s)
   real(wp), intent(out) :: xs(nn)             !< X after BELFIT (unchanged values)
   real(wp), intent(out) :: v(nn)              !< V (mm/s)
   real(wp), intent(out) :: vn(nn)             !< VN (mm/s)
   real(wp), intent(out) :: vln(nn)            !< VLN, smoothed
   real(wp), intent(out) :: vnln(nn)           !< VNLN
   real(wp), intent(out) :: am(nn)             !< AM
   real(wp), intent(out) :: xx(nn)             !< XX
   real(wp), intent(out) :: yy(nn)             !< YY
   real(wp), intent(out) :: xxn(nn)            !< XXN
   real(wp), intent(out) :: yyn(nn)            !< YYN
   real(wp), intent(out) :: xlnr(nn)           !< XLNR
   real(wp), intent(out) :: xnlnr(nn)          !< XNLNR
   real(wp), intent(out) :: amt(nn)            !< AMT
   real(wp), intent(out) :: amtn(nn)           !< AMTN
   real(wp), intent(out) :: el                 !< EL
   real(wp), intent(out) :: eln                !< ELN
   integer, intent(out) :: has_eln             !< 1 when ELN was found
   integer, intent(out) :: iel                 !< point of the + to - sign change (1-based)
   integer, intent(out) :: ieln                !< point of the - to + sign change (0: none)
   integer, intent(out) :: status              !< st_ok or a TRC code st_trc_* (status_codes)
   integer, intent(out) :: where               !< point of the error
   real(wp), intent(out) :: xx0(nn)            !< XX before the shift by EL
   real(wp), intent(out) :: xxn0(nn)           !< XXN before the shift by ELN
   xs = x
   call trc_reduce(nn, t, xs, xn, omnh, omnv, v, vn, vln, vnln, am, xx, yy, xxn, yyn, &
                   xlnr, xnlnr, amt, amtn, el, eln, has_eln, iel, ieln, status, where, xx0, xxn0)
end subroutine core_trc_reduce

!> BELFIT: group-fitting smoothing of Y as a function of X.
subroutine core_belfit(n, x, y, ys, status, where)
   use lienard_core, only: wp
   use trc, only: belfit
   implicit none
   integer, intent(in) :: n                    !< number of points
   real(wp), intent(in) :: x(n)                !< X
   real(wp), intent(in) :: y(n)                !< Y
   real(wp), intent(out) :: ys(n)              !< Y smoothed
   integer, intent(out) :: status              !< st_ok or a TRC code st_trc_* (status_codes)
   integer, intent(out) :: where               !< first point of a degenerate group
   real(wp) :: xxx(n), yw(n)
   yw = y
   call belfit(n, x, yw, xxx, ys, status, where)
end subroutine core_belfit

!> LSQFIT: least-squares polynomial of degree kdeg by orthogonal polynomials.
subroutine core_lsqfit(number, kdeg, x, y, coef)
   use lienard_core, only: wp
   use trc, only: lsqfit
   implicit none
   integer, intent(in) :: number               !< number of points
   integer, intent(in) :: kdeg                 !< degree
   real(wp), intent(in) :: x(number)           !< X
   real(wp), intent(in) :: y(number)           !< Y
   real(wp), intent(out) :: coef(kdeg + 1)     !< coefficients of X**0..X**kdeg
   real(wp) :: fitpol(kdeg + 2)
   call lsqfit(number, kdeg, x, y, fitpol)
   coef = fitpol(2:kdeg + 2)
end subroutine core_lsqfit

!> The generalised 1-DoF slider of `lieng diagnose` (module slider).
subroutine core_slider(n, dt, nsub, vd, load, wn, zeta, fs, ns, sg, fg, delta, dg, age_a, age_tau, age_r, age_v, &
                       kx, xref, creep0, creep1, creep_m, x0, t0, x, v, state, status)
   use lienard_core, only: wp
   use slider, only: slider_run
   implicit none
   integer, intent(in) :: n
   real(wp), intent(in) :: dt
   integer, intent(in) :: nsub
   real(wp), intent(in) :: vd(n), load(n)
   real(wp), intent(in) :: wn, zeta, fs
   integer, intent(in) :: ns
   real(wp), intent(in) :: sg(ns), fg(ns), dg(ns)
   real(wp), intent(in) :: delta, age_a, age_tau, age_r, age_v, kx, xref, creep0, creep1, creep_m, x0, t0
   real(wp), intent(out) :: x(n), v(n)
   integer, intent(out) :: state(n)
   integer, intent(out) :: status              !< st_ok, st_bad_argument or st_nonfinite_state (status_codes)
   call slider_run(n, dt, nsub, vd, load, wn, zeta, fs, ns, sg, fg, delta, dg, age_a, age_tau, age_r, age_v, &
                   kx, xref, creep0, creep1, creep_m, x0, t0, x, v, state, status)
end subroutine core_slider

!> The 2-DoF dual-pin-on-disc model (module twodof).
subroutine core_twodof(n, dt, nsub, m, c, k, fn, kn, mus, muk, v0, eta, s0, &
                       x1, v1, x2, v2, fnorm, ffric, state, nswitch, status)
   use lienard_core, only: wp
   use twodof, only: twodof_run
   implicit none
   integer, intent(in) :: n
   real(wp), intent(in) :: dt
   integer, intent(in) :: nsub
   real(wp), intent(in) :: m(2, 2), c(2, 2), k(2, 2)
   real(wp), intent(in) :: fn, kn, mus, muk, v0, eta
   real(wp), intent(in) :: s0(4)
   real(wp), intent(out) :: x1(n), v1(n), x2(n), v2(n), fnorm(n), ffric(n)
   integer, intent(out) :: state(n)
   integer, intent(out) :: nswitch, status
   call twodof_run(n, dt, nsub, m, c, k, fn, kn, mus, muk, v0, eta, s0, x1, v1, x2, v2, fnorm, ffric, state, &
                   nswitch, status)
end subroutine core_twodof

!> The 2-DoF (or n-DoF) rig propagated exactly between switches (module twodof).
subroutine core_twodof_exact(n, nz, nsub, h, kord, a, phi, coef, gs, nev, iv, v0, eta, mus, hold, nrow, z0, &
                             z, state, nswitch, status)
   use lienard_core, only: wp
   use twodof, only: twodof_exact
   implicit none
   integer, intent(in) :: n, nz, nsub, kord
   real(wp), intent(in) :: h
   real(wp), intent(in) :: a(nz, nz, 3), phi(nz, nz, 3), coef(0:kord, nz, 2, 3), gs(nz, 4, 2, 3)
   integer, intent(in) :: nev(3), iv
   real(wp), intent(in) :: v0, eta, mus
   real(wp), intent(in) :: hold(nz), nrow(nz), z0(nz)
   real(wp), intent(out) :: z(nz, n)
   integer, intent(out) :: state(n)
   integer, intent(out) :: nswitch, status
   call twodof_exact(n, nz, nsub, h, kord, a, phi, coef, gs, nev, iv, v0, eta, mus, hold, nrow, z0, &
                     z, state, nswitch, status)
end subroutine core_twodof_exact
