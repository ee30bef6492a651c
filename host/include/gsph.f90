! gsph Fortran interface: iso_c_binding declarations of the whole C ABI (gsph.h; scripts/ffi.sh
! checks that every function of gsph.h is bound here and called by a program) and helpers
! that turn Fortran strings into C strings and back. Compile with your program and link
! -lgsph:
!   gfortran -c gsph.f90 && gfortran prog.f90 gsph.o -L<dir> -lgsph
! Status codes are those of gsph.h (GSPH_OK = 0). Optional outputs of the C ABI (null
! allowed) are plain arguments here: pass a variable. Overrides are `type(c_ptr)` to an
! array of C strings (c_null_ptr with 0 of them); `KEY=VALUE` sets a key, `unset:KEY`
! removes one. See docs/embedding.md.
module gsph
  use, intrinsic :: iso_c_binding
  implicit none
  private
  public :: gsph_ok, gsph_err_pointer, gsph_err_argument, gsph_err_scene, gsph_err_simulation
  public :: gsph_err_io, gsph_err_internal, gsph_err_busy
  public :: gsph_particles, c_str, last_error, version, summary_json, series_names
  public :: gsph_version, gsph_set_threads, gsph_last_error
  public :: gsph_create_from_file, gsph_create_from_text, gsph_create_from_particles
  public :: gsph_create_from_checkpoint, gsph_destroy
  public :: gsph_count, gsph_dim, gsph_time, gsph_stable_dt, gsph_schedule
  public :: gsph_step, gsph_advance, gsph_run
  public :: gsph_field_components, gsph_read_field, gsph_write_field, gsph_read_ids
  public :: gsph_set_acceleration, gsph_momentum, gsph_energy, gsph_summary_json
  public :: gsph_series_shape, gsph_series_names, gsph_read_series, gsph_write_series
  public :: gsph_write_snapshot, gsph_write_snapshots, gsph_open_snapshots
  public :: gsph_append_snapshot, gsph_close_snapshots, gsph_write_checkpoint

  integer(c_int), parameter :: gsph_ok = 0, gsph_err_pointer = 1, gsph_err_argument = 2
  integer(c_int), parameter :: gsph_err_scene = 3, gsph_err_simulation = 4, gsph_err_io = 5
  integer(c_int), parameter :: gsph_err_internal = 6, gsph_err_busy = 7

  !> The caller's particles (gsph_particles of gsph.h): c_loc of arrays, c_null_ptr for the
  !> optional ones (velocity, density, energy, mass).
  type, bind(c) :: gsph_particles
    integer(c_size_t) :: count
    type(c_ptr) :: position, velocity, density, energy, mass, material, spacing
    integer(c_size_t) :: spacing_count
  end type

  interface
    function gsph_version() bind(c) result(p)
      import :: c_ptr
      type(c_ptr) :: p
    end function
    integer(c_int) function gsph_set_threads(threads) bind(c)
      import :: c_int, c_size_t
      integer(c_size_t), value :: threads
    end function
    integer(c_int) function gsph_create_from_file(path, overrides, n_overrides, sim) bind(c)
      import :: c_int, c_char, c_ptr, c_size_t
      character(kind=c_char), dimension(*), intent(in) :: path
      type(c_ptr), value :: overrides
      integer(c_size_t), value :: n_overrides
      type(c_ptr), intent(out) :: sim
    end function
    integer(c_int) function gsph_create_from_text(text, overrides, n_overrides, sim) bind(c)
      import :: c_int, c_char, c_ptr, c_size_t
      character(kind=c_char), dimension(*), intent(in) :: text
      type(c_ptr), value :: overrides
      integer(c_size_t), value :: n_overrides
      type(c_ptr), intent(out) :: sim
    end function
    integer(c_int) function gsph_create_from_particles(settings, overrides, n_overrides, &
        particles, sim) bind(c)
      import :: c_int, c_char, c_ptr, c_size_t, gsph_particles
      character(kind=c_char), dimension(*), intent(in) :: settings
      type(c_ptr), value :: overrides
      integer(c_size_t), value :: n_overrides
      type(gsph_particles), intent(in) :: particles
      type(c_ptr), intent(out) :: sim
    end function
    integer(c_int) function gsph_create_from_checkpoint(dir, sim) bind(c)
      import :: c_int, c_char, c_ptr
      character(kind=c_char), dimension(*), intent(in) :: dir
      type(c_ptr), intent(out) :: sim
    end function
    subroutine gsph_destroy(sim) bind(c)
      import :: c_ptr
      type(c_ptr), value :: sim
    end subroutine
    integer(c_int) function gsph_count(sim, count) bind(c)
      import :: c_int, c_ptr, c_size_t
      type(c_ptr), value :: sim
      integer(c_size_t), intent(out) :: count
    end function
    integer(c_int) function gsph_dim(sim, dim) bind(c)
      import :: c_int, c_ptr, c_size_t
      type(c_ptr), value :: sim
      integer(c_size_t), intent(out) :: dim
    end function
    integer(c_int) function gsph_time(sim, t, steps) bind(c)
      import :: c_int, c_ptr, c_double, c_int64_t
      type(c_ptr), value :: sim
      real(c_double), intent(out) :: t
      integer(c_int64_t), intent(out) :: steps
    end function
    integer(c_int) function gsph_stable_dt(sim, dt) bind(c)
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: sim
      real(c_double), intent(out) :: dt
    end function
    integer(c_int) function gsph_schedule(sim, t_end, snapshots) bind(c)
      import :: c_int, c_ptr, c_double, c_size_t
      type(c_ptr), value :: sim
      real(c_double), intent(out) :: t_end
      integer(c_size_t), intent(out) :: snapshots
    end function
    integer(c_int) function gsph_step(sim, dt, dt_taken) bind(c)
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: sim
      real(c_double), value :: dt
      real(c_double), intent(out) :: dt_taken
    end function
    integer(c_int) function gsph_advance(sim, t, steps) bind(c)
      import :: c_int, c_ptr, c_double, c_int64_t
      type(c_ptr), value :: sim
      real(c_double), value :: t
      integer(c_int64_t), intent(out) :: steps
    end function
    integer(c_int) function gsph_run(sim, steps) bind(c)
      import :: c_int, c_ptr, c_int64_t
      type(c_ptr), value :: sim
      integer(c_int64_t), intent(out) :: steps
    end function
    integer(c_int) function gsph_field_components(sim, name, components) bind(c)
      import :: c_int, c_ptr, c_char, c_size_t
      type(c_ptr), value :: sim
      character(kind=c_char), dimension(*), intent(in) :: name
      integer(c_size_t), intent(out) :: components
    end function
    integer(c_int) function gsph_read_field(sim, name, buf, len) bind(c)
      import :: c_int, c_ptr, c_char, c_double, c_size_t
      type(c_ptr), value :: sim
      character(kind=c_char), dimension(*), intent(in) :: name
      real(c_double), dimension(*), intent(out) :: buf
      integer(c_size_t), value :: len
    end function
    integer(c_int) function gsph_write_field(sim, name, data, len) bind(c)
      import :: c_int, c_ptr, c_char, c_double, c_size_t
      type(c_ptr), value :: sim
      character(kind=c_char), dimension(*), intent(in) :: name
      real(c_double), dimension(*), intent(in) :: data
      integer(c_size_t), value :: len
    end function
    integer(c_int) function gsph_read_ids(sim, ids, len) bind(c)
      import :: c_int, c_ptr, c_int32_t, c_size_t
      type(c_ptr), value :: sim
      integer(c_int32_t), dimension(*), intent(out) :: ids
      integer(c_size_t), value :: len
    end function
    integer(c_int) function gsph_set_acceleration(sim, a, len) bind(c)
      import :: c_int, c_ptr, c_double, c_size_t
      type(c_ptr), value :: sim
      real(c_double), dimension(*), intent(in) :: a
      integer(c_size_t), value :: len
    end function
    integer(c_int) function gsph_momentum(sim, momentum, external) bind(c)
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: sim
      real(c_double), dimension(3), intent(out) :: momentum, external
    end function
    integer(c_int) function gsph_energy(sim, kinetic, internal) bind(c)
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: sim
      real(c_double), intent(out) :: kinetic, internal
    end function
    integer(c_int) function gsph_summary_json(sim, buf, len, needed) bind(c)
      import :: c_int, c_ptr, c_size_t
      type(c_ptr), value :: sim, buf
      integer(c_size_t), value :: len
      integer(c_size_t), intent(out) :: needed
    end function
    integer(c_int) function gsph_series_shape(sim, rows, columns) bind(c)
      import :: c_int, c_ptr, c_size_t
      type(c_ptr), value :: sim
      integer(c_size_t), intent(out) :: rows, columns
    end function
    integer(c_int) function gsph_series_names(sim, buf, len, needed) bind(c)
      import :: c_int, c_ptr, c_size_t
      type(c_ptr), value :: sim, buf
      integer(c_size_t), value :: len
      integer(c_size_t), intent(out) :: needed
    end function
    integer(c_int) function gsph_read_series(sim, buf, len) bind(c)
      import :: c_int, c_ptr, c_double, c_size_t
      type(c_ptr), value :: sim
      real(c_double), dimension(*), intent(out) :: buf
      integer(c_size_t), value :: len
    end function
    integer(c_int) function gsph_write_series(sim, path) bind(c)
      import :: c_int, c_ptr, c_char
      type(c_ptr), value :: sim
      character(kind=c_char), dimension(*), intent(in) :: path
    end function
    integer(c_int) function gsph_write_snapshot(sim, path) bind(c)
      import :: c_int, c_ptr, c_char
      type(c_ptr), value :: sim
      character(kind=c_char), dimension(*), intent(in) :: path
    end function
    integer(c_int) function gsph_write_snapshots(sim, dir) bind(c)
      import :: c_int, c_ptr, c_char
      type(c_ptr), value :: sim
      character(kind=c_char), dimension(*), intent(in) :: dir
    end function
    integer(c_int) function gsph_open_snapshots(sim, dir) bind(c)
      import :: c_int, c_ptr, c_char
      type(c_ptr), value :: sim
      character(kind=c_char), dimension(*), intent(in) :: dir
    end function
    integer(c_int) function gsph_append_snapshot(sim) bind(c)
      import :: c_int, c_ptr
      type(c_ptr), value :: sim
    end function
    integer(c_int) function gsph_close_snapshots(sim) bind(c)
      import :: c_int, c_ptr
      type(c_ptr), value :: sim
    end function
    integer(c_int) function gsph_write_checkpoint(sim, dir) bind(c)
      import :: c_int, c_ptr, c_char
      type(c_ptr), value :: sim
      character(kind=c_char), dimension(*), intent(in) :: dir
    end function
    function gsph_last_error() bind(c) result(p)
      import :: c_ptr
      type(c_ptr) :: p
    end function
    integer(c_size_t) function c_strlen(s) bind(c, name="strlen")
      import :: c_ptr, c_size_t
      type(c_ptr), value :: s
    end function
  end interface

