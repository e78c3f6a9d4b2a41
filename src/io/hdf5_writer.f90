!> HDF5 output, one file per run. The file is written under a name of its own,
!> `path.tmp.<pid>.<n>`, and renamed to `path` only when closed, so an interrupted run never
!> leaves a file that looks whole. While it is written, davit holds the advisory lock
!> `path.lock`, and the output's path is checked before any work (davit_io_output_lock: a
!> second davit on the same output stops with a message; an input deck, a database, a
!> folder or a FIFO given as the output is refused).
!> Every dataset carries `units`, `description` and `long_name` (the same text, the name
!> netCDF/CF tools show) as UTF-8 strings. Time series are (components, time) in Fortran
!> order, which h5py shows as (time, components). Text datasets (a sweep's messages and
!> outcomes, a benchmark's names) are variable-length UTF-8 strings.
!>
!> Named dimensions (xarray/netCDF-4 readable): a dataset written with `dims` (one name per
!> axis, blank-separated, in the order of the Fortran array's extents) has each axis
!> attached to a netCDF-4 dimension (davit_io_hdf5_dims says how).
module davit_io_hdf5_writer
  use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char, c_loc, c_ptr
  use hdf5
  use davit_kinds, only: wp, i8
  use davit_error, only: error_type, fatal_error
  use davit_io_hdf5_reader, only: h5_start
  use davit_io_hdf5_dims, only: dim_registry_type, describe, put_str, note_failure
  use davit_io_files, only: create_empty, remove_file
  use davit_io_output_lock, only: check_output_path, acquire_lock, release_lock, note_tmp, &
                                  tmp_suffix, create_cause
  implicit none
  private
  public :: h5_writer_type, check_output_path, acquire_lock, release_lock

  type :: h5_writer_type
    !> HDF5 identifier of the open file (-1: none).
    integer(hid_t) :: file = -1
    !> The output's path and the temporary file written until close.
    character(len=:), allocatable :: path, tmp_path
    !> Where close() puts the file (path, unless retarget() names another).
    character(len=:), allocatable :: final_path
    !> Whether a file is open.
    logical :: is_open = .false.
    !> This writer took path.lock (and releases it); false when the caller holds it.
    logical :: owns_lock = .false.
    !> What the first HDF5 failure while writing was writing (unallocated while none);
    !> reported by close().
    character(len=:), allocatable :: failed_what
    !> The file's dimension scales and the axes attached to them (davit_io_hdf5_dims).
    type(dim_registry_type) :: scales
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
    procedure :: retarget => writer_retarget
  end type h5_writer_type

  interface
    function c_rename(old, new) bind(C, name="rename") result(status)
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: old(*), new(*)
      integer(c_int) :: status
    end function c_rename
  end interface

contains

  !> Check `path`, take its lock and create the temporary file; fails early (before any
  !> simulation) if the path is unwritable, not a davit output, or being written by
  !> another davit.
  subroutine writer_create(self, path, error)
    !> The writer.
    class(h5_writer_type), intent(inout) :: self
    !> Path of the output.
    character(len=*), intent(in) :: path
    !> Set when the path is refused, locked or cannot be created.
    type(error_type), allocatable, intent(out) :: error
    integer :: hdferr, perr, status
    integer(hid_t) :: fapl
    self%path = path
    self%final_path = path
    if (allocated(self%failed_what)) deallocate (self%failed_what)
    call self%scales%reset()
    call check_output_path(path, error)
    if (allocated(error)) return
    call acquire_lock(path, self%owns_lock, error)
    if (allocated(error)) return
    self%tmp_path = path//tmp_suffix()
    call note_tmp(path, self%tmp_path)
    ! created here first, so that a failure names its cause (HDF5's does not)
    status = create_empty(self%tmp_path)
    hdferr = status
    if (status == 0) then
      call h5_start()
      ! The 1.8 file format stores attributes over 64 KiB (a long deck's text) densely.
      call h5pcreate_f(H5P_FILE_ACCESS_F, fapl, perr)
      call h5pset_libver_bounds_f(fapl, H5F_LIBVER_V18_F, H5F_LIBVER_LATEST_F, perr)
      call h5fcreate_f(self%tmp_path, H5F_ACC_TRUNC_F, self%file, hdferr, access_prp=fapl)
      call h5pclose_f(fapl, perr)
    end if
    if (hdferr /= 0) then
      if (status == 0) call delete_file(self%tmp_path)
      if (self%owns_lock) call release_lock(path)
      self%owns_lock = .false.
      call fatal_error(error, "cannot create output file '"//path//"' (as '"// &
                       self%tmp_path//"' until it is whole): "//create_cause(status))
      return
    end if
    self%is_open = .true.
  end subroutine writer_create

  !> Put the file under `path` when closed instead of the name given to create().
  subroutine writer_retarget(self, path)
    !> The writer.
    class(h5_writer_type), intent(inout) :: self
    !> Path the file is put under at close.
    character(len=*), intent(in) :: path
    self%final_path = path
  end subroutine writer_retarget

  subroutine writer_group(self, name)
    !> The writer.
    class(h5_writer_type), intent(inout) :: self
    !> Path of the group ("/boat").
    character(len=*), intent(in) :: name
    integer(hid_t) :: gid
    integer :: hdferr
    call h5gcreate_f(self%file, name, gid, hdferr)
    call note_failure(self%failed_what, hdferr, "group "//name)
    if (hdferr == 0) call h5gclose_f(gid, hdferr)
  end subroutine writer_group

  subroutine writer_write_1d(self, name, data, units, description, dims)
    !> The writer.
    class(h5_writer_type), intent(inout) :: self
    !> Path of the dataset; its units; what it holds.
    character(len=*), intent(in) :: name, units, description
    !> The values.
    real(wp), intent(in) :: data(:)
    !> Dimension names, one per axis of `data` (see the module comment).
    character(len=*), intent(in), optional :: dims
    real(wp), allocatable, target :: buf(:)
    buf = data
    call write_dataset(self, name, shape(data, kind=hsize_t), H5T_NATIVE_DOUBLE, &
                       H5T_NATIVE_DOUBLE, c_loc(buf), units, description, dims)
  end subroutine writer_write_1d

  subroutine writer_write_2d(self, name, data, units, description, dims)
    !> The writer.
    class(h5_writer_type), intent(inout) :: self
    !> Path of the dataset; its units; what it holds.
    character(len=*), intent(in) :: name, units, description
    !> The values (Fortran order; HDF5 shows them transposed).
    real(wp), intent(in) :: data(:, :)
    !> Dimension names, one per axis of `data` (see the module comment).
    character(len=*), intent(in), optional :: dims
    real(wp), allocatable, target :: buf(:, :)
    buf = data
    call write_dataset(self, name, shape(data, kind=hsize_t), H5T_NATIVE_DOUBLE, &
                       H5T_NATIVE_DOUBLE, c_loc(buf), units, description, dims)
  end subroutine writer_write_2d

  subroutine writer_write_3d(self, name, data, units, description, dims)
    !> The writer.
    class(h5_writer_type), intent(inout) :: self
    !> Path of the dataset; its units; what it holds.
    character(len=*), intent(in) :: name, units, description
    !> The values (Fortran order; HDF5 shows them transposed).
    real(wp), intent(in) :: data(:, :, :)
    !> Dimension names, one per axis of `data` (see the module comment).
    character(len=*), intent(in), optional :: dims
    real(wp), allocatable, target :: buf(:, :, :)
    buf = data
    call write_dataset(self, name, shape(data, kind=hsize_t), H5T_NATIVE_DOUBLE, &
                       H5T_NATIVE_DOUBLE, c_loc(buf), units, description, dims)
  end subroutine writer_write_3d

  !> 64-bit integer dataset (codes, counts, flags), with its units and description.
  subroutine writer_write_1d_int(self, name, data, units, description, dims)
    !> The writer.
    class(h5_writer_type), intent(inout) :: self
    !> Path of the dataset; its units; what it holds.
    character(len=*), intent(in) :: name, units, description
    !> The values.
    integer(i8), intent(in) :: data(:)
    !> The dimensions' names, comma-separated, slowest first (absent: unnamed).
    character(len=*), intent(in), optional :: dims
    integer(i8), allocatable, target :: buf(:)
    buf = data
    call write_dataset(self, name, shape(data, kind=hsize_t), H5T_STD_I64LE, &
                       h5kind_to_type(i8, H5_INTEGER_KIND), c_loc(buf), units, &
                       description, dims)
  end subroutine writer_write_1d_int

  !> Variable-length UTF-8 string dataset, one string per entry with its trailing blanks
  !> removed. Variable-length, not fixed-length: netCDF-C 4.9 (ncdump, nccopy) crashes on
  !> a fixed-length string array and shows its entries after the first as NIL, while it
  !> reads variable-length UTF-8 as its own `string` type (as h5py, h5netcdf and xarray do).
  subroutine writer_write_strings(self, name, data, units, description, dims)
    !> The writer.
    class(h5_writer_type), intent(inout) :: self
    !> Path of the dataset; the strings; their units; what they hold.
    character(len=*), intent(in) :: name, data(:), units, description
    !> The dimension's name (absent: unnamed).
    character(len=*), intent(in), optional :: dims
    ! each entry NUL-terminated (a C string), pointed at by one element of ptr
    character(len=len(data) + 1), allocatable, target :: buf(:)
    type(c_ptr), allocatable, target :: ptr(:)
    integer(hid_t) :: atype, space, dset
    integer(hsize_t) :: extent(1)
    integer :: hdferr, i
    allocate (buf(size(data)), ptr(size(data)))
    do i = 1, size(data)
      buf(i) = trim(data(i))//c_null_char
      ptr(i) = c_loc(buf(i)(1:1))
    end do
    extent = size(data, kind=hsize_t)
    call vlen_text_type(atype, hdferr)
    call h5screate_simple_f(1, extent, space, hdferr)
    call h5dcreate_f(self%file, name, atype, space, dset, hdferr)
    call note_failure(self%failed_what, hdferr, name)
    if (hdferr == 0) then
      if (size(data) > 0) call h5dwrite_f(dset, atype, c_loc(ptr), hdferr)
      call note_failure(self%failed_what, hdferr, name)
      call describe(dset, units, description, self%failed_what)
      if (present(dims)) call self%scales%attach(self%file, name, dset, dims, extent, &
                                             self%failed_what)
      call h5dclose_f(dset, hdferr)
    end if
    call h5sclose_f(space, hdferr)
    call h5tclose_f(atype, hdferr)
  end subroutine writer_write_strings

  !> The variable-length UTF-8 string type (C strings: NUL-terminated), in file and memory.
  subroutine vlen_text_type(atype, hdferr)
    integer(hid_t), intent(out) :: atype
    integer, intent(out) :: hdferr
    call h5tcopy_f(H5T_STRING, atype, hdferr)
    if (hdferr == 0) call h5tset_cset_f(atype, H5T_CSET_UTF8_F, hdferr)
  end subroutine vlen_text_type

  !> One dataset of any rank from a contiguous buffer of memory type `mtype`, stored as
  !> `ftype`, with its units and description.
  subroutine write_dataset(self, name, extent, ftype, mtype, buf, units, description, dims)
    type(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: name, units, description
    integer(hsize_t), intent(in) :: extent(:)
    integer(hid_t), intent(in) :: ftype, mtype
    type(c_ptr), intent(in) :: buf
    character(len=*), intent(in), optional :: dims
    integer(hid_t) :: space, dset
    integer :: hdferr
    call h5screate_simple_f(size(extent), extent, space, hdferr)
    call h5dcreate_f(self%file, name, ftype, space, dset, hdferr)
    call note_failure(self%failed_what, hdferr, name)
    if (hdferr /= 0) return
    call h5dwrite_f(dset, mtype, buf, hdferr)
    call note_failure(self%failed_what, hdferr, name)
    call describe(dset, units, description, self%failed_what)
    if (present(dims)) call self%scales%attach(self%file, name, dset, dims, extent, &
                                             self%failed_what)
    call h5dclose_f(dset, hdferr)
    call h5sclose_f(space, hdferr)
  end subroutine write_dataset

  !> String attribute on the object `obj` ("/" for the root).
  subroutine writer_attr_str(self, obj, name, value)
    !> The writer.
    class(h5_writer_type), intent(inout) :: self
    !> The object's path ("/" for the root); the attribute's name and value.
    character(len=*), intent(in) :: obj, name, value
    integer(hid_t) :: oid
    integer :: hdferr
    call h5oopen_f(self%file, obj, oid, hdferr)
    call note_failure(self%failed_what, hdferr, obj)
    if (hdferr /= 0) return
    call put_str(oid, name, value, self%failed_what)
    call h5oclose_f(oid, hdferr)
  end subroutine writer_attr_str

  !> 64-bit integer attribute on the object `obj` ("/" for the root).
  subroutine writer_attr_int(self, obj, name, value)
    !> The writer.
    class(h5_writer_type), intent(inout) :: self
    !> The object's path ("/" for the root); the attribute's name.
    character(len=*), intent(in) :: obj, name
    !> The attribute's value.
    integer(i8), intent(in), target :: value
    call write_attr(self, obj, name, H5T_STD_I64LE, h5kind_to_type(i8, H5_INTEGER_KIND), &
                    c_loc(value))
  end subroutine writer_attr_int

  !> Double-precision attribute on the object `obj` ("/" for the root).
  subroutine writer_attr_real(self, obj, name, value)
    !> The writer.
    class(h5_writer_type), intent(inout) :: self
    !> The object's path ("/" for the root); the attribute's name.
    character(len=*), intent(in) :: obj, name
    !> The attribute's value.
    real(wp), intent(in), target :: value
    call write_attr(self, obj, name, H5T_NATIVE_DOUBLE, H5T_NATIVE_DOUBLE, c_loc(value))
  end subroutine writer_attr_real

  !> One scalar attribute from memory of type `mtype`, stored as `ftype`.
  subroutine write_attr(self, obj, name, ftype, mtype, buf)
    type(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: obj, name
    integer(hid_t), intent(in) :: ftype, mtype
    type(c_ptr), intent(in) :: buf
    integer(hid_t) :: oid, space, attr
    integer :: hdferr
    call h5oopen_f(self%file, obj, oid, hdferr)
    call h5screate_f(H5S_SCALAR_F, space, hdferr)
    call h5acreate_f(oid, name, ftype, space, attr, hdferr)
    call note_failure(self%failed_what, hdferr, obj//"@"//name)
    if (hdferr == 0) then
      call h5awrite_f(attr, mtype, buf, hdferr)
      call note_failure(self%failed_what, hdferr, obj//"@"//name)
      call h5aclose_f(attr, hdferr)
    end if
    call h5sclose_f(space, hdferr)
    call h5oclose_f(oid, hdferr)
  end subroutine write_attr

  !> Close the file and rename it into place; reports any write failure, after which the
  !> temporary file is removed and any earlier file under the name is left as it was.
  subroutine writer_close(self, error)
    !> The writer, closed.
    class(h5_writer_type), intent(inout) :: self
    !> Set when a write failed or the rename failed.
    type(error_type), allocatable, intent(out) :: error
    integer :: hdferr
    if (.not. self%is_open) return
    if (.not. allocated(self%failed_what)) then
      call self%scales%write_reference_lists(self%file, self%failed_what)
    end if
    call h5fclose_f(self%file, hdferr)
    self%is_open = .false.
    if (allocated(self%failed_what) .or. hdferr /= 0) then
      call delete_file(self%tmp_path)
      if (allocated(self%failed_what)) then
        call fatal_error(error, "writing '"//self%final_path//"' failed at "// &
                         self%failed_what//" (disk full or not writable?); any earlier '"// &
                         self%final_path//"' is left as it was")
      else
        call fatal_error(error, "closing '"//self%final_path//"' failed (disk full or "// &
                         "not writable?); any earlier '"//self%final_path// &
                         "' is left as it was")
      end if
    else if (c_rename(self%tmp_path//c_null_char, self%final_path//c_null_char) /= 0) then
      call delete_file(self%tmp_path)
      call fatal_error(error, "cannot rename '"//self%tmp_path//"' to '"// &
                       self%final_path//"'")
    end if
    if (self%owns_lock) call release_lock(self%path)
    self%owns_lock = .false.
  end subroutine writer_close

  !> Close and delete the temporary file (nothing is left behind).
  subroutine writer_discard(self)
    !> The writer, closed and its temporary file removed.
    class(h5_writer_type), intent(inout) :: self
    integer :: hdferr
    if (.not. self%is_open) return
    call h5fclose_f(self%file, hdferr)
    self%is_open = .false.
    call delete_file(self%tmp_path)
    if (self%owns_lock) call release_lock(self%path)
    self%owns_lock = .false.
  end subroutine writer_discard

  !> Remove `path` if it exists (never opened: a FIFO put under that name cannot block).
  subroutine delete_file(path)
    character(len=*), intent(in) :: path
    if (len(path) > 0) call remove_file(path)
  end subroutine delete_file

end module davit_io_hdf5_writer
