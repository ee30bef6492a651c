! Every function of the gsph module (gsph.f90), called once at least on the flyer plate
! (scripts/ffi.sh checks with nm that this program reaches every function of gsph.h, and
! runs it): each result is checked against another call or against what the scene says.
!
!   every_f SCENE(flyer_plate.toml) WORK_DIR
program every
  use, intrinsic :: iso_c_binding
  use gsph
  implicit none
  type(c_ptr) :: sim, other
  character(len=1024) :: scene, dir
  character(kind=c_char, len=32), target :: unset_ref
  type(c_ptr), target :: sets(1)
  real(c_double) :: t, dt, t_end, k, i, p(3), ext(3)
  real(c_double), allocatable :: rho(:), series(:), a(:), x1(:), x2(:)
  real(c_double), target :: pos(4), spacing(1)
  integer(c_int32_t), target :: mat(4)
  integer(c_int32_t), allocatable :: ids(:)
  integer(c_size_t) :: n, d, snaps, comps, rows, cols
  integer(c_int64_t) :: steps, more
  type(gsph_particles) :: parts
  character(len=:), allocatable :: text
  integer :: failures = 0

  call get_command_argument(1, scene)
  call get_command_argument(2, dir)

  call expect(len(version()) > 0, 'version')
  call expect(gsph_set_threads(100000_c_size_t) == gsph_err_argument, 'set_threads(100000)')
  call expect(index(last_error(), 'threads per core') > 0, 'set_threads message')

  ! a run with its snapshots and series, as `gsph run`
  call ok(gsph_create_from_file(c_str(scene), c_null_ptr, 0_c_size_t, sim), 'create_from_file')
  call ok(gsph_count(sim, n), 'count')
  call ok(gsph_dim(sim, d), 'dim')
  call expect(n == 100 .and. d == 1, 'count and dim')
  call ok(gsph_schedule(sim, t_end, snaps), 'schedule')
  call expect(t_end == 0.5e-6_c_double .and. snaps == 10, 'schedule values')
  call ok(gsph_stable_dt(sim, dt), 'stable_dt')
  call expect(dt > 0, 'stable_dt value')
  call ok(gsph_open_snapshots(sim, c_str(trim(dir) // '/run')), 'open_snapshots')
  call ok(gsph_run(sim, steps), 'run')
  call ok(gsph_close_snapshots(sim), 'close_snapshots')
  call ok(gsph_time(sim, t, more), 'time')
  call expect(more == steps .and. abs(t - t_end) < 1e-18_c_double, 'run reached t_end')
  call ok(gsph_series_shape(sim, rows, cols), 'series_shape')
  allocate (series(rows * cols))
  call ok(gsph_read_series(sim, series, rows * cols), 'read_series')
  call expect(series((rows - 1) * cols + 2) == real(steps, c_double), 'series: last step')
  text = series_names(sim)
  call expect(text(1:10) == 't,step,dt,', 'series_names')
  call ok(gsph_write_series(sim, c_str(trim(dir) // '/series.csv')), 'write_series')

  ! stepping, fields, ids, external accelerations, budgets
  call ok(gsph_step(sim, 0.0_c_double, dt), 'step')
  call ok(gsph_advance(sim, t + 1e-8_c_double, more), 'advance')
  call expect(more > 0, 'advance steps')
  call ok(gsph_field_components(sim, c_str('deviator'), comps), 'field_components')
  call expect(comps == 6, 'deviator components')
  allocate (rho(n), ids(n), a(n))
  call ok(gsph_read_field(sim, c_str('density'), rho, n), 'read_field')
  rho(1) = rho(1) * 1.001_c_double
  call ok(gsph_write_field(sim, c_str('density'), rho, n), 'write_field')
  call ok(gsph_read_ids(sim, ids, n), 'read_ids')
  call expect(ids(100) == 99, 'ids')
  call ok(gsph_energy(sim, k, i), 'energy')
  call expect(k > 0 .and. i > 0, 'energies')
  a = 1.0e6_c_double
  call ok(gsph_set_acceleration(sim, a, n), 'set_acceleration')
  call ok(gsph_step(sim, 0.0_c_double, dt), 'step with acceleration')
  call ok(gsph_set_acceleration(sim, a, 0_c_size_t), 'remove acceleration')
  call ok(gsph_momentum(sim, p, ext), 'momentum')
  call expect(ext(1) > 0 .and. ext(2) == 0, 'external impulse')
  text = summary_json(sim)
  call expect(index(text, '"external_work"') > 0, 'summary_json')
  call ok(gsph_write_snapshot(sim, c_str(trim(dir) // '/now.csv')), 'write_snapshot')
  call ok(gsph_write_snapshots(sim, c_str(trim(dir) // '/one')), 'write_snapshots')
  call ok(gsph_open_snapshots(sim, c_str(trim(dir) // '/two')), 'open_snapshots')
  call expect(gsph_append_snapshot(sim) == gsph_err_argument, 'append at the same step')
  call ok(gsph_step(sim, 0.0_c_double, dt), 'step')
  call ok(gsph_append_snapshot(sim), 'append_snapshot')
  call ok(gsph_close_snapshots(sim), 'close_snapshots')
  call gsph_destroy(sim)
  call expect(gsph_count(sim, n) == gsph_err_pointer, 'a destroyed handle is refused')

  ! checkpoints continue bit for bit
  call ok(gsph_create_from_file(c_str(scene), c_null_ptr, 0_c_size_t, sim), 'create')
  call ok(gsph_advance(sim, 0.1e-6_c_double, steps), 'advance')
  call ok(gsph_write_checkpoint(sim, c_str(trim(dir) // '/ck')), 'write_checkpoint')
  call ok(gsph_create_from_checkpoint(c_str(trim(dir) // '/ck'), other), 'create_from_checkpoint')
  call ok(gsph_advance(sim, 0.2e-6_c_double, steps), 'advance')
  call ok(gsph_advance(other, 0.2e-6_c_double, steps), 'advance')
  allocate (x1(100), x2(100))
  call ok(gsph_read_field(sim, c_str('x'), x1, 100_c_size_t), 'read x')
  call ok(gsph_read_field(other, c_str('x'), x2, 100_c_size_t), 'read x')
  call expect(all(x1 == x2), 'checkpoint continues bit for bit')
  call gsph_destroy(other)
  call gsph_destroy(sim)

  ! an override that unsets a key (the [reference]: no l1_error in the summary)
  unset_ref = 'unset:reference' // c_null_char
  sets(1) = c_loc(unset_ref)
  call ok(gsph_create_from_file(c_str(scene), c_loc(sets), 1_c_size_t, sim), 'create with unset')
  text = summary_json(sim)
  call expect(index(text, 'l1_error') == 0 .and. index(text, 'energy_final') > 0, 'unset reference')
  call gsph_destroy(sim)

  ! scene text, the caller's particles
  call ok(gsph_create_from_text(c_str('dim = 1' // new_line('a') // 'scheme = "ts1"' // new_line('a') // &
      't_end = 1e-7' // new_line('a') // '[[materials]]' // new_line('a') // 'name = "m"' // new_line('a') // &
      'rho0 = 1000.0' // new_line('a') // 'eos = { type = "linear", c0 = 1000.0 }' // new_line('a') // &
      '[[bodies]]' // new_line('a') // 'material = "m"' // new_line('a') // &
      'shape = { type = "segment", min = 0.0, max = 1e-3 }' // new_line('a') // 'spacing = 1e-4'), &
      c_null_ptr, 0_c_size_t, sim), 'create_from_text')
  call ok(gsph_count(sim, n), 'count')
  call expect(n == 10, 'from_text particles')
  call gsph_destroy(sim)
  pos = [0.0_c_double, 1e-4_c_double, 2e-4_c_double, 3e-4_c_double]
  mat = 0
  spacing = 1e-4_c_double
  parts%count = 4
  parts%position = c_loc(pos)
  parts%velocity = c_null_ptr
  parts%density = c_null_ptr
  parts%energy = c_null_ptr
  parts%mass = c_null_ptr
  parts%material = c_loc(mat)
  parts%spacing = c_loc(spacing)
  parts%spacing_count = 1
  call ok(gsph_create_from_particles(c_str('dim = 1' // new_line('a') // 'scheme = "ts1"' // new_line('a') // &
      't_end = 1e-7' // new_line('a') // '[[materials]]' // new_line('a') // 'name = "m"' // new_line('a') // &
      'rho0 = 1000.0' // new_line('a') // 'eos = { type = "linear", c0 = 1000.0 }'), &
      c_null_ptr, 0_c_size_t, parts, sim), 'create_from_particles')
  call ok(gsph_count(sim, n), 'count')
  call expect(n == 4, 'from_particles count')
  call gsph_destroy(sim)

  if (failures > 0) stop 1
  write (*, '(a)') 'every (Fortran): every function of the gsph module called and checked'

contains

  subroutine ok(status, what)
    integer(c_int), intent(in) :: status
    character(len=*), intent(in) :: what
    if (status /= gsph_ok) then
      write (0, '(a,a,a,a)') 'every (Fortran): ', what, ' failed: ', last_error()
      stop 1
    end if
  end subroutine

  subroutine expect(cond, what)
    logical, intent(in) :: cond
    character(len=*), intent(in) :: what
    if (.not. cond) then
      write (0, '(a,a)') 'every (Fortran): FAILED: ', what
      failures = failures + 1
    end if
  end subroutine
end program