contains

  !> A Fortran string as a NUL-terminated C string.
  function c_str(s) result(c)
    character(len=*), intent(in) :: s
    character(kind=c_char, len=len_trim(s) + 1) :: c
    c = trim(s) // c_null_char
  end function

  !> The NUL-terminated C string at `p` as a Fortran string.
  function from_c(p) result(msg)
    type(c_ptr), intent(in) :: p
    character(len=:), allocatable :: msg
    character(kind=c_char), pointer :: chars(:)
    integer :: n, i
    n = int(c_strlen(p))
    call c_f_pointer(p, chars, [n])
    allocate(character(len=n) :: msg)
    do i = 1, n
      msg(i:i) = chars(i)
    end do
  end function

  !> gsph's message for the last failed call on this thread.
  function last_error() result(msg)
    character(len=:), allocatable :: msg
    msg = from_c(gsph_last_error())
  end function

  !> The gsph version.
  function version() result(v)
    character(len=:), allocatable :: v
    v = from_c(gsph_version())
  end function

  !> The summary as JSON ("" if the call fails: see last_error()).
  function summary_json(sim) result(text)
    type(c_ptr), intent(in) :: sim
    character(len=:), allocatable :: text
    character(kind=c_char), allocatable, target :: buf(:)
    integer(c_size_t) :: need, size
    integer(c_int) :: status
    need = 0
    status = gsph_summary_json(sim, c_null_ptr, 0_c_size_t, need)
    size = max(need, 1_c_size_t)
    allocate(buf(size))
    text = ""
    if (gsph_summary_json(sim, c_loc(buf), size, need) == gsph_ok) text = from_c(c_loc(buf))
  end function

  !> The series' column names, comma-separated ("" if the call fails).
  function series_names(sim) result(text)
    type(c_ptr), intent(in) :: sim
    character(len=:), allocatable :: text
    character(kind=c_char), allocatable, target :: buf(:)
    integer(c_size_t) :: need, size
    integer(c_int) :: status
    need = 0
    status = gsph_series_names(sim, c_null_ptr, 0_c_size_t, need)
    size = max(need, 1_c_size_t)
    allocate(buf(size))
    text = ""
    if (gsph_series_names(sim, c_loc(buf), size, need) == gsph_ok) text = from_c(c_loc(buf))
  end function
end module gsph
