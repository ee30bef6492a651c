! gsph Fortran interface: iso_c_binding declarations of the C ABI (gsph.h) and helpers
! that turn Fortran strings into C strings. Compile with your program and link -lgsph:
!   gfortran -c gsph.f90 && gfortran prog.f90 gsph.o -L<dir> -lgsph
! Status codes are those of gsph.h (GSPH_OK = 0). See docs/embedding.md.
module gsph
  use, intrinsic :: iso_c_binding
  implicit none
  private
  public :: gsph_ok, gsph_err_argument, c_str, last_error
  public :: gsph_create_from_file, gsph_destroy, gsph_count, gsph_dim, gsph_time
  public :: gsph_step, gsph_advance, gsph_run, gsph_stable_dt
  public :: gsph_field_components, gsph_read_field, gsph_write_field
  public :: gsph_set_acceleration, gsph_momentum, gsph_energy

  integer(c_int), parameter :: gsph_ok = 0, gsph_err_argument = 2

  interface
    integer(c_int) function gsph_create_from_file(path, overrides, n_overrides, sim) bind(c)
      import :: c_int, c_char, c_ptr, c_size_t
      character(kind=c_char), dimension(*), intent(in) :: path
      type(c_ptr), value :: overrides
      integer(c_size_t), value :: n_overrides
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

  !> gsph's message for the last failed call on this thread.
  function last_error() result(msg)
    character(len=:), allocatable :: msg
    type(c_ptr) :: p
    character(kind=c_char), pointer :: chars(:)
    integer :: n, i
    p = gsph_last_error()
    n = int(c_strlen(p))
    call c_f_pointer(p, chars, [n])
    allocate(character(len=n) :: msg)
    do i = 1, n
      msg(i:i) = chars(i)
    end do
  end function
end module gsph
