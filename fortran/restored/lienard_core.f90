!> Shared core of LIENG-1 (thesis App. 4) and MLIEN / LIENG-2 (App. 6).
!>
!> S. S. Antoniou, "The mechanism of frictional oscillations", PhD thesis,
!> Imperial College London, 1971.  This module holds what the two programs
!> have in common:
!>
!>  * the slopes of the characteristic line and the search for its centre of
!>    symmetry (PINPUT of LIENG-1, statements 45-2001; CHALIN of MLIEN);
!>  * the look-up of the characteristic at the velocity of the current point
!>    (POINT, statements 305-342);
!>  * the Lienard construction step (POINT, statements 340-400).
!>
!> The arithmetic is the listing's, in double precision (the CDC 6600 word
!> was 60 bits).  Where the 1971 code is undefined (loops with no bound,
!> division by zero) the routines stop and return a status code instead;
!> every such place is listed in fortran/RESTORATION.md.
module lienard_core
   use iso_fortran_env, only: wp => real64
   use status_codes, only: st_ok, st_infinite_slope, st_no_negative_slope, st_centre_undefined, &
                           st_singular_point, st_dt_undefined, st_bad_size, st_arcos_domain, st_omega_zero, &
                           st_timdis_range
   implicit none
   private
   ! the status codes (status_codes), re-exported for the programs built on this module
   public :: st_ok, st_infinite_slope, st_no_negative_slope, st_centre_undefined, st_singular_point, &
             st_dt_undefined, st_bad_size, st_arcos_domain, st_omega_zero, st_timdis_range

   public :: wp
   public :: char_slopes, centre_of_symmetry, xb_listing, xb_bisect, point_step, point_advance, band_line

   !> Modes of the POINT step.
   !> 0 (listing): the listing's linear scan (DO 315 JJ=1,N) and its
   !>   trigonometry, DX = |DS*SIN(ATAN(Y/XK))|: the 1971 arithmetic.
   !> 1 (bisect): the same arithmetic; the segment is found by bisection,
   !>   which gives the same JJ when YCHL decreases strictly (checked before
   !>   the call): bit-identical results.
   !> 2 (fast): bisection and DX = DTHETA*|Y|, DY = DTHETA*|XK|, equal to the
   !>   listing's DX, DY in exact arithmetic (|sin(atan u)| = |u|/sqrt(1+u^2)),
   !>   without the three transcendental calls; differs in the last bits.
   integer, parameter, public :: lookup_listing = 0, lookup_bisect = 1, mode_fast = 2

   !> Relative difference below which SLOPE(LLL) and SLOPE(MMM) are equal in
   !> the centre search (rounding, not geometry; see centre_of_symmetry).
   real(wp), parameter, public :: slope_rtol = 1.0e-9_wp

