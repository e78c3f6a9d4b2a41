!> Text and types of HDF5 files apart from any open file: C strings handed out by HDF5
!> (variable-length strings) as Fortran text, the memory type to read stored text with
!> (its character set kept), a dataset's type class, and extents for messages.
module davit_io_hdf5_text
  use, intrinsic :: iso_c_binding, only: c_ptr, c_char, c_size_t, c_associated, c_f_pointer
  use hdf5, only: hid_t, hsize_t, size_t, H5T_FORTRAN_S1, h5dget_type_f, h5tget_class_f, &
                  h5tclose_f, h5tcopy_f, h5tset_size_f, h5tget_cset_f, h5tset_cset_f
  use davit_kinds, only: i8
  use davit_io_text, only: int_text, join_text
  implicit none
  private
  public :: extents_text, dataset_class, c_length, c_text, text_type

  interface
    !> The C library's strlen.
    function c_strlen(s) bind(C, name="strlen") result(n)
      import :: c_ptr, c_size_t
      type(c_ptr), value :: s
      integer(c_size_t) :: n
    end function c_strlen
  end interface

contains

  !> "2 x 3 x 4" for messages.
  function extents_text(d) result(text)
    !> Extents of a dataset.
    integer(hsize_t), intent(in) :: d(:)
    character(len=:), allocatable :: text
    character(len=20) :: items(size(d))
    integer :: k
    do k = 1, size(d)
      items(k) = int_text(int(d(k), i8))
    end do
    text = join_text(items, " x ")
  end function extents_text

  !> The type class of dataset `dset` (H5T_INTEGER_F, H5T_FLOAT_F, H5T_STRING_F, ...).
  integer function dataset_class(dset) result(tclass)
    !> The open dataset.
    integer(hid_t), intent(in) :: dset
    integer(hid_t) :: ftype
    integer :: hdferr
    tclass = -1
    call h5dget_type_f(dset, ftype, hdferr)
    if (hdferr /= 0) return
    call h5tget_class_f(ftype, tclass, hdferr)
    if (hdferr /= 0) tclass = -1
    call h5tclose_f(ftype, hdferr)
  end function dataset_class

  !> Length of the C string at `p` (0 for a null pointer: HDF5's empty string).
  integer function c_length(p) result(n)
    !> Address of a NUL-terminated C string (may be null).
    type(c_ptr), intent(in) :: p
    n = 0
    if (.not. c_associated(p)) return
    n = int(c_strlen(p))
  end function c_length

  !> The C string at `p` as Fortran text ("" for a null pointer).
  function c_text(p) result(text)
    !> Address of a NUL-terminated C string (may be null).
    type(c_ptr), intent(in) :: p
    character(len=:), allocatable :: text
    character(kind=c_char), pointer :: chars(:)
    integer :: i, n
    n = c_length(p)
    allocate (character(len=n) :: text)
    if (n == 0) return
    call c_f_pointer(p, chars, [n])
    do i = 1, n
      text(i:i) = chars(i)
    end do
  end function c_text

  !> The memory type of `width` characters for reading text stored as `ftype`: its
  !> character set too, since HDF5 converts no text between ASCII and UTF-8 (davit writes
  !> UTF-8 since its files name their dimensions; older files are ASCII).
  subroutine text_type(ftype, width, mtype)
    !> The stored (file) datatype of the text.
    integer(hid_t), intent(in) :: ftype
    !> Characters per string.
    integer(size_t), intent(in) :: width
    !> The memory datatype (the caller closes it).
    integer(hid_t), intent(out) :: mtype
    integer :: cset, hdferr
    call h5tcopy_f(H5T_FORTRAN_S1, mtype, hdferr)
    call h5tset_size_f(mtype, width, hdferr)
    call h5tget_cset_f(ftype, cset, hdferr)
    if (hdferr == 0) call h5tset_cset_f(mtype, cset, hdferr)
  end subroutine text_type

end module davit_io_hdf5_text
