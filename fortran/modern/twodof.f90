!> The 2-DoF dual-pin-on-disc model of the second seed (modern; beside the
!> 1971 code).  Coordinates: x1, the displacement of Part 1 (cylinder 1) at
!> the tensile spring's lever, and x2, the tangential displacement of the
!> lumped pins.  Equations (reconstruction: python/lieng/twodof.md):
!>
!>   M x'' + C x' + K x = (0, Ff)
!>   N = max(Fn + kn x2, 0)                     (normal contact force)
!>   slip:  Ff = muk N sign(v0 - x2')
!>   stick: x2' = v0, Ff from the second equation, while |Ff| <= mus N
!>
!> Leine's switch model: slip while |v0 - x2'| > eta; inside the band the
!> pins stick if the force that keeps them on the belt is within mus N,
!> else they slip in the direction of that force (transition).  Stick is
!> integrated as the belt's motion for x2 (so x2' = v0 exactly) and the
!> 1-DoF motion of x1.  Fixed-step classical Runge-Kutta sub-steps; the
!> switching events (v0 - x2' = 0 in slip, |Ff| = mus N in stick) are
!> located by bisection on the sub-step to machine precision.
module twodof
   use iso_fortran_env, only: wp => real64
   use status_codes, only: st_ok, st_bad_argument, st_nonfinite_state
   implicit none
   private
   public :: twodof_run, twodof_exact

   integer, parameter :: slip_state = 0, stick_state = 1

contains

   !> Accelerations of (x1, x2) in slip with friction ff.
   pure subroutine accel_slip(m, c, k, s, ff, a)
      real(wp), intent(in) :: m(2, 2), c(2, 2), k(2, 2), s(4), ff
      real(wp), intent(out) :: a(2)
      real(wp) :: r(2), det
      r(1) = -(c(1, 1)*s(2) + c(1, 2)*s(4) + k(1, 1)*s(1) + k(1, 2)*s(3))
      r(2) = -(c(2, 1)*s(2) + c(2, 2)*s(4) + k(2, 1)*s(1) + k(2, 2)*s(3)) + ff
      det = m(1, 1)*m(2, 2) - m(1, 2)*m(2, 1)
      a(1) = (m(2, 2)*r(1) - m(1, 2)*r(2))/det
      a(2) = (m(1, 1)*r(2) - m(2, 1)*r(1))/det
   end subroutine accel_slip

   !> In stick (x2' = v0, x2'' = 0): x1'' and the friction that holds the pins.
   pure subroutine stick_force(m, c, k, s, a1, ff)
      real(wp), intent(in) :: m(2, 2), c(2, 2), k(2, 2), s(4)
      real(wp), intent(out) :: a1, ff
      a1 = -(c(1, 1)*s(2) + c(1, 2)*s(4) + k(1, 1)*s(1) + k(1, 2)*s(3))/m(1, 1)
      ff = m(2, 1)*a1 + c(2, 1)*s(2) + c(2, 2)*s(4) + k(2, 1)*s(1) + k(2, 2)*s(3)
   end subroutine stick_force

   !> The state derivative in the given regime (dir: the sign of the slip friction).
   pure subroutine deriv(m, c, k, fn, kn, muk, v0, regime, dir, s, ds)
      real(wp), intent(in) :: m(2, 2), c(2, 2), k(2, 2), fn, kn, muk, v0, s(4), dir
      integer, intent(in) :: regime
      real(wp), intent(out) :: ds(4)
      real(wp) :: a(2), ff, a1
      if (regime == stick_state) then
         call stick_force(m, c, k, s, a1, ff)
         ds = [s(2), a1, v0, 0.0_wp]
      else
         ff = dir*muk*max(fn + kn*s(3), 0.0_wp)
         call accel_slip(m, c, k, s, ff, a)
         ds = [s(2), a(1), s(4), a(2)]
      end if
   end subroutine deriv

   pure subroutine rk4(m, c, k, fn, kn, muk, v0, regime, dir, h, s, sn)
      real(wp), intent(in) :: m(2, 2), c(2, 2), k(2, 2), fn, kn, muk, v0, dir, h, s(4)
      integer, intent(in) :: regime
      real(wp), intent(out) :: sn(4)
      real(wp) :: k1(4), k2(4), k3(4), k4(4)
      call deriv(m, c, k, fn, kn, muk, v0, regime, dir, s, k1)
      call deriv(m, c, k, fn, kn, muk, v0, regime, dir, s + 0.5_wp*h*k1, k2)
      call deriv(m, c, k, fn, kn, muk, v0, regime, dir, s + 0.5_wp*h*k2, k3)
      call deriv(m, c, k, fn, kn, muk, v0, regime, dir, s + h*k3, k4)
      sn = s + h/6.0_wp*(k1 + 2.0_wp*k2 + 2.0_wp*k3 + k4)
      if (regime == stick_state) sn(4) = v0
   end subroutine rk4

   !> The event function of a regime: slip: v0 - x2' (times dir, > 0 while
   !> the slip lasts); stick: mus N - |Ff| (> 0 while the stick holds).
   pure real(wp) function event(m, c, k, fn, kn, mus, v0, regime, dir, s) result(g)
      real(wp), intent(in) :: m(2, 2), c(2, 2), k(2, 2), fn, kn, mus, v0, dir, s(4)
      integer, intent(in) :: regime
      real(wp) :: a1, ff
      if (regime == stick_state) then
         call stick_force(m, c, k, s, a1, ff)
         g = mus*max(fn + kn*s(3), 0.0_wp) - abs(ff)
      else
         g = dir*(v0 - s(4))
      end if
   end function event

   subroutine twodof_run(n, dt, nsub, m, c, k, fn, kn, mus, muk, v0, eta, s0, &
                         x1, v1, x2, v2, fnorm, ffric, state, nswitch, status)
      integer, intent(in) :: n                 !< output samples (>= 2)
      real(wp), intent(in) :: dt               !< output interval (s), > 0
      integer, intent(in) :: nsub              !< Runge-Kutta sub-steps per output interval (>= 1)
      real(wp), intent(in) :: m(2, 2)          !< mass matrix (kg), symmetric positive definite
      real(wp), intent(in) :: c(2, 2)          !< damping matrix (N s/m)
      real(wp), intent(in) :: k(2, 2)          !< stiffness matrix (N/m)
      real(wp), intent(in) :: fn               !< preload: normal force at x2 = 0 (N)
      real(wp), intent(in) :: kn               !< normal force per metre of x2 (N/m): the inclined spring
      real(wp), intent(in) :: mus              !< static coefficient of friction
      real(wp), intent(in) :: muk              !< kinetic coefficient of friction
      real(wp), intent(in) :: v0               !< belt velocity (m/s)
      real(wp), intent(in) :: eta              !< Leine's velocity band (m/s), >= 0
      real(wp), intent(in) :: s0(4)            !< initial x1, x1', x2, x2' (m, m/s)
      real(wp), intent(out) :: x1(n)           !< x1 (m)
      real(wp), intent(out) :: v1(n)           !< x1' (m/s)
      real(wp), intent(out) :: x2(n)           !< x2 (m)
      real(wp), intent(out) :: v2(n)           !< x2' (m/s)
      real(wp), intent(out) :: fnorm(n)        !< normal contact force (N)
      real(wp), intent(out) :: ffric(n)        !< friction force on the pins (N)
      integer, intent(out) :: state(n)         !< 1 stick, 0 slip
      integer, intent(out) :: nswitch          !< number of stick/slip switches
      integer, intent(out) :: status           !< st_ok, st_bad_argument or st_nonfinite_state
      real(wp) :: s(4), sn(4), h, hleft, dir, g0, g1, lo, hi, mid, st(4), a1, ff
      integer :: i, j, regime, it

      status = st_ok
      nswitch = 0
      x1 = 0.0_wp; v1 = 0.0_wp; x2 = 0.0_wp; v2 = 0.0_wp; fnorm = 0.0_wp; ffric = 0.0_wp; state = 0
      if (n < 2 .or. nsub < 1 .or. .not. (dt > 0.0_wp) .or. .not. (eta >= 0.0_wp) .or. &
          .not. (m(1, 1)*m(2, 2) - m(1, 2)*m(2, 1) > 0.0_wp) .or. .not. (m(1, 1) > 0.0_wp)) then
         status = st_bad_argument
         return
      end if
      s = s0
      call classify(s, regime, dir)
      call record(1)
      h = dt/nsub
      do i = 2, n
         do j = 1, nsub
            hleft = h
            do while (hleft > 0.0_wp)
               call rk4(m, c, k, fn, kn, muk, v0, regime, dir, hleft, s, sn)
               g0 = event(m, c, k, fn, kn, mus, v0, regime, dir, s)
               g1 = event(m, c, k, fn, kn, mus, v0, regime, dir, sn)
               if (g1 > 0.0_wp .or. g0 <= 0.0_wp) then
                  s = sn
                  hleft = 0.0_wp
               else
                  ! the event lies in (0, hleft]: bisection on the step length
                  lo = 0.0_wp
                  hi = hleft
                  do it = 1, 200
                     mid = 0.5_wp*(lo + hi)
                     if (mid <= lo .or. mid >= hi) exit
                     call rk4(m, c, k, fn, kn, muk, v0, regime, dir, mid, s, st)
                     if (event(m, c, k, fn, kn, mus, v0, regime, dir, st) > 0.0_wp) then
                        lo = mid
                     else
                        hi = mid
                     end if
                  end do
                  call rk4(m, c, k, fn, kn, muk, v0, regime, dir, hi, s, sn)
                  s = sn
                  hleft = hleft - hi
                  call switch_regime()
               end if
            end do
         end do
         if (.not. all(abs(s) < huge(1.0_wp))) then
            status = st_nonfinite_state
            return
         end if
         call record(i)
      end do

   contains

      !> The regime of a state: slip outside the band |v0 - x2'| <= eta;
      !> inside it, stick when the holding force is within mus N.
      subroutine classify(sv, reg, d)
         real(wp), intent(inout) :: sv(4)
         integer, intent(out) :: reg
         real(wp), intent(out) :: d
         if (abs(v0 - sv(4)) > eta) then
            reg = slip_state
            d = sign(1.0_wp, v0 - sv(4))
            return
         end if
         sv(4) = v0
         call stick_force(m, c, k, sv, a1, ff)
         if (abs(ff) <= mus*max(fn + kn*sv(3), 0.0_wp)) then
            reg = stick_state
            d = 0.0_wp
         else                                   ! transition: slip in the direction of the holding force
            reg = slip_state
            d = sign(1.0_wp, ff)
         end if
      end subroutine classify

      subroutine switch_regime()
         integer :: old
         old = regime
         if (regime == stick_state) then
            call stick_force(m, c, k, s, a1, ff)
            regime = slip_state
            dir = sign(1.0_wp, ff)
         else
            s(4) = v0
            call classify(s, regime, dir)            ! stick, or slip on in the holding force's direction
         end if
         if (regime /= old) nswitch = nswitch + 1
      end subroutine switch_regime

      subroutine record(ii)
         integer, intent(in) :: ii
         x1(ii) = s(1); v1(ii) = s(2); x2(ii) = s(3); v2(ii) = s(4)
         fnorm(ii) = max(fn + kn*s(3), 0.0_wp)
         if (regime == stick_state) then
            call stick_force(m, c, k, s, a1, ff)
            ffric(ii) = ff
         else
            ffric(ii) = dir*muk*fnorm(ii)
         end if
         state(ii) = regime
      end subroutine record

   end subroutine twodof_run

   !> The hybrid model propagated exactly: each regime (1 stick, 2 slip with
   !> the friction forward, 3 slip backward) is linear in the augmented state
   !> z = (q, q', 1), z' = A_r z, so a full sub-step is z <- Phi_r z with
   !> Phi_r = expm(A_r h) (computed by the caller) and a part-step of length
   !> s <= h is the exponential series of A_r s (order kord; the caller keeps
   !> the spectral radius of A_r h below 1/2, so the series is exact to
   !> rounding).  The event functions of a regime are linear in z and so are
   !> polynomials in s along the flow: g_e(s) = sum_k (coef(k, :, e, r) . z) s^k
   !> with coef(k) = row_e A_r^k / k!.  Each sub-step samples them at four
   !> points; the first sign change from > 0 to <= 0 is bisected to machine
   !> precision on the polynomial, the state taken there, and the regime
   !> switched (Leine's switch model: stick -> slip in the direction of the
   !> holding force; slip -> stick if the holding force with the pins on the
   !> belt is within mus N, else slip on in its direction).
   subroutine twodof_exact(n, nz, nsub, h, kord, a, phi, coef, gs, nev, iv, v0, eta, mus, hold, nrow, z0, &
                           z, state, nswitch, status)
      integer, intent(in) :: n                    !< output samples (>= 2)
      integer, intent(in) :: nz                   !< size of the augmented state (2 DoFs: 5)
      integer, intent(in) :: nsub                 !< sub-steps per output interval (>= 1)
      real(wp), intent(in) :: h                   !< sub-step (s), > 0
      integer, intent(in) :: kord                 !< order of the exponential series (>= 1)
      real(wp), intent(in) :: a(nz, nz, 3)        !< regime matrices
      real(wp), intent(in) :: phi(nz, nz, 3)      !< expm(a h)
      real(wp), intent(in) :: coef(0:kord, nz, 2, 3)  !< the event polynomials' rows
      real(wp), intent(in) :: gs(nz, 4, 2, 3)     !< the event functions at s = h/4, h/2, 3h/4, h of a full step
      integer, intent(in) :: nev(3)               !< event functions per regime (1 or 2)
      integer, intent(in) :: iv                   !< index of the pins' velocity in z
      real(wp), intent(in) :: v0                  !< belt velocity (m/s)
      real(wp), intent(in) :: eta                 !< Leine's band (m/s), for the initial state
      real(wp), intent(in) :: mus                 !< static coefficient of friction
      real(wp), intent(in) :: hold(nz)            !< the holding force in stick: hold . z (z(iv) = v0)
      real(wp), intent(in) :: nrow(nz)            !< the normal force: nrow . z
      real(wp), intent(in) :: z0(nz)              !< initial state (last entry 1)
      real(wp), intent(out) :: z(nz, n)           !< the state at the samples
      integer, intent(out) :: state(n)            !< regime at the samples (1 stick, 2 slip +, 3 slip -)
      integer, intent(out) :: nswitch             !< number of regime switches
      integer, intent(out) :: status              !< st_ok, st_bad_argument or st_nonfinite_state
      real(wp) :: s(nz), p(0:kord, 2), hl, sev, se, lo, hi, mid, sj(0:4), gj(0:4)
      integer :: i, j, regime, e, jj, it, nsw_step
      logical :: fresh

      status = st_ok
      nswitch = 0
      z = 0.0_wp
      state = 0
      if (n < 2 .or. nsub < 1 .or. kord < 1 .or. .not. (h > 0.0_wp) .or. iv < 1 .or. iv > nz .or. &
          .not. (eta >= 0.0_wp) .or. any(nev < 1) .or. any(nev > 2)) then
         status = st_bad_argument
         return
      end if
      s = z0
      call classify(regime)
      fresh = .true.
      z(:, 1) = s
      state(1) = regime
      do i = 2, n
         do j = 1, nsub
            hl = h
            nsw_step = 0
            do while (hl > 0.0_wp)
               sev = huge(1.0_wp)
               do e = 1, nev(regime)
                  gj(0) = dot_product(coef(0, :, e, regime), s)
                  if (gj(0) < 0.0_wp .and. .not. fresh) then
                     sev = 0.0_wp                  ! already across (rounding at a step's end)
                     exit
                  end if
                  ! a full step: the samples from their precomputed rows; the polynomial only if a sign changes
                  if (hl == h) then
                     do jj = 1, 4
                        gj(jj) = dot_product(gs(:, jj, e, regime), s)
                     end do
                     if (.not. any(gj(1:4) <= 0.0_wp)) cycle
                  end if
                  p(:, e) = matmul(coef(:, :, e, regime), s)
                  sj(0) = 0.0_wp
                  gj(0) = p(0, e)
                  do jj = 1, 4
                     sj(jj) = hl*jj/4.0_wp
                     gj(jj) = poly(p(:, e), sj(jj))
                     if (gj(jj) <= 0.0_wp .and. gj(jj - 1) > 0.0_wp) then
                        lo = sj(jj - 1)
                        hi = sj(jj)
                        do it = 1, 200
                           mid = 0.5_wp*(lo + hi)
                           if (mid <= lo .or. mid >= hi) exit
                           if (poly(p(:, e), mid) > 0.0_wp) then
                              lo = mid
                           else
                              hi = mid
                           end if
                        end do
                        se = hi
                        if (se < sev) sev = se
                        exit
                     end if
                  end do
               end do
               if (sev > hl) then                   ! no event in this (part-)step
                  if (hl == h) then
                     s = matmul(phi(:, :, regime), s)
                  else
                     s = series(regime, s, hl)
                  end if
                  if (regime == 1) s(iv) = v0
                  hl = 0.0_wp
                  fresh = .false.
               else
                  if (sev > 0.0_wp) s = series(regime, s, sev)
                  hl = hl - sev
                  call switch_regime()
                  fresh = .true.
                  nsw_step = nsw_step + 1
                  if (nsw_step > 50) then           ! chattering: the switch model cannot decide
                     status = st_nonfinite_state
                     return
                  end if
               end if
            end do
         end do
         if (.not. all(abs(s) < huge(1.0_wp))) then
            status = st_nonfinite_state
            return
         end if
         z(:, i) = s
         state(i) = regime
      end do

   contains

      pure real(wp) function poly(c, x) result(y)
         real(wp), intent(in) :: c(0:kord), x
         integer :: k
         y = c(kord)
         do k = kord - 1, 0, -1
            y = y*x + c(k)
         end do
      end function poly

      !> expm(A_r t) z by the exponential series in Horner form.
      function series(r, zz, t) result(w)
         integer, intent(in) :: r
         real(wp), intent(in) :: zz(nz), t
         real(wp) :: w(nz)
         integer :: k
         w = zz
         do k = kord, 1, -1
            w = zz + (t/k)*matmul(a(:, :, r), w)
         end do
      end function series

      subroutine classify(reg)
         integer, intent(out) :: reg
         real(wp) :: ff
         if (abs(v0 - s(iv)) > eta) then
            if (v0 > s(iv)) then
               reg = 2
            else
               reg = 3
            end if
            return
         end if
         s(iv) = v0
         ff = dot_product(hold, s)
         if (abs(ff) <= mus*dot_product(nrow, s)) then
            reg = 1
         else if (ff > 0.0_wp) then
            reg = 2
         else
            reg = 3
         end if
      end subroutine classify

      subroutine switch_regime()
         integer :: old
         real(wp) :: ff
         old = regime
         if (regime == 1) then
            ff = dot_product(hold, s)
            if (ff > 0.0_wp) then
               regime = 2
            else
               regime = 3
            end if
         else
            s(iv) = v0
            call classify(regime)
         end if
         if (regime /= old) nswitch = nswitch + 1
      end subroutine switch_regime

   end subroutine twodof_exact

end module twodof
