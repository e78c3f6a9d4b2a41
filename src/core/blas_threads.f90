!> One thread for the BLAS/LAPACK library: davit calls it only on small matrices (set-up
!> solves, 6x6 inverses, the Rosenbrock Jacobians) from inside its own OpenMP sweep
!> threads, where OpenBLAS's own thread pool only competes for the cores (its idle
!> workers spin in sched_yield: 5-12 % of a run's samples under perf, issue 14).
!> OPENBLAS_NUM_THREADS is read when the library loads, before any of davit runs, so the
!> run-time call is looked up by name (dlsym): with another BLAS nothing happens.
module davit_core_blas_threads
  use, intrinsic :: iso_c_binding, only: c_ptr, c_funptr, c_null_ptr, c_char, c_int, &
                                         c_null_char, c_associated, c_f_procpointer
  implicit none
  private
  public :: single_threaded_blas, stop_idle_blas_workers

  interface
    function dlsym(handle, symbol) bind(c, name="dlsym") result(address)
      import :: c_ptr, c_funptr, c_char
      type(c_ptr), value :: handle
      !> Name of the C symbol looked up, NUL-terminated.
      character(kind=c_char), intent(in) :: symbol(*)
      type(c_funptr) :: address
    end function dlsym
  end interface

  abstract interface
    subroutine set_threads_interface(n) bind(c)
      import :: c_int
      integer(c_int), value :: n
    end subroutine set_threads_interface
    function shutdown_interface() bind(c) result(status)
      import :: c_int
      integer(c_int) :: status
    end function shutdown_interface
  end interface

contains

  !> openblas_set_num_threads(1) where the linked BLAS is OpenBLAS (RTLD_DEFAULT search).
  subroutine single_threaded_blas()
    type(c_funptr) :: address
    procedure(set_threads_interface), pointer :: set_threads
    address = dlsym(c_null_ptr, "openblas_set_num_threads"//c_null_char)
    if (.not. c_associated(address)) return
    call c_f_procpointer(address, set_threads)
    call set_threads(1_c_int)
  end subroutine single_threaded_blas

  !> Stop OpenBLAS's worker threads, which its library constructor starts before davit
  !> runs (one per further core): after single_threaded_blas nothing hands them work, but
  !> each spins in sched_yield until its timeout, ~0.1 s of a second core's time per process
  !> (`/usr/bin/time` of a 40 s launch: 0.20+0.10 s user+system, 0.20+0.01 s with
  !> OPENBLAS_NUM_THREADS=1). blas_thread_shutdown_ is OpenBLAS's own (its fork handler);
  !> a later call that wanted threads would start them again. Only for the davit program:
  !> a host that loads davit's library owns its BLAS threads.
  subroutine stop_idle_blas_workers()
    type(c_funptr) :: address
    procedure(shutdown_interface), pointer :: shutdown
    integer(c_int) :: status
    address = dlsym(c_null_ptr, "blas_thread_shutdown_"//c_null_char)
    if (.not. c_associated(address)) return
    call c_f_procpointer(address, shutdown)
    status = shutdown()
  end subroutine stop_idle_blas_workers

end module davit_core_blas_threads
