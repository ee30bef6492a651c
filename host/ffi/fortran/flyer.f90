! The flyer plate (cases/flyer_plate.toml) from Fortran: loads the scene, runs it to t_end
! as `gsph run` does, reads the stress deviator and pressure, and checks the peak
! compressive sigma_xx = s_xx - p against the value on the command line (scripts/ffi.sh
! passes the one `gsph run` wrote to final.csv).
!
!   flyer_f SCENE EXPECTED_PEAK_SIGMA_XX
program flyer
  use, intrinsic :: iso_c_binding
  use gsph
  implicit none
  type(c_ptr) :: sim
  character(len=1024) :: scene, arg
  real(c_double) :: expected, peak, rel, t
  real(c_double), allocatable :: s(:), p(:)
  integer(c_size_t) :: n, comps, i
  integer(c_int64_t) :: steps

  if (command_argument_count() < 2) then
    write (0, '(a)') 'usage: flyer_f SCENE EXPECTED_PEAK_SIGMA_XX'
    stop 2
  end if
  call get_command_argument(1, scene)
  call get_command_argument(2, arg)
  read (arg, *) expected

  if (gsph_create_from_file(c_str(scene), c_null_ptr, 0_c_size_t, sim) /= gsph_ok) call die('create')
  if (gsph_run(sim, steps) /= gsph_ok) call die('run')
  if (gsph_count(sim, n) /= gsph_ok) call die('count')
  if (gsph_field_components(sim, c_str('deviator'), comps) /= gsph_ok) call die('components')
  allocate (s(n * comps), p(n))
  if (gsph_read_field(sim, c_str('deviator'), s, n * comps) /= gsph_ok) call die('deviator')
  if (gsph_read_field(sim, c_str('pressure'), p, n) /= gsph_ok) call die('pressure')
  ! a field the scene does not simulate is refused with its reason
  if (gsph_read_field(sim, c_str('damage'), p, n) /= gsph_err_argument) then
    write (0, '(a)') 'flyer_f: reading damage of a scene without damage was accepted'
    stop 1
  end if
  write (*, '(a,a)') 'flyer (Fortran): damage refused: ', last_error()
  if (gsph_read_field(sim, c_str('pressure'), p, n) /= gsph_ok) call die('pressure')
  peak = 0
  do i = 1, n
    peak = min(peak, s((i - 1) * comps + 1) - p(i))
  end do
  if (gsph_time(sim, t, steps) /= gsph_ok) call die('time')
  write (*, '(a,i0,a,i0,a,es24.16,a,es24.16,a)') 'flyer (Fortran): ', n, ' particles, ', steps, &
    ' steps, peak sigma_xx ', peak, ' Pa (gsph run: ', expected, ')'
  call gsph_destroy(sim)
  rel = abs(peak - expected) / abs(expected)
  if (.not. (rel <= 1d-12)) then
    write (0, '(a,es10.3)') 'flyer_f: peak sigma_xx differs from gsph run by (relative) ', rel
    stop 1
  end if

contains
  subroutine die(what)
    character(len=*), intent(in) :: what
    write (0, '(a,a,a)') 'flyer_f: ', what, ': ' // last_error()
    stop 1
  end subroutine
end program flyer