contains

   !> Slopes of the characteristic line, DO 90 of PINPUT:
   !> SLOPE(J) = (YCHL(J)-YCHL(J+1)) / (XCHL(J)-XCHL(J+1)), J = 1..N-1.
   pure subroutine char_slopes(n, xchl, ychl, slope, status, where)
      integer, intent(in) :: n                 !< number of points of the characteristic
      real(wp), intent(in) :: xchl(n)          !< abscissae XCHL(1..N) (displacement)
      real(wp), intent(in) :: ychl(n)          !< ordinates YCHL(1..N) (velocity)
      real(wp), intent(out) :: slope(n)        !< SLOPE(1..N-1); SLOPE(N) is set to 0
      integer, intent(out) :: status           !< st_ok or st_infinite_slope
      integer, intent(out) :: where            !< J of the offending segment, else 0
      integer :: j
      real(wp) :: dxchl, dychl

      status = st_ok
      where = 0
      slope = 0.0_wp
      do j = 1, n - 1
         dxchl = xchl(j) - xchl(j + 1)
         dychl = ychl(j) - ychl(j + 1)
         if (dxchl == 0.0_wp) then
            status = st_infinite_slope
            where = j
            return
         end if
         slope(j) = dychl/dxchl
      end do
   end subroutine char_slopes

   !> Centre of symmetry of the characteristic (PINPUT statements 135-2001).
   !>
   !> I: the negative-slope segment with the largest slope; LLL..MMM: the run
   !> of negative slopes around it; then the point on the steeper end of the
   !> run where the slope equals the slope at the other end (linear
   !> interpolation of the slope between two neighbouring points), and the
   !> middle of that point and the other end gives XMDL, YMDL.
   pure subroutine centre_of_symmetry(n, xchl, ychl, slope, isel, lll, mmm, branch, &
                                      xmdl, ymdl, status, where)
      integer, intent(in) :: n                 !< number of points (N >= 3)
      real(wp), intent(in) :: xchl(n)          !< abscissae of the characteristic
      real(wp), intent(in) :: ychl(n)          !< ordinates of the characteristic
      real(wp), intent(out) :: slope(n)        !< slopes as computed by char_slopes
      integer, intent(out) :: isel             !< I: the negative-slope segment with the largest slope
      integer, intent(out) :: lll              !< first segment of the negative-slope run
      integer, intent(out) :: mmm              !< last segment of the negative-slope run
      integer, intent(out) :: branch           !< 0: SLOPE(LLL)=SLOPE(MMM) (FORMAT 1006); -1: .LT. (1007); +1: .GT. (1008)
      real(wp), intent(out) :: xmdl            !< XMDL, abscissa of the centre of symmetry
      real(wp), intent(out) :: ymdl            !< YMDL, ordinate (the mean driving velocity)
      integer, intent(out) :: status           !< st_ok or an error code
      integer, intent(out) :: where            !< segment index the error refers to
      integer :: k, i, l, ll, mm
      real(wp) :: a, slopex, aa, bb, cc, dd, xx, yy

      aa = 0.0_wp; bb = 0.0_wp

      isel = 0; lll = 0; mmm = 0; branch = 0
      xmdl = 0.0_wp; ymdl = 0.0_wp
      if (n < 3) then
         status = st_bad_size
         where = n
         slope = 0.0_wp
         return
      end if
      call char_slopes(n, xchl, ychl, slope, status, where)
      if (status /= st_ok) return
      k = n - 1

      ! 135: first negative slope.  The listing tests I.GE.K after the
      ! increment, so SLOPE(K) is never a starting point (kept as listed).
      i = 1
      do
         if (slope(i) < 0.0_wp) exit
         i = i + 1
         if (i >= k) then
            status = st_no_negative_slope
            where = 0
            return
         end if
      end do

      ! 140-170: the negative slope with the largest value.  The listing's
      ! loop 141 has no bound when the slopes after L are not negative; the
      ! intended end of the scan is L > K (statement 170).
      search: do
         l = i + 1
         do
            if (l > k) exit search
            if (slope(l) < 0.0_wp) then
               a = slope(i) - slope(l)
               if (a < 0.0_wp) then
                  i = l
                  cycle search
               end if
            end if
            l = l + 1
         end do
      end do search
      isel = i

      ! 185-200: the run of negative slopes around I.  The listing's loops have
      ! no bound; the run stops at segment 1 and at segment K.
      ll = i - 1
      do while (ll >= 1)
         if (slope(ll) >= 0.0_wp) exit
         ll = ll - 1
      end do
      lll = ll + 1
      mm = i + 1
      do while (mm <= k)
         if (slope(mm) >= 0.0_wp) exit
         mm = mm + 1
      end do
      mmm = mm - 1

      ! The listing compares SLOPE(LLL) and SLOPE(MMM) exactly.  Slopes of a
      ! straight run differ only by rounding (more so after TIMDIS has moved
      ! the line many times), and then AA/BB at 210/220 is a ratio of two
      ! rounding errors that throws the centre anywhere, or divides by zero.
      ! Within slope_rtol the slopes are taken as equal (statement 2001's
      ! branch), which is the listing's intent; RESTORATION.md, P19.
      if (abs(slope(mmm) - slope(lll)) <= slope_rtol*max(abs(slope(lll)), abs(slope(mmm)))) then
         branch = 0
      else if (slope(lll) < slope(mmm)) then
         ! 210
         branch = -1
         slopex = slope(mmm)
         aa = slopex - slope(lll)
         bb = slope(lll + 1) - slope(lll)
      else
         ! 220
         branch = 1
         slopex = slope(lll)
         aa = slopex - slope(mmm - 1)
         bb = slope(mmm) - slope(mmm - 1)
      end if
      if (branch /= 0 .and. bb == 0.0_wp) then
         ! the listing divides by zero: the centre is undefined
         status = st_centre_undefined
         where = merge(lll, mmm - 1, branch < 0)
         return
      end if
      if (branch < 0) then
         cc = xchl(lll + 1) - xchl(lll)
         xx = (aa/bb)*cc + xchl(lll)
         dd = ychl(lll + 1) - ychl(lll)
         yy = (aa/bb)*dd + ychl(lll)
         xmdl = (xx + xchl(mmm))/2.0_wp
         ymdl = (yy + ychl(mmm))/2.0_wp
      else if (branch > 0) then
         cc = xchl(mmm) - xchl(mmm - 1)
         xx = (aa/bb)*cc + xchl(mmm - 1)
         dd = ychl(mmm) - ychl(mmm - 1)
         yy = (aa/bb)*dd + ychl(mmm - 1)
         xmdl = (xx + xchl(lll))/2.0_wp
         ymdl = (yy + ychl(lll))/2.0_wp
      else
         xmdl = (xchl(lll) + xchl(mmm))/2.0_wp
         ymdl = (ychl(lll) + ychl(mmm))/2.0_wp
      end if
      status = st_ok
      where = 0
   end subroutine centre_of_symmetry

   !> XB, the abscissa of the characteristic at velocity Y, exactly as POINT
   !> statements 305-342 find it: the first JJ with Y >= YCHL(JJ); equality
   !> takes XCHL(JJ); otherwise linear interpolation between JJ-1 and JJ;
   !> above YCHL(1) XB = XCHL(1); below every YCHL XB = XCHL(N).
   pure function xb_listing(n, xchl, ychl, y) result(xb)
      integer, intent(in) :: n                 !< number of points
      real(wp), intent(in) :: xchl(n)          !< abscissae of the characteristic
      real(wp), intent(in) :: ychl(n)          !< ordinates of the characteristic
      real(wp), intent(in) :: y                !< velocity of the current point Y(L)
      real(wp) :: xb                           !< abscissa of S, the foot of the construction
      integer :: jj
      real(wp) :: c

      do jj = 1, n
         c = y - ychl(jj)
         if (c < 0.0_wp) cycle
         xb = xb_at(n, xchl, ychl, y, jj, c)
         return
      end do
      xb = xchl(n)
   end function xb_listing

   !> The same XB as xb_listing, finding JJ by bisection.  Valid only for a
   !> strictly decreasing YCHL, where the first JJ with YCHL(JJ) <= Y is unique.
   pure function xb_bisect(n, xchl, ychl, y) result(xb)
      integer, intent(in) :: n                 !< number of points
      real(wp), intent(in) :: xchl(n)          !< abscissae of the characteristic
      real(wp), intent(in) :: ychl(n)          !< ordinates, strictly decreasing
      real(wp), intent(in) :: y                !< velocity of the current point
      real(wp) :: xb                           !< abscissa of S
      integer :: lo, hi, mid

      if (y - ychl(n) < 0.0_wp) then
         xb = xchl(n)
         return
      end if
      ! invariant: y - ychl(hi) >= 0, and y - ychl(lo-1) < 0 for lo > 1
      lo = 1
      hi = n
      do while (lo < hi)
         mid = (lo + hi)/2
         if (y - ychl(mid) < 0.0_wp) then
            lo = mid + 1
         else
            hi = mid
         end if
      end do
      xb = xb_at(n, xchl, ychl, y, lo, y - ychl(lo))
   end function xb_bisect

   !> Statements 320-335 for a found JJ (C = Y - YCHL(JJ) >= 0).
   pure function xb_at(n, xchl, ychl, y, jj, c) result(xb)
      integer, intent(in) :: n, jj
      real(wp), intent(in) :: xchl(n), ychl(n), y, c
      real(wp) :: xb
      if (c == 0.0_wp) then
         xb = xchl(jj)                                  ! 320
      else if (jj == 1) then
         xb = xchl(1)                                   ! 335
      else                                              ! 330
         xb = ((xchl(jj) - xchl(jj - 1))*(ychl(jj - 1) - y)/(ychl(jj - 1) - ychl(jj))) &
              + xchl(jj - 1)
      end if
   end function xb_at

   !> One step of Lienard's construction, POINT statements 305-400.
   !>
   !> From P = (X, Y) the foot S = (XB, 0) is found on the characteristic; the
   !> next point lies on the tangent to the circle about S, a distance
   !> DS = DTHETA*|SP| away, in the quadrant-determined direction; the time
   !> increment is DT = |2*DX / (2*Y - DY)|.
   pure subroutine point_step(n, xchl, ychl, dtheta, x, y, t, lookup, &
                              xn, yn, tn, r, xb, xk, ds, dx, dy, dt, status)
      integer, intent(in) :: n                 !< number of points of the characteristic
      real(wp), intent(in) :: xchl(n)          !< abscissae of the characteristic
      real(wp), intent(in) :: ychl(n)          !< ordinates of the characteristic
      real(wp), intent(in) :: dtheta           !< DTHETA, angle increment (rad)
      real(wp), intent(in) :: x                !< X(L)
      real(wp), intent(in) :: y                !< Y(L)
      real(wp), intent(in) :: t                !< T(L)
      integer, intent(in) :: lookup            !< lookup_listing, lookup_bisect or mode_fast
      real(wp), intent(out) :: xn              !< X(L+1)
      real(wp), intent(out) :: yn              !< Y(L+1)
      real(wp), intent(out) :: tn              !< T(L+1) = T(L) + DT
      real(wp), intent(out) :: r               !< R = |SP|
      real(wp), intent(out) :: xb              !< XB, abscissa of S
      real(wp), intent(out) :: xk              !< XK = X(L) - XB
      real(wp), intent(out) :: ds              !< DS = DTHETA*R
      real(wp), intent(out) :: dx              !< DX = |DS sin(THETA)|
      real(wp), intent(out) :: dy              !< DY = |DS cos(THETA)|
      real(wp), intent(out) :: dt              !< DT, the time increment
      integer, intent(out) :: status           !< st_ok, st_singular_point or st_dt_undefined
      real(wp) :: theta, den

      status = st_ok
      if (lookup == lookup_bisect .or. lookup == mode_fast) then
         xb = xb_bisect(n, xchl, ychl, y)
      else
         xb = xb_listing(n, xchl, ychl, y)
      end if
      xk = x - xb                                       ! 340
      r = sqrt(y**2 + xk**2)
      ds = 0.0_wp; dx = 0.0_wp; dy = 0.0_wp; dt = 0.0_wp
      xn = x; yn = y; tn = t
      if (xk == 0.0_wp .and. y == 0.0_wp) then
         status = st_singular_point
         return
      end if
      ds = dtheta*r
      if (lookup == mode_fast) then
         dx = dtheta*abs(y)
         dy = dtheta*abs(xk)
      else
         theta = atan(y/xk)
         dx = abs(ds*sin(theta))
         dy = abs(ds*cos(theta))
      end if
      den = 2.0_wp*y - dy
      if (den == 0.0_wp) then
         status = st_dt_undefined
         return
      end if
      dt = abs((2.0_wp*dx)/den)
      tn = t + dt
      if (xk >= 0.0_wp .and. y >= 0.0_wp) then         ! 360
         xn = x + dx
         yn = y - dy
      else if (xk >= 0.0_wp .and. y < 0.0_wp) then     ! 370
         xn = x - dx
         yn = y - dy
      else if (xk < 0.0_wp .and. y < 0.0_wp) then      ! 380
         xn = x - dx
         yn = y + dy
      else                                              ! 390
         xn = x + dx
         yn = y + dy
      end if
   end subroutine point_step

   !> NSTEPS POINT steps from (X, Y, T), keeping only the last point: the
   !> step loop of the main program without the arrays (used where only the
   !> end point matters, and to measure the step rate).
   pure subroutine point_advance(n, xchl, ychl, dtheta, nsteps, lookup, x, y, t, status, where)
      integer, intent(in) :: n                 !< number of points of the characteristic
      real(wp), intent(in) :: xchl(n)          !< abscissae of the characteristic
      real(wp), intent(in) :: ychl(n)          !< ordinates of the characteristic
      real(wp), intent(in) :: dtheta           !< DTHETA
      integer, intent(in) :: nsteps            !< number of steps
      integer, intent(in) :: lookup            !< lookup_listing or lookup_bisect
      real(wp), intent(inout) :: x             !< X, advanced in place
      real(wp), intent(inout) :: y             !< Y, advanced in place
      real(wp), intent(inout) :: t             !< T (uncorrected), advanced in place
      integer, intent(out) :: status           !< st_ok or the failing status
      integer, intent(out) :: where            !< the failing step, else 0
      integer :: l
      real(wp) :: xn, yn, tn, r, xb, xk, ds, dx, dy, dt

      status = st_ok
      where = 0
      if (lookup == mode_fast) then
         call fast_advance(n, xchl, ychl, dtheta, nsteps, x, y, t, status, where)
         return
      end if
      do l = 1, nsteps
         call point_step(n, xchl, ychl, dtheta, x, y, t, lookup, xn, yn, tn, r, xb, xk, ds, dx, dy, dt, status)
         if (status /= st_ok) then
            where = l
            return
         end if
         x = xn
         y = yn
         t = tn
      end do
   end subroutine point_advance

   !> The line of band J of the characteristic, X = A + B*Y for YLO <= Y < YHI:
   !> band 0 above YCHL(1) and band N below YCHL(N) hold the end values
   !> (POINT reads XCHL(1) above YCHL(1), XCHL(N) below YCHL(N)); band J,
   !> 1 <= J < N, is the segment from point J to point J+1.
   pure subroutine band_line(n, xchl, ychl, j, a, b, ylo, yhi)
      integer, intent(in) :: n                 !< number of points of the characteristic
      real(wp), intent(in) :: xchl(n)          !< abscissae of the characteristic
      real(wp), intent(in) :: ychl(n)          !< ordinates, strictly decreasing
      integer, intent(in) :: j                 !< the band, 0..N
      real(wp), intent(out) :: a, b            !< the band's line X = A + B*Y
      real(wp), intent(out) :: ylo, yhi        !< its velocity limits
      if (j == 0) then
         a = xchl(1); b = 0.0_wp; ylo = ychl(1); yhi = huge(1.0_wp)
      else if (j == n) then
         a = xchl(n); b = 0.0_wp; ylo = -huge(1.0_wp); yhi = ychl(n)
      else
         b = (xchl(j + 1) - xchl(j))/(ychl(j + 1) - ychl(j))
         a = xchl(j) - b*ychl(j)
         ylo = ychl(j + 1); yhi = ychl(j)
      end if
   end subroutine band_line

   !> NSTEPS steps of mode_fast in one loop, for speed: the band of the
   !> characteristic is followed from the previous step (a hunt, not a
   !> bisection), each band's line is precomputed as XB = A + B*Y (one
   !> multiply-add in place of the listing's division), and the quadrant
   !> signs are folded: X(L+1) = X + DTHETA*Y, Y(L+1) = Y - DTHETA*XK, which
   !> equal X +- DX, Y -+ DY of statements 360-390 exactly.  Same steps as
   !> point_step's mode_fast to the rounding of XB (about 1e-16 relative).
   pure subroutine fast_advance(n, xchl, ychl, dtheta, nsteps, x, y, t, status, where)
      integer, intent(in) :: n                 !< number of points of the characteristic (>= 2)
      real(wp), intent(in) :: xchl(n)          !< abscissae of the characteristic
      real(wp), intent(in) :: ychl(n)          !< ordinates, strictly decreasing
      real(wp), intent(in) :: dtheta           !< DTHETA
      integer, intent(in) :: nsteps            !< number of steps
      real(wp), intent(inout) :: x             !< X, advanced in place
      real(wp), intent(inout) :: y             !< Y, advanced in place
      real(wp), intent(inout) :: t             !< T (uncorrected), advanced in place
      integer, intent(out) :: status           !< st_ok, st_singular_point or st_dt_undefined
      integer, intent(out) :: where            !< the failing step, else 0
      real(wp) :: a(0:n), b(0:n), lo(0:n), hi(0:n), xb, xk, dx, dy, den, xl, yl, tl
      integer :: k, l

      ! band k: lo(k) <= Y < hi(k); k = 0 above YCHL(1), k = N below YCHL(N)
      do k = 0, n
         call band_line(n, xchl, ychl, k, a(k), b(k), lo(k), hi(k))
      end do
      status = st_ok
      where = 0
      k = n/2
      xl = x; yl = y; tl = t                   ! locals: the loop keeps them in registers
      do l = 1, nsteps
         do while (k < n .and. yl < lo(k))
            k = k + 1
         end do
         do while (k > 0 .and. yl >= hi(k))
            k = k - 1
         end do
         xb = a(k) + b(k)*yl
         xk = xl - xb
         dx = dtheta*abs(yl)
         dy = dtheta*abs(xk)
         den = 2.0_wp*yl - dy
         if ((xk == 0.0_wp .and. yl == 0.0_wp) .or. den == 0.0_wp) then
            status = merge(st_singular_point, st_dt_undefined, xk == 0.0_wp .and. yl == 0.0_wp)
            where = l
            exit
         end if
         tl = tl + abs((2.0_wp*dx)/den)
         xl = xl + dtheta*yl
         yl = yl - dtheta*xk
      end do
      x = xl; y = yl; t = tl
   end subroutine fast_advance

end module lienard_core
