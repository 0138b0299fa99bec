!> The generalised 1-DoF stick-slip slider of `lieng diagnose`: the thesis's
!> model (a dynamometer of natural frequency wn on a belt, one friction
!> characteristic, constant load and drive) with the extensions the
!> diagnosis can switch on: a load factor L(t) + kx (x - xref) (load
!> variation through an exogenous record or through the rig's coupling of
!> the normal force to the displacement, triggering),
!> a drive velocity vd(t) (drive modulation), a static limit growing with the
!> stick time (ageing) and two kinetic branches (twin mechanism).
!>
!>   slip:  x'' = wn**2 (L(t) F - x) - 2 zeta wn x',
!>          F = sign(s) (fk + ds exp(-|s|/vs)) + b delta/2,  s = vd - x'
!>          (b = -1 while the relative speed grows, +1 after it has peaked)
!>   stick: x' = vd(t), until |x| > L(t) fs (1 + a ln(1 + ts/tau))
!>   slip -> stick when s <= 0 and |x| <= L(t) fs.
!>
!> Semi-implicit (symplectic) Euler sub-steps; vd and L are linear between
!> the output samples.  Units: mm, s.
module slider
   use iso_fortran_env, only: wp => real64
   implicit none
   private
   public :: slider_run

contains

   subroutine slider_run(n, dt, nsub, vd, load, wn, zeta, fs, fk, ds, vs, delta, age_a, age_tau, kx, xref, &
                         x0, x, v, state, status)
      integer, intent(in) :: n                !< number of output samples (>= 2)
      real(wp), intent(in) :: dt              !< output sample interval (s), > 0
      integer, intent(in) :: nsub             !< sub-steps per sample (>= 1)
      real(wp), intent(in) :: vd(n)           !< drive velocity at the samples (mm/s)
      real(wp), intent(in) :: load(n)         !< load factor N/N0 at the samples (> 0)
      real(wp), intent(in) :: wn              !< natural frequency (rad/s), > 0
      real(wp), intent(in) :: zeta            !< damping ratio
      real(wp), intent(in) :: fs              !< static limit (mm)
      real(wp), intent(in) :: fk              !< kinetic level (mm)
      real(wp), intent(in) :: ds              !< Stribeck excess (mm)
      real(wp), intent(in) :: vs              !< Stribeck velocity (mm/s), > 0
      real(wp), intent(in) :: delta           !< decelerating minus accelerating branch (mm)
      real(wp), intent(in) :: age_a           !< ageing: relative growth per e-fold of stick time
      real(wp), intent(in) :: age_tau         !< ageing time scale (s), > 0
      real(wp), intent(in) :: kx              !< load factor per mm of displacement (coupling)
      real(wp), intent(in) :: xref            !< displacement at which the coupling adds nothing (mm)
      real(wp), intent(in) :: x0              !< initial displacement (mm), starts stuck
      real(wp), intent(out) :: x(n)           !< displacement (mm)
      real(wp), intent(out) :: v(n)           !< velocity (mm/s)
      integer, intent(out) :: state(n)        !< 1 stick, 0 slip
      integer, intent(out) :: status          !< 0 ok, 1 bad arguments, 2 non-finite state
      real(wp) :: h, xs, vs_, t_st, s, sprev, f, lfac, vdr, lim, a, w
      integer :: i, k
      logical :: stick
      real(wp) :: b

      status = 0
      x = 0.0_wp; v = 0.0_wp; state = 0
      if (n < 2 .or. nsub < 1 .or. .not. (dt > 0.0_wp) .or. .not. (wn > 0.0_wp) .or. .not. (vs > 0.0_wp) &
          .or. .not. (age_tau > 0.0_wp)) then
         status = 1
         return
      end if
      h = dt / nsub
      xs = x0
      vs_ = vd(1)
      stick = .true.
      t_st = 0.0_wp
      b = -1.0_wp
      sprev = 0.0_wp
      x(1) = xs; v(1) = vs_; state(1) = 1
      do i = 1, n - 1
         do k = 1, nsub
            w = (k - 0.5_wp) / nsub
            vdr = (1.0_wp - w) * vd(i) + w * vd(i + 1)
            lfac = (1.0_wp - w) * load(i) + w * load(i + 1)
            if (kx /= 0.0_wp) lfac = max(lfac + kx * (xs - xref), 0.05_wp)
            if (stick) then
               vs_ = vdr
               xs = xs + h * vdr
               t_st = t_st + h
               lim = lfac * fs
               if (age_a /= 0.0_wp) lim = lim * (1.0_wp + age_a * log(1.0_wp + t_st / age_tau))
               if (abs(xs) > lim) then
                  stick = .false.
                  b = -1.0_wp
                  sprev = 0.0_wp
               end if
            else
               s = vdr - vs_
               if (s > 0.0_wp) then
                  f = fk + ds * exp(-s / vs) + 0.5_wp * b * delta
               else if (s < 0.0_wp) then
                  f = -(fk + ds * exp(s / vs))
               else
                  f = 0.0_wp
               end if
               a = wn * wn * (lfac * f - xs) - 2.0_wp * zeta * wn * vs_
               vs_ = vs_ + h * a
               xs = xs + h * vs_
               s = vdr - vs_
               if (s < sprev .and. b < 0.0_wp) b = 1.0_wp
               sprev = s
               if (s <= 0.0_wp .and. abs(xs) <= lfac * fs) then
                  stick = .true.
                  t_st = 0.0_wp
                  vs_ = vdr
               end if
            end if
         end do
         if (.not. (abs(xs) < huge(1.0_wp) .and. abs(vs_) < huge(1.0_wp))) then
            status = 2
            return
         end if
         x(i + 1) = xs
         v(i + 1) = vs_
         state(i + 1) = merge(1, 0, stick)
      end do
   end subroutine slider_run

end module slider
