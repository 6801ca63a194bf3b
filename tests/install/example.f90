! A minimal Fortran program against the installed railcontact through iso_c_binding
! (ctest install.package; docs/C_API.md "Fortran"):
!   gfortran example.f90 -L PREFIX/lib -lrailcontact
! nH-FastSim creep forces on a Hertzian ellipse, checked against saturation at mu F3.
program railcontact_example
  use, intrinsic :: iso_c_binding
  implicit none

  type, bind(c) :: rc_creepage
    real(c_double) :: xi, eta, phi_per_m
  end type
  type, bind(c) :: rc_forces
    real(c_double) :: F1_N, F2_N, M3_Nm, adhesion_fraction
  end type

  interface
    integer(c_int) function rc_solver_create(solver) bind(c, name="rc_solver_create")
      import :: c_ptr, c_int
      type(c_ptr), intent(out) :: solver
    end function
    integer(c_int) function rc_solver_destroy(solver) bind(c, name="rc_solver_destroy")
      import :: c_ptr, c_int
      type(c_ptr), value :: solver
    end function
    integer(c_int) function rc_solver_set_ellipse(solver, a, b, f3) bind(c, name="rc_solver_set_ellipse")
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: solver
      real(c_double), value :: a, b, f3
    end function
    integer(c_int) function rc_solver_solve(solver, creepage, forces) bind(c, name="rc_solver_solve")
      import :: c_ptr, c_int, rc_creepage, rc_forces
      type(c_ptr), value :: solver
      type(rc_creepage), intent(in) :: creepage
      type(rc_forces), intent(out) :: forces
    end function
  end interface

  type(c_ptr) :: solver
  type(rc_forces) :: forces
  integer(c_int) :: status

  status = rc_solver_create(solver)
  if (status /= 0) stop 1
  status = rc_solver_set_ellipse(solver, 6d-3, 4d-3, 80d3)   ! a, b (m), F3 (N)
  if (status /= 0) stop 2
  status = rc_solver_solve(solver, rc_creepage(0.05d0, 0d0, 0d0), forces)
  if (status /= 0) stop 3
  print '(a, f10.1, a, f10.1, a)', 'Fortran: F1 = ', forces%F1_N, ' N (-mu F3 = ', -0.3d0 * 80d3, ' N)'
  if (abs(forces%F1_N / (-0.3d0 * 80d3) - 1d0) > 1d-2) stop 4
  status = rc_solver_solve(solver, rc_creepage(ieee_nan(), 0d0, 0d0), forces)
  if (status /= 1) stop 5    ! RC_INVALID_INPUT
  status = rc_solver_destroy(solver)
contains
  real(c_double) function ieee_nan()
    use, intrinsic :: ieee_arithmetic
    ieee_nan = ieee_value(0d0, ieee_quiet_nan)
  end function
end program
