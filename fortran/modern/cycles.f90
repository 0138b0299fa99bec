!> Return maps on the abscissa for limit cycles (modern, beside the 1971 code).
!>
!> The equation of the Lienard plane, dX/dT = Y, dY/dT = -(X - C(Y)), with
!> C(Y) the characteristic as POINT reads it (linear between points, XCHL(1)
!> above YCHL(1), XCHL(N) below YCHL(N)).  From (X0, 0) right of the
!> equilibrium the trajectory turns clockwise: down, across the abscissa on
!> the left (XLEFT), up, and back across it on the right (XRIGHT = P(X0)).
!>
!> Two ways to follow it:
!>  * exact: on each band YCHL(J+1) <= Y <= YCHL(J) the characteristic is
!>    X = A + B*Y and the equation is linear, u'' - B u' + u = 0 with
!>    u = X - A; its closed-form solution is evaluated and the crossings of
!>    the band limits and of the abscissa are located by bisection to
!>    machine precision;
!>  * faithful: the listing's POINT step with the deck's DTHETA, crossings by
!>    linear interpolation, time as steps*DTHETA (the angle turned about S).
module cycles
   use lienard_core, only: wp, point_step, st_ok, band_line
   use status_codes, only: st_no_return
   implicit none
   private
   public :: return_map_exact, return_map_faithful, flow_exact

   real(wp), parameter :: hstep = 0.02_wp      ! search step in time (units 1/omega_n)

