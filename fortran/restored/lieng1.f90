!> LIENG-1 (thesis App. 4): phase portraits by Lienard's construction with a
!> fixed characteristic line.
!>
!> The main program of the listing: for each of the trajectories, start at
!> (XINP, YINP), call POINT until the trajectory has NPTS points (3000 in the
!> listing), apply the near-abscissa time correction (DO 140), then step the
!> initial point by XINP = XINP - XINCR, YINP = YINP - YINCR (9 trajectories
!> in the listing, MK = 0..8).  PINPUT's checks and the centre of symmetry
!> live in lienard_core; card input, the line-printer listing and the plots
!> are done by the Python layer.
module lieng1
   use lienard_core, only: wp, point_step, st_ok, st_bad_size, mode_fast
   implicit none
   private
   public :: lieng1_trajectory, lieng1_portrait, time_correction, time_correction_fast

   !> AA = 1.1*A: a time increment more than 10 % above the mean of the four
   !> before it is corrected (reading of the OCR "AA=/,1 *A", see RESTORATION.md).
   real(wp), parameter, public :: tcorr_factor = 1.1_wp
   !> IF(ABS(Y(J-1)).LT.0.2 ...): the band about the abscissa where the time
   !> correction applies.
   real(wp), parameter, public :: tcorr_band = 0.2_wp

