!> The generalised 1-DoF stick-slip slider of `lieng diagnose`: the thesis's
!> model (a dynamometer of natural frequency wn on a belt, one single-valued
!> friction characteristic of general shape, constant load and drive, a small
!> relative velocity in stick, ch. 2.3.1.1) with the extensions the diagnosis
!> can switch on: a load factor L(t) + kx (x - xref) (load variation through
!> an exogenous record or through the rig's coupling of the normal force to
!> the displacement, triggering), a drive velocity vd(t) (drive modulation),
!> a static limit growing with the stick time (ageing) and with the loading
!> velocity (rate-dependent static friction), two kinetic branches
!> (twin mechanism) and creep growing towards the static limit.
!>
!>   slip:  x'' = wn**2 (L(t) F - x) - 2 zeta wn x',
!>          F = sign(s) phi(|s|) + b delta/2 + [b > 0] psi(|s|),  s = vd - x'
!>          phi tabulated at (sg, fg), linear between the points, constant
!>          beyond the ends (b = -1 while the relative speed grows, +1 after
!>          it has peaked); psi at (sg, dg): the decelerating branch's own
!>          departure from phi (two branches of general shape; 0 in the
!>          baseline)
!>   stick: x' = vd(t) (1 - c0 - c1 r**m), r = x / limit (creep; m the
!>          exponent: how close to the limit the creep gathers),
!>          until |x| > L(t) fs (1 + a ln(1 + ts/tau) + r ln(max(vl, vr)/vr)),
!>          vl the fastest |vd| of the stick so far (its loading velocity)
!>   slip -> stick when s <= 0 and |x| <= L(t) fs.
!>
!> Semi-implicit (symplectic) Euler sub-steps; vd and L are linear between
!> the output samples.  Units: mm, s.
module slider
   use iso_fortran_env, only: wp => real64
   use status_codes, only: st_ok, st_bad_argument, st_nonfinite_state
   implicit none
   private
   public :: slider_run

