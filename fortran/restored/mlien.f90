!> MLIEN / LIENG-2 (thesis App. 6): phase portraits with a driving velocity
!> that varies in time, VO(t) = AMPV0*COS(OMEGA*t), and the triggering
!> oscillation.
!>
!> The main program: CHALIN locates the centre of symmetry (VO = YMDL,
!> PHI = ARCOS(VO/AMPV0)); T(1) = PHI/OMEGA; then for each point POINT (the
!> Lienard step of lienard_core plus the triggering ellipse), TIMDIS (the
!> characteristic translated so that its centre follows AMPV0*COS(OMEGA*T)
!> and the line passes through the origin) and CHALIN again.
module mlien
   use lienard_core, only: wp, centre_of_symmetry, point_step, st_ok, st_bad_size, &
                           st_arcos_domain, st_omega_zero, st_timdis_range
   implicit none
   private
   public :: chalin, timdis, trigger_offset, mlien_run

   !> The listing's value of pi in the triggering block (3.1415927).
   real(wp), parameter :: pi_listing = 3.1415927_wp

contains

   !> CHALIN: slopes and centre of symmetry, VO = YMDL, PHI = ARCOS(VO/AMPV0).
   !> With strict_phi, |VO/AMPV0| > 1 or AMPV0 = 0 is st_arcos_domain; else the
   !> argument is clamped to [-1, 1] (used after TIMDIS, where VO equals
   !> AMPV0*COS(OMEGA*T) up to rounding and PHI is no longer used).
   pure subroutine chalin(n, xchl, ychl, ampv0, strict_phi, slope, xmdl, ymdl, vo, phi, status, where)
      integer, intent(in) :: n                 !< number of points
      real(wp), intent(in) :: xchl(n)          !< abscissae of the characteristic
      real(wp), intent(in) :: ychl(n)          !< ordinates of the characteristic
      real(wp), intent(in) :: ampv0            !< AMPV0, amplitude of the driving velocity
      logical, intent(in) :: strict_phi        !< treat an ARCOS argument outside [-1, 1] as an error
      real(wp), intent(out) :: slope(n)        !< SLOPE(1..N-1)
      real(wp), intent(out) :: xmdl            !< XMDL
      real(wp), intent(out) :: ymdl            !< YMDL
      real(wp), intent(out) :: vo              !< VO = YMDL
      real(wp), intent(out) :: phi             !< PHI = ARCOS(VO/AMPV0)
      integer, intent(out) :: status           !< st_ok or an error code
      integer, intent(out) :: where            !< index the error refers to
      integer :: isel, lll, mmm, branch
      real(wp) :: arg

      vo = 0.0_wp; phi = 0.0_wp
      call centre_of_symmetry(n, xchl, ychl, slope, isel, lll, mmm, branch, xmdl, ymdl, status, where)
      if (status /= st_ok) return
      vo = ymdl
      if (ampv0 == 0.0_wp) then
         status = st_arcos_domain
         return
      end if
      arg = vo/ampv0
      if (abs(arg) > 1.0_wp) then
         if (strict_phi) then
            status = st_arcos_domain
            return
         end if
         arg = sign(1.0_wp, arg)
      end if
      phi = acos(arg)
   end subroutine chalin

   !> TIMDIS: translate the characteristic for time TL.  DIFF = VO - VON with
   !> VON = AMPV0*COS(OMEGA*TL); ADIFF is the abscissa of the characteristic
   !> at velocity DIFF (statements 315-340); every point moves by
   !> (-ADIFF, -DIFF).  DIFF above YCHL(1) (the listing reads XCHL(0)) or
   !> below YCHL(N) (ADIFF undefined) is st_timdis_range.
   pure subroutine timdis(n, xchl, ychl, vo, ampv0, omega, tl, diff, adiff, status)
      integer, intent(in) :: n                 !< number of points
      real(wp), intent(inout) :: xchl(n)       !< abscissae, translated in place
      real(wp), intent(inout) :: ychl(n)       !< ordinates, translated in place
      real(wp), intent(in) :: vo               !< VO, the present centre velocity
      real(wp), intent(in) :: ampv0            !< AMPV0
      real(wp), intent(in) :: omega            !< OMEGA
      real(wp), intent(in) :: tl               !< T(L), the time of the new point
      real(wp), intent(out) :: diff            !< DIFF = VO - VON
      real(wp), intent(out) :: adiff           !< ADIFF
      integer, intent(out) :: status           !< st_ok or st_timdis_range
      real(wp) :: von, c
      integer :: jj, j

      von = ampv0*cos(omega*tl)
      diff = vo - von
      adiff = 0.0_wp
      status = st_timdis_range
      do jj = 1, n
         c = diff - ychl(jj)
         if (c < 0.0_wp) cycle
         if (c == 0.0_wp) then
            adiff = xchl(jj)                                    ! 320
         else
            if (jj == 1) return                                 ! would read XCHL(0)
            adiff = ((xchl(jj) - xchl(jj - 1))*(ychl(jj - 1) - diff)/(ychl(jj - 1) - ychl(jj))) &
                    + xchl(jj - 1)                              ! 330
         end if
         status = st_ok
         exit
      end do
      if (status /= st_ok) return                               ! ADIFF undefined
      do j = 1, n                                               ! DO 3000 J=1,N
         xchl(j) = xchl(j) - adiff
         ychl(j) = ychl(j) - diff
      end do
   end subroutine timdis

   !> The triggering offset added to the new point by MLIEN's POINT, as listed:
   !> OMTRIL = OMETRI*T(L+1) + OMINTR; AKTRI = OMTRIL/2.*3.1415927 (that is
   !> OMTRIL*pi/2: the precedence of the listing); PHITRI = OMTRIL -
   !> INT(AKTRI)*2.*3.1415927; XTRI = ATRI*COS(PHITRI), YTRI = BTRI*SIN(PHITRI).
   pure subroutine trigger_offset(tn, omintr, ometri, atri, btri, xtri, ytri)
      real(wp), intent(in) :: tn               !< T(L+1)
      real(wp), intent(in) :: omintr           !< OMINTR, initial phase (rad)
      real(wp), intent(in) :: ometri           !< OMETRI, angular velocity (rad per time unit)
      real(wp), intent(in) :: atri             !< ATRI, x semi-axis of the ellipse (mm)
      real(wp), intent(in) :: btri             !< BTRI, y semi-axis of the ellipse (mm/s)
      real(wp), intent(out) :: xtri            !< XTRI
      real(wp), intent(out) :: ytri            !< YTRI
      real(wp) :: omtril, aktri, anktri, aaktri, phitri

      omtril = ometri*tn + omintr
      aktri = omtril/2.0_wp*pi_listing
      anktri = aint(aktri)                     ! NKTRI=AKTRI; ANKTRI=NKTRI (no integer overflow)
      aaktri = anktri*2.0_wp*pi_listing
      phitri = omtril - aaktri
      xtri = atri*cos(phitri)
      ytri = btri*sin(phitri)
   end subroutine trigger_offset

   !> The MLIEN run: NPTS points from (XINP, YINP) at T(1) = PHI/OMEGA.
   pure subroutine mlien_run(n, xchl0, ychl0, dtheta, omega, ampv0, xinp, yinp, npts, trig, lookup, &
                             x, y, t, r, xmdl, ymdl, xchl, ychl, status, where)
      integer, intent(in) :: n                 !< number of points of the characteristic
      real(wp), intent(in) :: xchl0(n)         !< the characteristic as read
      real(wp), intent(in) :: ychl0(n)         !< its ordinates
      real(wp), intent(in) :: dtheta           !< DTHETA
      real(wp), intent(in) :: omega            !< OMEGA, cyclic frequency of the drive (rad per time unit)
      real(wp), intent(in) :: ampv0            !< AMPV0, amplitude of the driving velocity
      real(wp), intent(in) :: xinp             !< XINP
      real(wp), intent(in) :: yinp             !< YINP
      integer, intent(in) :: npts              !< points (3000 in the listing)
      real(wp), intent(in) :: trig(4)          !< OMINTR, OMETRI, ATRI, BTRI
      integer, intent(in) :: lookup            !< POINT mode (lienard_core)
      real(wp), intent(out) :: x(npts)         !< X
      real(wp), intent(out) :: y(npts)         !< Y
      real(wp), intent(out) :: t(npts)         !< T
      real(wp), intent(out) :: r(npts)         !< R of the step from each point (0 for the last)
      real(wp), intent(out) :: xmdl(npts)      !< XMDL of the characteristic in force at each point
      real(wp), intent(out) :: ymdl(npts)      !< YMDL likewise (= AMPV0*COS(OMEGA*T) after TIMDIS)
      real(wp), intent(out) :: xchl(n)         !< the last position of the characteristic
      real(wp), intent(out) :: ychl(n)         !< its ordinates
      integer, intent(out) :: status           !< st_ok or an error code
      integer, intent(out) :: where            !< L of the failure (0: before the first step)
      real(wp) :: slope(n), vo, phi, xn, yn, tn, rr, xb, xk, ds, dx, dy, dt, xtri, ytri, diff, adiff
      real(wp) :: xm, ym
      integer :: l, w

      x = 0.0_wp; y = 0.0_wp; t = 0.0_wp; r = 0.0_wp; xmdl = 0.0_wp; ymdl = 0.0_wp
      xchl = xchl0
      ychl = ychl0
      where = 0
      if (npts < 1 .or. n < 3) then
         status = st_bad_size
         return
      end if
      call chalin(n, xchl, ychl, ampv0, .true., slope, xm, ym, vo, phi, status, w)
      if (status /= st_ok) return
      if (omega == 0.0_wp) then
         status = st_omega_zero
         return
      end if
      t(1) = phi/omega
      x(1) = xinp
      y(1) = yinp
      xmdl(1) = xm
      ymdl(1) = ym
      do l = 1, npts - 1
         call point_step(n, xchl, ychl, dtheta, x(l), y(l), t(l), lookup, &
                         xn, yn, tn, rr, xb, xk, ds, dx, dy, dt, status)
         if (status /= st_ok) then
            where = l
            return
         end if
         r(l) = rr
         call trigger_offset(tn, trig(1), trig(2), trig(3), trig(4), xtri, ytri)
         x(l + 1) = xn + xtri
         y(l + 1) = yn + ytri
         t(l + 1) = tn
         call timdis(n, xchl, ychl, vo, ampv0, omega, t(l + 1), diff, adiff, status)
         if (status /= st_ok) then
            where = l + 1
            return
         end if
         call chalin(n, xchl, ychl, ampv0, .false., slope, xm, ym, vo, phi, status, w)
         if (status /= st_ok) then
            where = l + 1
            return
         end if
         xmdl(l + 1) = xm
         ymdl(l + 1) = ym
      end do
   end subroutine mlien_run

end module mlien
