!> HDF5 output, one file per run. The file is written under `path.tmp` and renamed to
!> `path` only when closed, so an interrupted run never leaves a file that looks whole.
!> Every dataset carries `units` and `description` attributes. Time series are (components,
!> time) in Fortran order, which h5py shows as (time, components).
module davit_io_hdf5_writer
  use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char, c_loc, c_ptr
  use hdf5
  use davit_kinds, only: wp, i8
  use davit_error, only: error_type, fatal_error
  implicit none
  private
  public :: h5_writer_type

  type :: h5_writer_type
    integer(hid_t) :: file = -1
    character(len=:), allocatable :: path, tmp_path
    logical :: is_open = .false.
    !> First HDF5 failure while writing; reported by close().
    logical :: failed = .false.
    character(len=:), allocatable :: failed_what
  contains
    procedure :: create => writer_create
    procedure :: group => writer_group
    procedure :: write_1d => writer_write_1d
    procedure :: write_2d => writer_write_2d
    procedure :: write_3d => writer_write_3d
    procedure :: write_1d_int => writer_write_1d_int
    procedure :: write_strings => writer_write_strings
    procedure :: attr_str => writer_attr_str
    procedure :: attr_int => writer_attr_int
    procedure :: attr_real => writer_attr_real
    procedure :: close => writer_close
    procedure :: discard => writer_discard
  end type h5_writer_type

  interface
    function c_rename(old, new) bind(C, name="rename") result(status)
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: old(*), new(*)
      integer(c_int) :: status
    end function c_rename
  end interface

