!> `davit bench`'s accuracy column (issue 14): each scene's run against a converged
!> reference of the same deck (`bench_reference.h5` in the decks folder, written by
!> `python -m postproc.bench_reference`: RK4 at a 10x smaller step, the paper-literal
!> scene at a 4x smaller one), so that every speed figure stands beside the error it was
!> bought with. The errors are those of the work-precision study (postproc.study): the
!> largest CG distance on the common samples before the reference's first fender contact
!> and after it, and the relative error of the launch log's resolved peak sling and
!> cable-segment tensions (the largest over slings and segments).
module davit_bench_accuracy
  use davit_kinds, only: wp
  use davit_error, only: error_type
  use davit_io_hdf5_reader, only: h5_reader_type
  implicit none
  private
  public :: accuracy_type, scene_accuracy

  type :: accuracy_type
    !> .false. where the decks folder has no reference for the scene.
    logical :: known = .false.
    !> Largest CG distance [m] before the reference's first contact and after it (0 if
    !> the reference has none), relative peak-tension errors [-].
    real(wp) :: cg_before = 0.0_wp, cg_after = 0.0_wp, sling = 0.0_wp, segment = 0.0_wp
  end type accuracy_type

contains

  !> Compare a run (sample times, CG positions (3, n), resolved peaks) with the reference
  !> of scene `name` in `path`; unknown (known = .false.) when the file or the scene is
  !> missing or unreadable.
  function scene_accuracy(path, name, time, position, sling, segment) result(acc)
    !> Reference file, and the scene's name (its group in the file).
    character(len=*), intent(in) :: path, name
    !> The run's sample times [s], CG positions (3, n) [m] (inertial frame), and resolved peak
    !> sling and cable-segment tensions [N].
    real(wp), intent(in) :: time(:), position(:, :), sling(:), segment(:)
    type(accuracy_type) :: acc
    type(h5_reader_type) :: h5
    type(error_type), allocatable :: error
    real(wp), allocatable :: rt(:), rx(:), contact(:), rsling(:), rseg(:)
    integer, allocatable :: dims(:)
    logical :: exists
    integer :: n, k
    real(wp) :: d
    inquire (file=path, exist=exists)
    if (.not. exists) return
    call h5%open(path, error)
    if (allocated(error)) return
    call h5%read_1d(name//"/time", rt, error)
    if (.not. allocated(error)) call h5%read_array(name//"/position", rx, dims, error)
    if (.not. allocated(error)) call h5%read_1d(name//"/first_contact_time", contact, error)
    if (.not. allocated(error)) call h5%read_1d(name//"/peak_sling_tension", rsling, error)
    if (.not. allocated(error)) call h5%read_1d(name//"/peak_segment_tension", rseg, error)
    call h5%close()
    if (allocated(error)) return
    if (size(rsling) /= size(sling) .or. size(rseg) /= size(segment)) return
    n = min(size(time), size(rt))
    do while (n > 1)
      if (abs(time(n) - rt(n)) <= 1.0e-9_wp) exit
      n = n - 1
    end do
    do k = 1, n
      if (abs(time(k) - rt(k)) > 1.0e-9_wp) return
      d = norm2(position(:, k) - rx(3*k - 2:3*k))
      if (contact(1) < 0.0_wp .or. rt(k) < contact(1)) then
        acc%cg_before = max(acc%cg_before, d)
      else
        acc%cg_after = max(acc%cg_after, d)
      end if
    end do
    acc%sling = worst_relative(sling, rsling)
    acc%segment = worst_relative(segment, rseg)
    acc%known = .true.
  end function scene_accuracy

  !> max |a/b - 1| over the entries with b > 0.
  pure real(wp) function worst_relative(a, b) result(e)
    !> Values a and references b.
    real(wp), intent(in) :: a(:), b(:)
    integer :: i
    e = 0.0_wp
    do i = 1, size(b)
      if (b(i) > 0.0_wp) e = max(e, abs(a(i)/b(i) - 1.0_wp))
    end do
  end function worst_relative

end module davit_bench_accuracy