contains

   !> phi(s) for s >= 0: linear interpolation in the table, constant beyond it.
   pure function phi(s, ns, sg, fg) result(f)
      real(wp), intent(in) :: s          !< sliding velocity (mm/s), >= 0
      integer, intent(in) :: ns          !< number of table points (>= 1)
      real(wp), intent(in) :: sg(ns)     !< sliding velocities, increasing (mm/s)
      real(wp), intent(in) :: fg(ns)     !< friction over stiffness there (mm)
      real(wp) :: f
      integer :: j
      if (s <= sg(1)) then
         f = fg(1)
         return
      end if
      do j = 2, ns
         if (s <= sg(j)) then
            f = fg(j - 1) + (fg(j) - fg(j - 1)) * (s - sg(j - 1)) / (sg(j) - sg(j - 1))
            return
         end if
      end do
      f = fg(ns)
   end function phi

   subroutine slider_run(n, dt, nsub, vd, load, wn, zeta, fs, ns, sg, fg, delta, dg, age_a, age_tau, age_r, age_v, &
                         kx, xref, creep0, creep1, creep_m, x0, t0, x, v, state, status)
      integer, intent(in) :: n                !< number of output samples (>= 2)
      real(wp), intent(in) :: dt              !< output sample interval (s), > 0
      integer, intent(in) :: nsub             !< sub-steps per sample (>= 1)
      real(wp), intent(in) :: vd(n)           !< drive velocity at the samples (mm/s)
      real(wp), intent(in) :: load(n)         !< load factor N/N0 at the samples (> 0)
      real(wp), intent(in) :: wn              !< natural frequency (rad/s), > 0
      real(wp), intent(in) :: zeta            !< damping ratio
      real(wp), intent(in) :: fs              !< static limit (mm)
      integer, intent(in) :: ns               !< points of the characteristic table (>= 1)
      real(wp), intent(in) :: sg(ns)          !< sliding velocities of the table, increasing (mm/s)
      real(wp), intent(in) :: fg(ns)          !< the characteristic there: friction over stiffness (mm)
      real(wp), intent(in) :: delta           !< decelerating minus accelerating branch (mm)
      real(wp), intent(in) :: dg(ns)          !< the decelerating branch less phi at sg (mm; zeros: one branch)
      real(wp), intent(in) :: age_a           !< ageing: relative growth per e-fold of stick time
      real(wp), intent(in) :: age_tau         !< ageing time scale (s), > 0
      real(wp), intent(in) :: age_r           !< static limit's relative growth per e-fold of the loading velocity
      real(wp), intent(in) :: age_v           !< loading velocity at and below which that term adds nothing (mm/s), > 0
      real(wp), intent(in) :: kx              !< load factor per mm of displacement (coupling)
      real(wp), intent(in) :: xref            !< displacement at which the coupling adds nothing (mm)
      real(wp), intent(in) :: creep0          !< relative velocity in stick as a fraction of the drive
      real(wp), intent(in) :: creep1          !< creep growing as (x / limit)**creep_m towards the static limit
      real(wp), intent(in) :: creep_m         !< that exponent (>= 1; 4 the smooth rise of ch. 2.3.1.1's line)
      real(wp), intent(in) :: x0              !< initial displacement (mm), starts stuck
      real(wp), intent(in) :: t0              !< how long it has been stuck at the start (s, >= 0: the ageing's clock)
      real(wp), intent(out) :: x(n)           !< displacement (mm)
      real(wp), intent(out) :: v(n)           !< velocity (mm/s)
      integer, intent(out) :: state(n)        !< 1 stick, 0 slip
      integer, intent(out) :: status          !< st_ok, st_bad_argument or st_nonfinite_state
      real(wp) :: h, xs, vs_, t_st, s, sprev, f, lfac, vdr, lim, a, w, r, b, vl, grow
      integer :: i, k
      logical :: stick, twin2, rel

      status = st_ok
      x = 0.0_wp; v = 0.0_wp; state = 0
      if (n < 2 .or. nsub < 1 .or. ns < 1 .or. .not. (dt > 0.0_wp) .or. .not. (wn > 0.0_wp) &
          .or. .not. (age_tau > 0.0_wp) .or. .not. (age_v > 0.0_wp) .or. .not. (t0 >= 0.0_wp) &
          .or. .not. (creep_m >= 1.0_wp)) then
         status = st_bad_argument
         return
      end if
      twin2 = any(dg /= 0.0_wp)
      h = dt / nsub
      xs = x0
      vs_ = vd(1)
      stick = .true.
      rel = .false.
      t_st = t0
      vl = abs(vd(1))
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
               t_st = t_st + h
               vl = max(vl, abs(vdr))
               lim = lfac * fs
               if (age_a /= 0.0_wp .or. age_r /= 0.0_wp) then
                  grow = 0.0_wp
                  if (age_a /= 0.0_wp) grow = age_a * log(1.0_wp + t_st / age_tau)
                  if (age_r /= 0.0_wp) grow = grow + age_r * log(max(vl, age_v) / age_v)
                  lim = lim * max(1.0_wp + grow, 0.05_wp)
               end if
               vs_ = vdr
               if (creep0 /= 0.0_wp .or. creep1 /= 0.0_wp) then
                  r = 0.0_wp
                  if (lim > 0.0_wp) r = min(max(xs / lim, 0.0_wp), 1.0_wp)
                  vs_ = vdr * (1.0_wp - creep0 - creep1 * r**creep_m)
               end if
               xs = xs + h * vs_
               if (abs(xs) > lim) then
                  stick = .false.
                  rel = .true.
                  b = -1.0_wp
                  sprev = 0.0_wp
               end if
            else
               s = vdr - vs_
               ! until the slider has moved off the drive's velocity on the side the spring force moves it
               ! (``rel``), the friction is the characteristic at s -> 0 on that side: a measured drive whose
               ! velocity wobbles between sub-steps made s of the other sign right after the release, and the
               ! friction then pushed the way the spring does, a kick of twice the friction for a sub-step
               ! (a slip twice as large as a wobble of 0.5 % decided; half the slips of a noisy drive)
               if (rel .and. s * sign(1.0_wp, xs) > 0.0_wp) rel = .false.
               if (rel) s = 0.0_wp
               if (s > 0.0_wp) then
                  f = phi(s, ns, sg, fg) + 0.5_wp * b * delta
                  if (twin2 .and. b > 0.0_wp) f = f + phi(s, ns, sg, dg)
               else if (s < 0.0_wp) then
                  f = -phi(-s, ns, sg, fg)
               else
                  ! s = 0: the sub-step right after the release (the slider still at the drive's
                  ! velocity): the characteristic at s -> 0 on the side the spring force moves it
                  ! (was 0, which kicked every slip off with the whole spring force for a sub-step:
                  ! a slip from a large x, a force record with an offset, ran away)
                  if (xs >= 0.0_wp) then
                     f = phi(0.0_wp, ns, sg, fg) + 0.5_wp * b * delta
                  else
                     f = -phi(0.0_wp, ns, sg, fg)
                  end if
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
                  vl = abs(vdr)
                  vs_ = vdr
               end if
            end if
         end do
         if (.not. (abs(xs) < huge(1.0_wp) .and. abs(vs_) < huge(1.0_wp))) then
            status = st_nonfinite_state
            return
         end if
         x(i + 1) = xs
         v(i + 1) = vs_
         state(i + 1) = merge(1, 0, stick)
      end do
   end subroutine slider_run

end module slider