contains

   !> Band of velocity y: 0 above YCHL(1), J for YCHL(J+1) <= y < YCHL(J), N below YCHL(N).
   pure integer function band_of(n, ychl, y, dir) result(j)
      integer, intent(in) :: n
      real(wp), intent(in) :: ychl(n), y
      integer, intent(in) :: dir               ! on a limit: +1 take the band above, -1 below
      integer :: k
      j = n
      do k = 1, n
         if (y > ychl(k) .or. (y == ychl(k) .and. dir > 0)) then
            j = k - 1
            return
         end if
      end do
   end function band_of

   !> Closed-form solution of u'' - b u' + u = 0 from (u0, y0) after time t.
   !> For a steep band (|b| > 2, real roots l1 > l2 with l1*l2 = 1) and w*t > 1
   !> the solution is written with exp(l1 t) and exp(l2 t), the smaller root
   !> in magnitude as 1/(the larger): exp(sg t)*cosh(w t) would overflow to
   !> inf*0 on a steep stick part (|b| of thousands) long before the point
   !> leaves it.
   pure subroutine linear_flow(b, u0, y0, t, u, y)
      real(wp), intent(in) :: b, u0, y0, t
      real(wp), intent(out) :: u, y
      real(wp) :: sg, disc, w, c, s, e, l1, l2, e1, e2
      sg = 0.5_wp*b
      disc = sg*sg - 1.0_wp
      if (disc > 0.0_wp) then
         w = sqrt(disc)
         if (w*t > 1.0_wp) then
            if (sg >= 0.0_wp) then
               l1 = sg + w
               l2 = 1.0_wp/l1
            else
               l2 = sg - w
               l1 = 1.0_wp/l2
            end if
            e1 = exp(l1*t)
            e2 = exp(l2*t)
            c = 0.5_wp*(e1 + e2)                ! exp(sg t) cosh(w t)
            s = 0.5_wp*(e1 - e2)/w              ! exp(sg t) sinh(w t)/w
            u = u0*c + (y0 - sg*u0)*s
            y = y0*c + (sg*y0 - u0)*s
            return
         end if
      end if
      if (disc < 0.0_wp) then
         w = sqrt(-disc)
         c = cos(w*t)
         s = sin(w*t)/w
      else if (disc > 0.0_wp) then
         w = sqrt(disc)
         c = cosh(w*t)
         s = sinh(w*t)/w
      else
         c = 1.0_wp
         s = t
      end if
      e = exp(sg*t)
      u = e*(u0*c + (y0 - sg*u0)*s)
      y = e*(y0*c + (sg*y0 - u0)*s)
   end subroutine linear_flow

   !> Follow the exact flow from (x, y) until Y crosses 0 in direction
   !> ydir (-1: from above to below, +1: from below to above) or time tmax
   !> passes.  On return (x, y) is the crossing (y = 0) and t the time.
   pure subroutine flow_exact(n, xchl, ychl, ydir, tmax, x, y, t, status)
      integer, intent(in) :: n                 !< number of points of the characteristic
      real(wp), intent(in) :: xchl(n)          !< abscissae
      real(wp), intent(in) :: ychl(n)          !< ordinates, strictly decreasing
      integer, intent(in) :: ydir              !< direction of the abscissa crossing sought
      real(wp), intent(in) :: tmax             !< time limit
      real(wp), intent(inout) :: x             !< X, advanced
      real(wp), intent(inout) :: y             !< Y, advanced
      real(wp), intent(inout) :: t             !< T, advanced
      integer, intent(out) :: status           !< st_ok or st_no_return
      integer :: j, k, ev, nev
      real(wp) :: a, b, ylo, yhi, u0, y0, ta, tb, tm, u, yy, ua, ya, t0, ymove, yref, hb
      logical :: hit

      status = st_ok
      ! the direction of motion in Y decides the band on a limit
      ymove = -(x - xb_of(n, xchl, ychl, y))
      j = band_of(n, ychl, y, merge(1, -1, ymove > 0.0_wp))
      t0 = t
      nev = 0
      do while (t - t0 < tmax)
         ! a guard: a motion that stops advancing in time is not followed forever
         nev = nev + 1
         if (nev > 10000000) exit
         call band_line(n, xchl, ychl, j, a, b, ylo, yhi)
         u0 = x - a
         y0 = y
         ta = 0.0_wp
         yref = y0
         hit = .false.
         ev = 0
         ! a steep band with a growing mode (b > 2): exp(l1 t) must not overflow
         ! between samples, so the search step shrinks to 20/l1
         hb = hstep
         if (b > 2.0_wp) hb = min(hstep, 20.0_wp/(0.5_wp*b + sqrt(0.25_wp*b*b - 1.0_wp)))
         do k = 1, 1000000
            tb = ta + hb
            call linear_flow(b, u0, y0, tb, u, yy)
            call classify(yy, yref, ev)
            if (ev /= 0) then
               hit = .true.
               exit
            end if
            ta = tb
            yref = yy
            if (t + tb - t0 > tmax) exit
         end do
         if (.not. hit) then
            call linear_flow(b, u0, y0, ta, u, yy)
            x = u + a; y = yy; t = t + ta
            status = st_no_return
            return
         end if
         ! the first event in (ta, tb]: each level crossed between the two
         ! samples is located by the Illinois method on y(t) - level (a few
         ! evaluations of the closed form, where bisection took ~50); the
         ! earliest crossing wins
         tm = tb
         k = 0
         if (ydir < 0 .and. yref > 0.0_wp .and. yy <= 0.0_wp) call earliest(1, 0.0_wp, tm, k)
         if (ydir > 0 .and. yref < 0.0_wp .and. yy >= 0.0_wp) call earliest(1, 0.0_wp, tm, k)
         if (yy > yhi) call earliest(2, yhi, tm, k)
         if (yy < ylo) call earliest(3, ylo, tm, k)
         ev = k
         tb = tm
         call linear_flow(b, u0, y0, tb, u, yy)
         t = t + tb
         x = u + a
         select case (ev)
         case (1)              ! the abscissa
            y = 0.0_wp
            return
         case (2)              ! up into the band above
            y = yhi
            j = j - 1
         case (3)              ! down into the band below
            y = ylo
            j = j + 1
         end select
      end do
      status = st_no_return

   contains

      !> Locate the crossing of ``level`` (event e) in (ta, tb] and keep it
      !> in (tm, k) if it is the earliest so far.
      pure subroutine earliest(e, level, tm, k)
         integer, intent(in) :: e
         real(wp), intent(in) :: level
         real(wp), intent(inout) :: tm
         integer, intent(inout) :: k
         real(wp) :: tr
         tr = illinois(b, u0, y0, level, ta, tb, yref - level, yy - level)
         if (k == 0 .or. tr < tm) then
            tm = tr
            k = e
         end if
      end subroutine earliest

      !> The first event between the sample yr (no event) and yv: 1 the
      !> abscissa in direction ydir, 2 above the band, 3 below it.
      pure subroutine classify(yv, yr, e)
         real(wp), intent(in) :: yv, yr
         integer, intent(out) :: e
         e = 0
         if (ydir < 0 .and. yr > 0.0_wp .and. yv <= 0.0_wp) e = 1
         if (ydir > 0 .and. yr < 0.0_wp .and. yv >= 0.0_wp) e = 1
         if (e == 0 .and. yv > yhi) e = 2
         if (e == 0 .and. yv < ylo) e = 3
      end subroutine classify

   end subroutine flow_exact

   !> The root of y(t) - level in [t1, t2] on the band's closed form, by the
   !> Illinois variant of regula falsi (g1 = y(t1) - level and g2 = y(t2) -
   !> level of opposite signs, or g2 = 0), to the resolution of t.
   pure function illinois(b, u0, y0, level, t1, t2, g1, g2) result(tr)
      real(wp), intent(in) :: b                !< the band's slope dX/dY
      real(wp), intent(in) :: u0, y0           !< the band's start (u = X - A, Y)
      real(wp), intent(in) :: level            !< the level of Y sought
      real(wp), intent(in) :: t1, t2           !< the bracket (no event at t1)
      real(wp), intent(in) :: g1, g2           !< Y - level at t1 and t2
      real(wp) :: tr                           !< the crossing time
      real(wp) :: ta, tb, fa, fb, tc, fc, u, y
      integer :: it
      ta = t1; tb = t2; fa = g1; fb = g2
      tr = tb
      if (fb == 0.0_wp) return
      if (fa == 0.0_wp) then
         ! on the level at t1 (a band entered at its limit) and leaving it:
         ! the first time Y - level is seen beyond it, by bisection, so that
         ! the motion advances (a root at t1 itself would leave it in place)
         do it = 1, 200
            tc = 0.5_wp*(ta + tb)
            if (tc <= ta .or. tc >= tb) exit
            call linear_flow(b, u0, y0, tc, u, y)
            if ((y - level)*g2 > 0.0_wp) then
               tb = tc
            else
               ta = tc
            end if
         end do
         tr = tb
         return
      end if
      do it = 1, 100
         tc = (ta*fb - tb*fa)/(fb - fa)
         if (.not. (tc > min(ta, tb) .and. tc < max(ta, tb))) exit
         call linear_flow(b, u0, y0, tc, u, y)
         fc = y - level
         if (fc == 0.0_wp) then
            tb = tc; fb = fc
            exit
         end if
         if (sign(1.0_wp, fc) /= sign(1.0_wp, fb)) then
            ta = tb; fa = fb
         else
            fa = 0.5_wp*fa
         end if
         tb = tc; fb = fc
         if (abs(tb - ta) <= 4.0_wp*epsilon(1.0_wp)*max(abs(ta), abs(tb))) exit
      end do
      ! the latest estimate: the bracket has shrunk to it, or the next secant
      ! step no longer moves it (Y is set to the level by the caller)
      tr = tb
   end function illinois

   pure function xb_of(n, xchl, ychl, y) result(xb)
      integer, intent(in) :: n
      real(wp), intent(in) :: xchl(n), ychl(n), y
      real(wp) :: xb, a, b, ylo, yhi
      call band_line(n, xchl, ychl, band_of(n, ychl, y, 1), a, b, ylo, yhi)
      xb = a + b*y
   end function xb_of

   !> The exact return map for M starting points X0 on the abscissa.
   pure subroutine return_map_exact(n, xchl, ychl, m, x0, tmax, xleft, xright, period, status)
      integer, intent(in) :: n                 !< number of points of the characteristic
      real(wp), intent(in) :: xchl(n)          !< abscissae
      real(wp), intent(in) :: ychl(n)          !< ordinates, strictly decreasing
      integer, intent(in) :: m                 !< number of starting points
      real(wp), intent(in) :: x0(m)            !< starting abscissae (right of the equilibrium)
      real(wp), intent(in) :: tmax             !< time limit for each half turn
      real(wp), intent(out) :: xleft(m)        !< the crossing on the left
      real(wp), intent(out) :: xright(m)       !< P(X0), the crossing on the right
      real(wp), intent(out) :: period(m)       !< time of the revolution
      integer, intent(out) :: status(m)        !< st_ok or st_no_return
      integer :: i
      real(wp) :: x, y, t
      do i = 1, m
         x = x0(i); y = 0.0_wp; t = 0.0_wp
         xleft(i) = x; xright(i) = x; period(i) = 0.0_wp
         call flow_exact(n, xchl, ychl, 1, tmax, x, y, t, status(i))
         xleft(i) = x
         if (status(i) /= st_ok) cycle
         call flow_exact(n, xchl, ychl, -1, tmax, x, y, t, status(i))
         xright(i) = x
         period(i) = t
      end do
   end subroutine return_map_exact

   !> The faithful return map: the listing's POINT steps with DTHETA.
   pure subroutine return_map_faithful(n, xchl, ychl, dtheta, lookup, m, x0, maxsteps, &
                                       xleft, xright, period, status)
      integer, intent(in) :: n                 !< number of points of the characteristic
      real(wp), intent(in) :: xchl(n)          !< abscissae
      real(wp), intent(in) :: ychl(n)          !< ordinates
      real(wp), intent(in) :: dtheta           !< DTHETA
      integer, intent(in) :: lookup            !< POINT mode
      integer, intent(in) :: m                 !< number of starting points
      real(wp), intent(in) :: x0(m)            !< starting abscissae
      integer, intent(in) :: maxsteps          !< step limit for each half turn
      real(wp), intent(out) :: xleft(m)        !< the crossing on the left
      real(wp), intent(out) :: xright(m)       !< P(X0)
      real(wp), intent(out) :: period(m)       !< steps*DTHETA of the revolution
      integer, intent(out) :: status(m)        !< st_ok, st_no_return or a POINT status
      integer :: i, k, half, st
      real(wp) :: x, y, t, xn, yn, tn, r, xb, xk, ds, dx, dy, dt, f
      do i = 1, m
         x = x0(i); y = 0.0_wp; t = 0.0_wp
         xleft(i) = x; xright(i) = x; period(i) = 0.0_wp
         half = 1
         st = st_no_return
         do k = 1, 2*maxsteps
            call point_step(n, xchl, ychl, dtheta, x, y, t, lookup, xn, yn, tn, r, xb, xk, ds, dx, dy, dt, st)
            if (st /= st_ok) exit
            st = st_no_return
            period(i) = period(i) + dtheta
            if (half == 1 .and. y < 0.0_wp .and. yn >= 0.0_wp) then
               xleft(i) = x + y/(y - yn)*(xn - x)
               half = 2
            else if (half == 2 .and. y > 0.0_wp .and. yn <= 0.0_wp) then
               f = y/(y - yn)
               xright(i) = x + f*(xn - x)
               period(i) = period(i) - (1.0_wp - f)*dtheta
               st = st_ok
               exit
            end if
            x = xn; y = yn; t = tn
         end do
         status(i) = st
      end do
   end subroutine return_map_faithful

end module cycles