contains

   !> One trajectory: statements 60-145 of the main program.
   pure subroutine lieng1_trajectory(n, xchl, ychl, dtheta, xinp, yinp, npts, lookup, &
                                     x, y, t, status, where)
      integer, intent(in) :: n                 !< number of points of the characteristic
      real(wp), intent(in) :: xchl(n)          !< abscissae of the characteristic
      real(wp), intent(in) :: ychl(n)          !< ordinates of the characteristic
      real(wp), intent(in) :: dtheta           !< DTHETA, angle increment of the construction
      real(wp), intent(in) :: xinp             !< XINP, initial displacement
      real(wp), intent(in) :: yinp             !< YINP, initial velocity
      integer, intent(in) :: npts              !< points per trajectory (3000 in the listing)
      integer, intent(in) :: lookup            !< lookup_listing or lookup_bisect
      real(wp), intent(out) :: x(npts)         !< X(1..NPTS)
      real(wp), intent(out) :: y(npts)         !< Y(1..NPTS)
      real(wp), intent(out) :: t(npts)         !< T(1..NPTS), after the time correction
      integer, intent(out) :: status           !< st_ok or the status of the failing POINT call
      integer, intent(out) :: where            !< L of the failing POINT call, else 0
      integer :: l
      real(wp) :: r, xb, xk, ds, dx, dy, dt

      where = 0
      x = 0.0_wp; y = 0.0_wp; t = 0.0_wp
      if (npts < 1 .or. n < 2) then
         status = st_bad_size
         return
      end if
      status = st_ok
      x(1) = xinp
      y(1) = yinp
      t(1) = 0.0_wp
      ! The listing calls POINT for L = 1..3000 and so writes a 3001st point
      ! past the arrays (it then restores X(1), Y(1), T(1), which that write
      ! had overlaid).  Here the loop stops at the last point.
      do l = 1, npts - 1
         call point_step(n, xchl, ychl, dtheta, x(l), y(l), t(l), lookup, &
                         x(l + 1), y(l + 1), t(l + 1), r, xb, xk, ds, dx, dy, dt, status)
         if (status /= st_ok) then
            where = l
            return
         end if
      end do
      if (lookup == mode_fast) then
         call time_correction_fast(npts, y, t)
      else
         call time_correction(npts, y, t)
      end if
   end subroutine lieng1_trajectory

   !> The near-abscissa time correction, DO 140 J=6,NPTS of the main program.
   !>
   !> A is the mean of the four increments before T(J); where |Y(J-1)| < 0.2
   !> and T(J)-T(J-1) > 1.1*A, the increment is replaced by A
   !> (T(J) = T(J-1) + A) and D, the excess, is subtracted from every later
   !> time T(K), K = J+1..NPTS.  The OCR reads "DO 160 K=J,3000", which would
   !> correct T(J) a second time and make every later time run away to large
   !> negative values; RESTORATION.md gives the evidence for J+1.
   pure subroutine time_correction(npts, y, t)
      integer, intent(in) :: npts              !< number of points
      real(wp), intent(in) :: y(npts)          !< velocities Y(1..NPTS)
      real(wp), intent(inout) :: t(npts)       !< times T(1..NPTS), corrected in place
      integer :: j, k
      real(wp) :: a, aa, xco, d

      do j = 6, npts
         a = ((t(j - 4) - t(j - 5)) + (t(j - 3) - t(j - 4)) + (t(j - 2) - t(j - 3)) &
              + (t(j - 1) - t(j - 2)))/4.0_wp
         aa = tcorr_factor*a
         xco = t(j) - t(j - 1)
         if (abs(y(j - 1)) < tcorr_band .and. xco > aa) then
            d = xco - a
            xco = a
            t(j) = t(j - 1) + xco
            do k = j + 1, npts
               t(k) = t(k) - d
            end do
         end if
      end do
   end subroutine time_correction

   !> The same correction in O(NPTS), for mode_fast: the excesses D are summed
   !> as they are found and subtracted from each later time once, where the
   !> listing subtracts each D from every later time in turn (O(NPTS) per
   !> correction).  The same times to rounding (the order of the subtractions
   !> differs); mode_fast is not bit-identical to the listing anyway.
   pure subroutine time_correction_fast(npts, y, t)
      integer, intent(in) :: npts              !< number of points
      real(wp), intent(in) :: y(npts)          !< velocities Y(1..NPTS)
      real(wp), intent(inout) :: t(npts)       !< times T(1..NPTS), corrected in place
      integer :: j
      real(wp) :: a, xco, shift

      shift = 0.0_wp                           ! the sum of the excesses found so far
      do j = 6, npts
         t(j) = t(j) - shift                   ! T(J-5..J-1) are final; T(J) now as the listing has it
         a = ((t(j - 4) - t(j - 5)) + (t(j - 3) - t(j - 4)) + (t(j - 2) - t(j - 3)) &
              + (t(j - 1) - t(j - 2)))/4.0_wp
         xco = t(j) - t(j - 1)
         if (abs(y(j - 1)) < tcorr_band .and. xco > tcorr_factor*a) then
            shift = shift + (xco - a)
            t(j) = t(j - 1) + a
         end if
      end do
   end subroutine time_correction_fast

   !> The phase portrait: NTRAJ trajectories (9 in the listing), the k-th
   !> starting where the (k-1)-th started less (XINCR, YINCR).
   pure subroutine lieng1_portrait(n, xchl, ychl, dtheta, xinp, yinp, xincr, yincr, &
                                   ntraj, npts, lookup, x, y, t, status, where, itraj)
      integer, intent(in) :: n                 !< number of points of the characteristic
      real(wp), intent(in) :: xchl(n)          !< abscissae of the characteristic
      real(wp), intent(in) :: ychl(n)          !< ordinates of the characteristic
      real(wp), intent(in) :: dtheta           !< DTHETA
      real(wp), intent(in) :: xinp             !< XINP of the first trajectory
      real(wp), intent(in) :: yinp             !< YINP of the first trajectory
      real(wp), intent(in) :: xincr            !< XINCR, subtracted from XINP after each trajectory
      real(wp), intent(in) :: yincr            !< YINCR, subtracted from YINP after each trajectory
      integer, intent(in) :: ntraj             !< number of trajectories (9 in the listing)
      integer, intent(in) :: npts              !< points per trajectory (3000 in the listing)
      integer, intent(in) :: lookup            !< lookup_listing or lookup_bisect
      real(wp), intent(out) :: x(npts, ntraj)  !< X of each trajectory
      real(wp), intent(out) :: y(npts, ntraj)  !< Y of each trajectory
      real(wp), intent(out) :: t(npts, ntraj)  !< T of each trajectory
      integer, intent(out) :: status           !< st_ok or the first failure
      integer, intent(out) :: where            !< L of the failing POINT call
      integer, intent(out) :: itraj            !< trajectory of the failure (1-based), else 0
      integer :: mk
      real(wp) :: xs, ys

      itraj = 0
      where = 0
      status = st_ok
      x = 0.0_wp; y = 0.0_wp; t = 0.0_wp
      xs = xinp
      ys = yinp
      do mk = 1, ntraj
         call lieng1_trajectory(n, xchl, ychl, dtheta, xs, ys, npts, lookup, &
                                x(:, mk), y(:, mk), t(:, mk), status, where)
         if (status /= st_ok) then
            itraj = mk
            return
         end if
         xs = xs - xincr
         ys = ys - yincr
      end do
   end subroutine lieng1_portrait

end module lieng1
