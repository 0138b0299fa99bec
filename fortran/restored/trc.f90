!> TRC (thesis App. 7): from the recorder readings of the two dynamometer
!> traces to the experimental phase-plane trajectories and, by the reverse
!> Lienard construction, the friction characteristic.
!>
!> The listing's main program is split in three steps that the Python layer
!> calls in turn (card input, the printed tables and the plots are Python's):
!>
!> * trc_calibrate: statements 40-50 up to the velocities: readings to mm,
!>   the cross-interference correction (App. 5, A5-3/A5-4), time from the
!>   paper distance and the paper speed;
!> * trc_reduce: statements 50-540: velocities, Lienard-plane velocities,
!>   the apparent coefficient AM, BELFIT smoothing, the reverse Lienard
!>   construction of both modes (loop 51), the origin search (loops 52, 520)
!>   and the EL / ELN shift (loop 540);
!> * belfit: the "group fitting" smoothing of ch. 3.3.2 with LSQFIT, POLYNL
!>   and POLFIT (least squares by orthogonal polynomials) as listed.
!>
!> Every reading of the OCR that had to be chosen is in RESTORATION.md
!> (entries R1-R30).
module trc
   use iso_fortran_env, only: wp => real64
   use status_codes, only: trc_ok => st_ok, trc_bad_size => st_trc_few_points, trc_no_el => st_trc_no_el, &
                           trc_degenerate_fit => st_trc_degenerate_fit, trc_zero_dt => st_trc_zero_dt
   implicit none
   private
   public :: trc_calibrate, trc_reduce, belfit, lsqfit
   public :: trc_ok, trc_bad_size, trc_no_el, trc_degenerate_fit, trc_zero_dt


   !> HOR = HO/500., X = HOR + H*SENSF/500.: the horizontal bridge's calibration
   real(wp), parameter, public :: cal_h = 500.0_wp
   !> HONR = HON/568.2, XN = HONR + HN*SENSN/568.2: the normal bridge's calibration
   real(wp), parameter, public :: cal_n = 568.2_wp
   !> AMT = XX*OMNH**2/9810.: g in mm/s**2
   real(wp), parameter, public :: g_mm = 9810.0_wp
   !> BELFIT's {D, n, N} = {2, 5, 8} (ch. 3.3.2): K, M, L of the listing
   integer, parameter, public :: belfit_deg = 2, belfit_group = 5, belfit_passes = 8

contains

   !> Statements 40-50 of the main program up to the velocities: the readings
   !> (hundredths of recorder millimetres, as punched with 18I4) to time in
   !> seconds and the two displacements in mm, corrected for the cross-
   !> interference of the bridges.
   pure subroutine trc_calibrate(nn, nt, nh, nhn, ho, hon, vel, sensf, sensn, an1, an2, t, x, xn)
      integer, intent(in) :: nn                !< NN, number of points of the trace
      integer, intent(in) :: nt(nn)            !< NT, paper distance from the previous point (1/100 mm)
      integer, intent(in) :: nh(nn)            !< NH, horizontal trace reading (1/100 mm)
      integer, intent(in) :: nhn(nn)           !< NHN, normal trace reading (1/100 mm)
      real(wp), intent(in) :: ho               !< HO, horizontal reference level (microstrain)
      real(wp), intent(in) :: hon              !< HON, normal reference level (microstrain)
      real(wp), intent(in) :: vel              !< VEL, paper speed (mm/s), not 0
      real(wp), intent(in) :: sensf            !< SENSF, sensitivity of the friction-force trace
      real(wp), intent(in) :: sensn            !< SENSN, sensitivity of the normal-force trace
      real(wp), intent(in) :: an1              !< AN1, interference of the friction on the normal trace (fraction)
      real(wp), intent(in) :: an2              !< AN2, interference of the normal on the friction trace (fraction)
      real(wp), intent(out) :: t(nn)           !< T, time (s), T(1) = 0
      real(wp), intent(out) :: x(nn)           !< X, horizontal displacement (mm), corrected
      real(wp), intent(out) :: xn(nn)          !< XN, normal displacement (mm), corrected
      real(wp) :: hor, honr, tc, h, hn, xreal, xnreal
      integer :: i

      hor = ho / cal_h
      honr = hon / cal_n
      do i = 1, nn
         tc = real(nt(i), wp) / 100.0_wp
         h = real(nh(i), wp) / 100.0_wp
         hn = real(nhn(i), wp) / 100.0_wp
         if (i == 1) then
            t(1) = 0.0_wp
         else
            t(i) = ((t(i - 1) * vel) + tc) / vel
         end if
         x(i) = hor + h * sensf / cal_h
         xn(i) = honr + hn * sensn / cal_n
         xreal = (x(i) - an2 * xn(i)) / (1.0_wp - an1 * an2)
         xnreal = (xn(i) - an1 * x(i)) / (1.0_wp - an1 * an2)
         x(i) = xreal
         xn(i) = xnreal
      end do
   end subroutine trc_calibrate

   !> Statements 50-540 of the main program.  On entry T, X, XN are the
   !> calibrated trace; on return X is BELFIT's copy of it (BELFIT smooths the
   !> velocity as a function of X and leaves X itself unchanged) and every
   !> other array holds what the listing prints, after the EL / ELN shift.
   !> Points 1 and NN of XX, YY, XXN, YYN are not constructed (loop 51 runs
   !> J = 2..NN-1): they keep the listing's zero, shifted.
   subroutine trc_reduce(nn, t, x, xn, omnh, omnv, v, vn, vln, vnln, am, xx, yy, xxn, yyn, &
                         xlnr, xnlnr, amt, amtn, el, eln, has_eln, iel, ieln, status, where, xx0, xxn0)
      integer, intent(in) :: nn                !< NN, number of points
      real(wp), intent(in) :: t(nn)            !< T (s)
      real(wp), intent(inout) :: x(nn)         !< X (mm)
      real(wp), intent(in) :: xn(nn)           !< XN (mm)
      real(wp), intent(in) :: omnh             !< OMNH, natural frequency of the horizontal mode (rad/s)
      real(wp), intent(in) :: omnv             !< OMNV, natural frequency of the normal mode (rad/s)
      real(wp), intent(out) :: v(nn)           !< V = dX/dt (mm/s), backward difference, V(1) = 0
      real(wp), intent(out) :: vn(nn)          !< VN = dXN/dt (mm/s)
      real(wp), intent(out) :: vln(nn)         !< VLN = V/OMNH (mm), smoothed by BELFIT
      real(wp), intent(out) :: vnln(nn)        !< VNLN = VN/OMNV (mm)
      real(wp), intent(out) :: am(nn)          !< AM = X/XN, the apparent coefficient of friction
      real(wp), intent(out) :: xx(nn)          !< XX, characteristic of the horizontal mode (mm), shifted by EL
      real(wp), intent(out) :: yy(nn)          !< YY, its velocity coordinate (= smoothed VLN)
      real(wp), intent(out) :: xxn(nn)         !< XXN, characteristic of the normal mode, shifted by ELN
      real(wp), intent(out) :: yyn(nn)         !< YYN, its velocity coordinate (= VNLN)
      real(wp), intent(out) :: xlnr(nn)        !< XLNR = X - EL
      real(wp), intent(out) :: xnlnr(nn)       !< XNLNR = XN - ELN
      real(wp), intent(out) :: amt(nn)         !< AMT = XX*OMNH**2/9810
      real(wp), intent(out) :: amtn(nn)        !< AMTN = XXN*OMNV**2/9810
      real(wp), intent(out) :: el              !< EL, the horizontal origin
      real(wp), intent(out) :: eln             !< ELN, the normal origin (0 when has_eln = 0)
      integer, intent(out) :: has_eln          !< 1 when the normal sign change was found
      integer, intent(out) :: iel              !< I of loop 52: the last + before the - run (0: none)
      integer, intent(out) :: ieln             !< I of loop 520: the last - before the + run (0: none)
      integer, intent(out) :: status           !< trc_ok or an error code
      integer, intent(out) :: where            !< the point the error refers to
      real(wp), intent(out) :: xx0(nn)         !< XX before the shift by EL (not in the listing: for origin fits)
      real(wp), intent(out) :: xxn0(nn)        !< XXN before the shift by ELN (likewise)
      real(wp) :: xxx(nn), yyy(nn)
      real(wp) :: xk, xl, al1, al2, xkn, xln, anl1, anl2
      integer :: i, j, nk, ifound

      v = 0.0_wp; vn = 0.0_wp; vln = 0.0_wp; vnln = 0.0_wp; am = 0.0_wp
      xx = 0.0_wp; yy = 0.0_wp; xxn = 0.0_wp; yyn = 0.0_wp
      xlnr = 0.0_wp; xnlnr = 0.0_wp; amt = 0.0_wp; amtn = 0.0_wp
      el = 0.0_wp; eln = 0.0_wp; has_eln = 0; iel = 0; ieln = 0; where = 0
      xx0 = 0.0_wp; xxn0 = 0.0_wp
      status = trc_ok
      if (nn < 2 * belfit_group) then
         status = trc_bad_size
         return
      end if
      ! DO 50 I=2,NN (the velocities part)
      do i = 2, nn
         if (t(i) == t(i - 1)) then
            status = trc_zero_dt
            where = i
            return
         end if
         v(i) = (x(i) - x(i - 1)) / (t(i) - t(i - 1))
         vn(i) = (xn(i) - xn(i - 1)) / (t(i) - t(i - 1))
         vln(i) = v(i) / omnh
         vnln(i) = vn(i) / omnv
      end do
      ! AM(I)=X(I)/XN(I) is inside loop 50 (I = 2..NN): AM(1) stays 0.
      do i = 2, nn
         am(i) = x(i) / xn(i)
      end do

      ! CALL BELFIT(X,VLN,NN,XXX,YYY); DO 701: X=XXX, VLN=YYY
      call belfit(nn, x, vln, xxx, yyy, status, where)
      if (status /= trc_ok) return
      x = xxx
      vln = yyy

      ! DO 51 J=2,NK: the reverse Lienard construction
      nk = nn - 1
      do j = 2, nk
         yy(j) = vln(j)
         xk = x(j) + (vln(j) * (vln(j - 1) - vln(j))) / (x(j - 1) - x(j))
         xl = x(j) + (vln(j) * (vln(j) - vln(j + 1))) / (x(j) - x(j + 1))
         al1 = sqrt((x(j - 1) - x(j))**2 + (vln(j - 1) - vln(j))**2)
         al2 = sqrt((x(j) - x(j + 1))**2 + (vln(j) - vln(j + 1))**2)
         xx(j) = (xk * al1 + xl * al2) / (al1 + al2)
         yyn(j) = vnln(j)
         xkn = xn(j) + (vnln(j) * (vnln(j - 1) - vnln(j))) / (xn(j - 1) - xn(j))
         xln = xn(j) + (vnln(j) * (vnln(j) - vnln(j + 1))) / (xn(j) - xn(j + 1))
         anl1 = sqrt((xn(j - 1) - xn(j))**2 + (vnln(j - 1) - vnln(j))**2)
         anl2 = sqrt((xn(j) - xn(j + 1))**2 + (vnln(j) - vnln(j + 1))**2)
         xxn(j) = (xkn * anl1 + xln * anl2) / (anl1 + anl2)
      end do

      xx0 = xx
      xxn0 = xxn

      ! DO 52 I=2,NN: VLN > 0 followed by four negative samples.  The listing
      ! reads up to VLN(NN+4), zeros that fail the test: I <= NN-4 here.
      ifound = 0
      do i = 2, nn - 4
         if (vln(i) > 0.0_wp .and. vln(i + 1) < 0.0_wp .and. vln(i + 2) < 0.0_wp .and. &
             vln(i + 3) < 0.0_wp .and. vln(i + 4) < 0.0_wp) then
            ifound = i
            exit
         end if
      end do
      if (ifound == 0) then
         status = trc_no_el
         return
      end if
      i = ifound
      iel = ifound
      el = (xx(i + 1) * yy(i) - xx(i) * yy(i + 1)) / (yy(i) - yy(i + 1))

      ! DO 520 I=2,NK: VNLN < 0 followed by four positive samples
      ifound = 0
      do i = 2, min(nk, nn - 4)
         if (vnln(i) < 0.0_wp .and. vnln(i + 1) > 0.0_wp .and. vnln(i + 2) > 0.0_wp .and. &
             vnln(i + 3) > 0.0_wp .and. vnln(i + 4) > 0.0_wp) then
            ifound = i
            exit
         end if
      end do
      if (ifound /= 0) then
         i = ifound
         ieln = ifound
         eln = (xxn(i + 1) * yyn(i) - xxn(i) * yyn(i + 1)) / (yyn(i) - yyn(i + 1))
         has_eln = 1
      end if

      ! DO 540 I=1,NN
      do i = 1, nn
         xlnr(i) = x(i) - el
         xnlnr(i) = xn(i) - eln
         xx(i) = xx(i) - el
         xxn(i) = xxn(i) - eln
         amt(i) = (xx(i) * omnh**2) / g_mm
         amtn(i) = (xxn(i) * omnv**2) / g_mm
      end do
   end subroutine trc_reduce

   !> SUBROUTINE BELFIT(X,Y,N,XXX,YYY): "group fitting" (ch. 3.3.2).  A
   !> polynomial of degree K = 2 in X is fitted to Y over every group of M = 5
   !> consecutive points; each point's new Y is the mean of its fitted values
   !> over the groups that hold it; L = 8 passes.  Y is smoothed in place as
   !> in the listing, X is not changed; XXX, YYY are copies of the result.
   subroutine belfit(n, x, y, xxx, yyy, status, where)
      integer, intent(in) :: n                 !< N, number of points (>= 2M: at 2M-1 the listing divides the
                                               !< last points' sums by one run too many, deviation D14)
      real(wp), intent(in) :: x(n)             !< X, the abscissae
      real(wp), intent(inout) :: y(n)          !< Y, smoothed in place
      real(wp), intent(out) :: xxx(n)          !< XXX = X
      real(wp), intent(out) :: yyy(n)          !< YYY = Y after the last pass
      integer, intent(out) :: status           !< trc_ok, trc_bad_size or trc_degenerate_fit
      integer, intent(out) :: where            !< first point of the degenerate group
      integer, parameter :: m = belfit_group, k = belfit_deg, l = belfit_passes
      real(wp) :: psi(n), chi(m), psii(m), c(4)
      integer :: i, nn, ka, kk, kn, kl, id, iff

      status = trc_ok
      where = 0
      xxx = x
      yyy = y
      if (n < 2 * m) then
         status = trc_bad_size
         return
      end if
      do i = 1, l
         nn = n - m + 1
         c = 0.0_wp
         psi = 0.0_wp
         do ka = 1, nn
            chi = x(ka:ka + m - 1)
            psii = y(ka:ka + m - 1)
            if (count_distinct(chi) <= k) then
               status = trc_degenerate_fit
               where = ka
               return
            end if
            call lsqfit(m, k, chi, psii, c)
            do kk = 1, m
               kn = ka + kk - 1
               psi(kn) = c(4) * chi(kk)**2 + c(3) * chi(kk) + c(2) + psi(kn)
            end do
         end do
         ! Loop 50: ID, the number of groups that hold point KL.  The listing
         ! counts down IFF for KL >= NN without initialising it; IFF = M+1 at
         ! each pass makes ID = M, M-1, ..., 1 there (RESTORATION.md R13).
         iff = m + 1
         do kl = 1, n
            if (kl <= m) then
               id = kl
            else if (kl > m .and. kl < nn) then
               id = m
            else
               iff = iff - 1
               id = iff
            end if
            y(kl) = psi(kl) / real(id, wp)
         end do
      end do
      xxx = x
      yyy = y
   contains
      pure integer function count_distinct(a)
         real(wp), intent(in) :: a(:)
         integer :: p, q
         count_distinct = 0
         do p = 1, size(a)
            if (all([(a(q) /= a(p), q = 1, p - 1)])) count_distinct = count_distinct + 1
         end do
      end function count_distinct
   end subroutine belfit

   !> SUBROUTINE LSQFIT: unit weights (DO 7 WT(I)=1.0), then POLYNL.  The
   !> listing's AP, EQWT and WRITER arguments are not used (WRITER = 0 skips
   !> the storage of the orthogonal polynomials for COVAR).  FITPOL(I+1) is
   !> the coefficient of X**(I-1).
   pure subroutine lsqfit(number, kdeg, x, y, fitpol)
      integer, intent(in) :: number            !< NUMBER of points
      integer, intent(in) :: kdeg              !< KDEG, degree of the polynomial
      real(wp), intent(in) :: x(number)        !< X
      real(wp), intent(in) :: y(number)        !< Y
      real(wp), intent(out) :: fitpol(kdeg + 2) !< FITPOL(2..KDEG+2): coefficients of X**0..X**KDEG
      real(wp) :: wt(number)
      wt = 1.0_wp
      call polynl(number, kdeg, x, y, wt, fitpol)
   end subroutine lsqfit

   !> SUBROUTINE POLYNL: initialisation for POLFIT.
   pure subroutine polynl(number, kdeg, x, y, wt, fitpol)
      integer, intent(in) :: number            !< NUMBER of points
      integer, intent(in) :: kdeg              !< KDEG
      real(wp), intent(in) :: x(number)        !< X
      real(wp), intent(in) :: y(number)        !< Y
      real(wp), intent(in) :: wt(number)       !< WT, weights
      real(wp), intent(out) :: fitpol(kdeg + 2) !< FITPOL
      real(wp) :: resid(number), u(number), v(number), var(number)
      real(wp) :: f(kdeg + 2), ortpol(kdeg + 2), h(kdeg + 2), c(kdeg + 2)
      integer :: i, j, k2
      do i = 1, number
         resid(i) = y(i)
         u(i) = 1.0_wp
         v(i) = 0.0_wp
         var(i) = 0.0_wp
      end do
      k2 = kdeg + 2
      do j = 1, k2
         fitpol(j) = 0.0_wp
         f(j) = 0.0_wp
         ortpol(j) = 0.0_wp
         h(j) = 0.0_wp
      end do
      ortpol(2) = 1.0_wp
      c(1) = 0.0_wp
      call polfit(number, kdeg, x, wt, resid, u, v, var, fitpol, f, ortpol, h, c)
   end subroutine polynl

   !> SUBROUTINE POLFIT: least squares by orthogonal polynomials generated by
   !> the three-term recurrence P(j+1) = (X - A)*P(j) - B*P(j-1), each fitted
   !> to the current residual; FITPOL accumulates C(j+1)*P(j) in powers of X.
   !> The listing's last pass builds one polynomial more than it needs and
   !> writes it one place past the arrays (H(5), F(5), ORTPOL(5) with KD = 4):
   !> here the recurrence is skipped after the last degree (R18).
   pure subroutine polfit(number, kdeg, x, wt, resid, u, v, var, fitpol, f, ortpol, h, c)
      integer, intent(in) :: number            !< NUMBER of points
      integer, intent(in) :: kdeg              !< KDEG
      real(wp), intent(in) :: x(number)        !< X
      real(wp), intent(in) :: wt(number)       !< WT
      real(wp), intent(inout) :: resid(number) !< RESID, residuals of the current fit
      real(wp), intent(inout) :: u(number)     !< U, P(j-1) at X
      real(wp), intent(inout) :: v(number)     !< V, P(j) at X
      real(wp), intent(inout) :: var(number)   !< VAR, variance of the fitted values
      real(wp), intent(inout) :: fitpol(kdeg + 2) !< FITPOL
      real(wp), intent(inout) :: f(kdeg + 2)   !< F, coefficients of P(j-1)
      real(wp), intent(inout) :: ortpol(kdeg + 2) !< ORTPOL, coefficients of P(j)
      real(wp), intent(inout) :: h(kdeg + 2)   !< H, coefficients of P(j+1)
      real(wp), intent(inout) :: c(kdeg + 2)   !< C, coefficients in the orthogonal basis
      real(wp) :: div, dinv(kdeg + 1), a, b, ex, ey, z, w
      integer :: i, j, kplus, nt, ns

      div = 1.0_wp
      a = 0.0_wp
      b = -1.0_wp
      kplus = kdeg + 1
      dinv = 0.0_wp
      nt = 1
      do j = 1, kplus
         ex = 0.0_wp
         ey = 0.0_wp
         z = 0.0_wp
         do i = 1, number
            if (j > 1) then
               var(i) = var(i) + v(i) * v(i) * dinv(j - 1)
               resid(i) = resid(i) - c(j) * v(i)
            end if
            w = (x(i) - a) * v(i) - b * u(i)
            u(i) = v(i)
            v(i) = w
            w = wt(i) * v(i) * v(i)
            ex = ex + w
            w = w * x(i)
            ey = ey + w
            w = resid(i) * wt(i) * v(i)
            z = z + w
         end do
         a = ey / ex
         b = ex / div
         div = ex
         c(j + 1) = z / ex
         do i = 1, j
            nt = i + 1
            fitpol(nt) = fitpol(nt) + c(j + 1) * ortpol(nt)
         end do
         dinv(j) = 1.0_wp / div
         if (j == kplus) exit
         do i = 1, nt
            ns = i + 1
            h(ns) = ortpol(i) - a * ortpol(ns) - b * f(ns)
         end do
         do i = 1, nt
            ns = i + 1
            f(ns) = ortpol(ns)
            ortpol(ns) = h(ns)
         end do
      end do
   end subroutine polfit

end module trc