contains

  !> Create `path.tmp`; fails early (before any simulation) if the path is unwritable.
  subroutine writer_create(self, path, error)
    class(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: path
    type(error_type), allocatable, intent(out) :: error
    integer :: hdferr, perr
    integer(hid_t) :: fapl
    self%path = path
    self%tmp_path = path//".tmp"
    call h5open_f(hdferr)
    call h5eset_auto_f(0, hdferr)
    ! The 1.8 file format stores attributes over 64 KiB (a long deck's text) densely.
    call h5pcreate_f(H5P_FILE_ACCESS_F, fapl, perr)
    call h5pset_libver_bounds_f(fapl, H5F_LIBVER_V18_F, H5F_LIBVER_LATEST_F, perr)
    call h5fcreate_f(self%tmp_path, H5F_ACC_TRUNC_F, self%file, hdferr, access_prp=fapl)
    call h5pclose_f(fapl, perr)
    if (hdferr /= 0) then
      call fatal_error(error, "cannot create output file '"//path// &
                       "': directory missing or not writable")
      return
    end if
    self%is_open = .true.
  end subroutine writer_create

  subroutine writer_group(self, name)
    class(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: name
    integer(hid_t) :: gid
    integer :: hdferr
    call h5gcreate_f(self%file, name, gid, hdferr)
    call check(self, hdferr, "group "//name)
    if (hdferr == 0) call h5gclose_f(gid, hdferr)
  end subroutine writer_group

  subroutine writer_write_1d(self, name, data, units, description)
    class(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: name, units, description
    real(wp), intent(in) :: data(:)
    real(wp), allocatable, target :: buf(:)
    buf = data
    call write_real(self, name, shape(data, kind=hsize_t), c_loc(buf), units, description)
  end subroutine writer_write_1d

  subroutine writer_write_2d(self, name, data, units, description)
    class(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: name, units, description
    real(wp), intent(in) :: data(:, :)
    real(wp), allocatable, target :: buf(:, :)
    buf = data
    call write_real(self, name, shape(data, kind=hsize_t), c_loc(buf), units, description)
  end subroutine writer_write_2d

  subroutine writer_write_3d(self, name, data, units, description)
    class(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: name, units, description
    real(wp), intent(in) :: data(:, :, :)
    real(wp), allocatable, target :: buf(:, :, :)
    buf = data
    call write_real(self, name, shape(data, kind=hsize_t), c_loc(buf), units, description)
  end subroutine writer_write_3d

  !> 64-bit integer dataset (codes, counts, flags), with its units and description.
  subroutine writer_write_1d_int(self, name, data, units, description)
    class(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: name, units, description
    integer(i8), intent(in) :: data(:)
    integer(i8), allocatable, target :: buf(:)
    integer(hid_t) :: space, dset
    integer(hsize_t) :: dims(1)
    integer :: hdferr
    buf = data
    dims = size(data, kind=hsize_t)
    call h5screate_simple_f(1, dims, space, hdferr)
    call h5dcreate_f(self%file, name, H5T_STD_I64LE, space, dset, hdferr)
    call check(self, hdferr, name)
    if (hdferr /= 0) return
    call h5dwrite_f(dset, h5kind_to_type(i8, H5_INTEGER_KIND), c_loc(buf), hdferr)
    call check(self, hdferr, name)
    call describe(self, dset, units, description)
    call h5dclose_f(dset, hdferr)
    call h5sclose_f(space, hdferr)
  end subroutine writer_write_1d_int

  !> Fixed-length string dataset (blank-padded to the longest entry, at least 1 character).
  subroutine writer_write_strings(self, name, data, units, description)
    class(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: name, data(:), units, description
    character(len=:), allocatable, target :: buf(:)
    integer(hid_t) :: atype, space, dset
    integer(hsize_t) :: dims(1)
    integer :: hdferr, width, i
    width = 1
    do i = 1, size(data)
      width = max(width, len_trim(data(i)))
    end do
    allocate (character(len=width) :: buf(size(data)))
    do i = 1, size(data)
      buf(i) = data(i)
    end do
    dims = size(data, kind=hsize_t)
    call h5tcopy_f(H5T_FORTRAN_S1, atype, hdferr)
    call h5tset_size_f(atype, int(width, size_t), hdferr)
    call h5screate_simple_f(1, dims, space, hdferr)
    call h5dcreate_f(self%file, name, atype, space, dset, hdferr)
    call check(self, hdferr, name)
    if (hdferr == 0) then
      if (size(data) > 0) call h5dwrite_f(dset, atype, c_loc(buf), hdferr)
      call check(self, hdferr, name)
      call describe(self, dset, units, description)
      call h5dclose_f(dset, hdferr)
    end if
    call h5sclose_f(space, hdferr)
    call h5tclose_f(atype, hdferr)
  end subroutine writer_write_strings

  !> One double-precision dataset of any rank from a contiguous buffer, with its
  !> units and description.
  subroutine write_real(self, name, dims, buf, units, description)
    type(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: name, units, description
    integer(hsize_t), intent(in) :: dims(:)
    type(c_ptr), intent(in) :: buf
    integer(hid_t) :: space, dset
    integer :: hdferr
    call h5screate_simple_f(size(dims), dims, space, hdferr)
    call h5dcreate_f(self%file, name, H5T_NATIVE_DOUBLE, space, dset, hdferr)
    call check(self, hdferr, name)
    if (hdferr /= 0) return
    call h5dwrite_f(dset, H5T_NATIVE_DOUBLE, buf, hdferr)
    call check(self, hdferr, name)
    call describe(self, dset, units, description)
    call h5dclose_f(dset, hdferr)
    call h5sclose_f(space, hdferr)
  end subroutine write_real

  !> String attribute on the object `obj` ("/" for the root).
  subroutine writer_attr_str(self, obj, name, value)
    class(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: obj, name, value
    integer(hid_t) :: oid
    integer :: hdferr
    call h5oopen_f(self%file, obj, oid, hdferr)
    call check(self, hdferr, obj)
    if (hdferr /= 0) return
    call put_str(self, oid, name, value)
    call h5oclose_f(oid, hdferr)
  end subroutine writer_attr_str

  subroutine writer_attr_int(self, obj, name, value)
    class(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: obj, name
    integer(i8), intent(in), target :: value
    integer(hid_t) :: oid, space, attr
    integer :: hdferr
    call h5oopen_f(self%file, obj, oid, hdferr)
    call h5screate_f(H5S_SCALAR_F, space, hdferr)
    call h5acreate_f(oid, name, H5T_STD_I64LE, space, attr, hdferr)
    call check(self, hdferr, obj//"@"//name)
    if (hdferr == 0) then
      call h5awrite_f(attr, h5kind_to_type(i8, H5_INTEGER_KIND), c_loc(value), hdferr)
      call check(self, hdferr, obj//"@"//name)
      call h5aclose_f(attr, hdferr)
    end if
    call h5sclose_f(space, hdferr)
    call h5oclose_f(oid, hdferr)
  end subroutine writer_attr_int

  subroutine writer_attr_real(self, obj, name, value)
    class(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: obj, name
    real(wp), intent(in) :: value
    integer(hid_t) :: oid, space, attr
    integer(hsize_t) :: dims(1) = [1]
    integer :: hdferr
    call h5oopen_f(self%file, obj, oid, hdferr)
    call h5screate_f(H5S_SCALAR_F, space, hdferr)
    call h5acreate_f(oid, name, H5T_NATIVE_DOUBLE, space, attr, hdferr)
    call check(self, hdferr, obj//"@"//name)
    if (hdferr == 0) then
      call h5awrite_f(attr, H5T_NATIVE_DOUBLE, value, dims, hdferr)
      call h5aclose_f(attr, hdferr)
    end if
    call h5sclose_f(space, hdferr)
    call h5oclose_f(oid, hdferr)
  end subroutine writer_attr_real

  !> Close the file and rename it into place; reports any write failure.
  subroutine writer_close(self, error)
    class(h5_writer_type), intent(inout) :: self
    type(error_type), allocatable, intent(out) :: error
    integer :: hdferr
    if (.not. self%is_open) return
    call h5fclose_f(self%file, hdferr)
    self%is_open = .false.
    if (self%failed .or. hdferr /= 0) then
      call delete_file(self%tmp_path)
      if (self%failed) then
        call fatal_error(error, "writing '"//self%path//"' failed at "//self%failed_what)
      else
        call fatal_error(error, "closing '"//self%path//"' failed")
      end if
      return
    end if
    if (c_rename(self%tmp_path//c_null_char, self%path//c_null_char) /= 0) then
      call fatal_error(error, "cannot rename '"//self%tmp_path//"' to '"//self%path//"'")
    end if
  end subroutine writer_close

  !> Close and delete the temporary file (nothing is left behind).
  subroutine writer_discard(self)
    class(h5_writer_type), intent(inout) :: self
    integer :: hdferr
    if (.not. self%is_open) return
    call h5fclose_f(self%file, hdferr)
    self%is_open = .false.
    call delete_file(self%tmp_path)
  end subroutine writer_discard

  subroutine describe(self, dset, units, description)
    type(h5_writer_type), intent(inout) :: self
    integer(hid_t), intent(in) :: dset
    character(len=*), intent(in) :: units, description
    call put_str(self, dset, "units", units)
    call put_str(self, dset, "description", description)
  end subroutine describe

  subroutine put_str(self, oid, name, value)
    type(h5_writer_type), intent(inout) :: self
    integer(hid_t), intent(in) :: oid
    character(len=*), intent(in) :: name, value
    integer(hid_t) :: atype, space, attr
    integer(hsize_t) :: dims(1) = [1]
    integer :: hdferr
    call h5tcopy_f(H5T_FORTRAN_S1, atype, hdferr)
    call h5tset_size_f(atype, int(max(1, len(value)), size_t), hdferr)
    call h5screate_f(H5S_SCALAR_F, space, hdferr)
    call h5acreate_f(oid, name, atype, space, attr, hdferr)
    call check(self, hdferr, "attribute "//name)
    if (hdferr == 0) then
      if (len(value) == 0) then
        call h5awrite_f(attr, atype, " ", dims, hdferr)
      else
        call h5awrite_f(attr, atype, value, dims, hdferr)
      end if
      call check(self, hdferr, "attribute "//name)
      call h5aclose_f(attr, hdferr)
    end if
    call h5sclose_f(space, hdferr)
    call h5tclose_f(atype, hdferr)
  end subroutine put_str

  subroutine check(self, hdferr, what)
    type(h5_writer_type), intent(inout) :: self
    integer, intent(in) :: hdferr
    character(len=*), intent(in) :: what
    if (hdferr /= 0 .and. .not. self%failed) then
      self%failed = .true.
      self%failed_what = what
    end if
  end subroutine check

  subroutine delete_file(path)
    character(len=*), intent(in) :: path
    integer :: unit, ios
    open (newunit=unit, file=path, status="old", iostat=ios)
    if (ios == 0) close (unit, status="delete")
  end subroutine delete_file

end module davit_io_hdf5_writer
