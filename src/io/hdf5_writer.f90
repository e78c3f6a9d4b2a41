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
!> attached to an HDF5 dimension scale (H5DS), which netCDF-4, h5netcdf and xarray read as
!> its named dimension. A 1-D dataset whose dims is its own name (/time, /rao/omega) is the
!> coordinate scale of that dimension; any other name is looked up in the dataset's group
!> and then its parents (netCDF's scoping), and where none exists a dimension-only scale
!> `group/name` is created as netCDF-4 does (no data, NAME "This is a netCDF dimension but
!> not a netCDF variable."), so datasets of a group that share a name share one dimension.
!> A dimension has one length: a second dataset disagreeing with it fails the write.
module davit_io_hdf5_writer
  use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char, c_loc, c_ptr, c_size_t, &
                                         c_sizeof, c_int64_t
  use hdf5
  use h5ds, only: h5dsset_scale_f
  use davit_kinds, only: wp, i8
  use davit_error, only: error_type, fatal_error
  use davit_io_hdf5_reader, only: h5_start
  use davit_io_namelist, only: int_to_str
  use davit_io_files, only: create_empty, remove_file
  use davit_io_output_lock, only: check_output_path, acquire_lock, release_lock, note_tmp, &
                                  tmp_suffix, create_cause
  implicit none
  private
  public :: h5_writer_type, check_output_path, acquire_lock, release_lock

  !> A dimension scale written so far: dataset `group/name` (group "" is the root).
  type :: dim_scale_type
    character(len=:), allocatable :: group, name
    integer(hsize_t) :: length = 0
  end type dim_scale_type

  !> One axis of a dataset on a scale: an entry of the scale's REFERENCE_LIST.
  type :: attachment_type
    character(len=:), allocatable :: dataset
    !> Index in the writer's scales; the axis in HDF5's (C) order, from 0.
    integer :: scale = 0, axis = 0
  end type attachment_type

  !> HDF5's hvl_t (one DIMENSION_LIST element) and H5DS's ds_list_t (one REFERENCE_LIST
  !> element), as the HDF5 C library lays them out.
  type, bind(c) :: vlen_type
    integer(c_size_t) :: len = 0
    type(c_ptr) :: p
  end type vlen_type
  type, bind(c) :: reference_type
    integer(c_int64_t) :: dataset = 0  ! hobj_ref_t: the object's address
    integer(c_int) :: dimension = 0
  end type reference_type

  !> netCDF-4's NAME of a dimension-only scale, which its readers hide as a variable.
  !> The longest suffix of a temporary file: ".tmp.", a process id (up to 7 digits on
  !> Linux, pid_max 4194304), "." and a counter of up to 6 digits.
  character(len=*), parameter :: not_a_variable = &
    "This is a netCDF dimension but not a netCDF variable."

  type :: h5_writer_type
    integer(hid_t) :: file = -1
    character(len=:), allocatable :: path, tmp_path
    !> Where close() puts the file (path, unless retarget() names another).
    character(len=:), allocatable :: final_path
    logical :: is_open = .false.
    !> This writer took path.lock (and releases it); false when the caller holds it.
    logical :: owns_lock = .false.
    !> First HDF5 failure while writing; reported by close().
    logical :: failed = .false.
    character(len=:), allocatable :: failed_what
    !> The dimension scales of this file, in the order written.
    type(dim_scale_type), allocatable :: scales(:)
    !> Every axis attached so far; the scales' REFERENCE_LISTs are written at close.
    type(attachment_type), allocatable :: attached(:)
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
    class(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: path
    type(error_type), allocatable, intent(out) :: error
    integer :: hdferr, perr, status
    integer(hid_t) :: fapl
    self%path = path
    self%final_path = path
    self%failed = .false.
    if (allocated(self%scales)) deallocate (self%scales)
    if (allocated(self%attached)) deallocate (self%attached)
    allocate (self%scales(0), self%attached(0))
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
    class(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: path
    self%final_path = path
  end subroutine writer_retarget

  subroutine writer_group(self, name)
    class(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: name
    integer(hid_t) :: gid
    integer :: hdferr
    call h5gcreate_f(self%file, name, gid, hdferr)
    call check(self, hdferr, "group "//name)
    if (hdferr == 0) call h5gclose_f(gid, hdferr)
  end subroutine writer_group

  subroutine writer_write_1d(self, name, data, units, description, dims)
    class(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: name, units, description
    real(wp), intent(in) :: data(:)
    !> Dimension names, one per axis of `data` (see the module comment).
    character(len=*), intent(in), optional :: dims
    real(wp), allocatable, target :: buf(:)
    buf = data
    call write_real(self, name, shape(data, kind=hsize_t), c_loc(buf), units, description, &
                    dims)
  end subroutine writer_write_1d

  subroutine writer_write_2d(self, name, data, units, description, dims)
    class(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: name, units, description
    real(wp), intent(in) :: data(:, :)
    !> Dimension names, one per axis of `data` (see the module comment).
    character(len=*), intent(in), optional :: dims
    real(wp), allocatable, target :: buf(:, :)
    buf = data
    call write_real(self, name, shape(data, kind=hsize_t), c_loc(buf), units, description, &
                    dims)
  end subroutine writer_write_2d

  subroutine writer_write_3d(self, name, data, units, description, dims)
    class(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: name, units, description
    real(wp), intent(in) :: data(:, :, :)
    !> Dimension names, one per axis of `data` (see the module comment).
    character(len=*), intent(in), optional :: dims
    real(wp), allocatable, target :: buf(:, :, :)
    buf = data
    call write_real(self, name, shape(data, kind=hsize_t), c_loc(buf), units, description, &
                    dims)
  end subroutine writer_write_3d

  !> 64-bit integer dataset (codes, counts, flags), with its units and description.
  subroutine writer_write_1d_int(self, name, data, units, description, dims)
    class(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: name, units, description
    integer(i8), intent(in) :: data(:)
    character(len=*), intent(in), optional :: dims
    integer(i8), allocatable, target :: buf(:)
    integer(hid_t) :: space, dset
    integer(hsize_t) :: extent(1)
    integer :: hdferr
    buf = data
    extent = size(data, kind=hsize_t)
    call h5screate_simple_f(1, extent, space, hdferr)
    call h5dcreate_f(self%file, name, H5T_STD_I64LE, space, dset, hdferr)
    call check(self, hdferr, name)
    if (hdferr /= 0) return
    call h5dwrite_f(dset, h5kind_to_type(i8, H5_INTEGER_KIND), c_loc(buf), hdferr)
    call check(self, hdferr, name)
    call describe(self, dset, units, description)
    if (present(dims)) call attach_dims(self, name, dset, dims, extent)
    call h5dclose_f(dset, hdferr)
    call h5sclose_f(space, hdferr)
  end subroutine writer_write_1d_int

  !> Variable-length UTF-8 string dataset, one string per entry with its trailing blanks
  !> removed. Variable-length, not fixed-length: netCDF-C 4.9 (ncdump, nccopy) crashes on
  !> a fixed-length string array and shows its entries after the first as NIL, while it
  !> reads variable-length UTF-8 as its own `string` type (as h5py, h5netcdf and xarray do).
  subroutine writer_write_strings(self, name, data, units, description, dims)
    class(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: name, data(:), units, description
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
    call check(self, hdferr, name)
    if (hdferr == 0) then
      if (size(data) > 0) call h5dwrite_f(dset, atype, c_loc(ptr), hdferr)
      call check(self, hdferr, name)
      call describe(self, dset, units, description)
      if (present(dims)) call attach_dims(self, name, dset, dims, extent)
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

  !> One double-precision dataset of any rank from a contiguous buffer, with its
  !> units and description.
  subroutine write_real(self, name, extent, buf, units, description, dims)
    type(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: name, units, description
    integer(hsize_t), intent(in) :: extent(:)
    type(c_ptr), intent(in) :: buf
    character(len=*), intent(in), optional :: dims
    integer(hid_t) :: space, dset
    integer :: hdferr
    call h5screate_simple_f(size(extent), extent, space, hdferr)
    call h5dcreate_f(self%file, name, H5T_NATIVE_DOUBLE, space, dset, hdferr)
    call check(self, hdferr, name)
    if (hdferr /= 0) return
    call h5dwrite_f(dset, H5T_NATIVE_DOUBLE, buf, hdferr)
    call check(self, hdferr, name)
    call describe(self, dset, units, description)
    if (present(dims)) call attach_dims(self, name, dset, dims, extent)
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
    integer(hsize_t), parameter :: dims(1) = [1]
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

  !> Close the file and rename it into place; reports any write failure, after which the
  !> temporary file is removed and any earlier file under the name is left as it was.
  subroutine writer_close(self, error)
    class(h5_writer_type), intent(inout) :: self
    type(error_type), allocatable, intent(out) :: error
    integer :: hdferr
    if (.not. self%is_open) return
    if (.not. self%failed) call write_reference_lists(self)
    call h5fclose_f(self%file, hdferr)
    self%is_open = .false.
    if (self%failed .or. hdferr /= 0) then
      call delete_file(self%tmp_path)
      if (self%failed) then
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
    class(h5_writer_type), intent(inout) :: self
    integer :: hdferr
    if (.not. self%is_open) return
    call h5fclose_f(self%file, hdferr)
    self%is_open = .false.
    call delete_file(self%tmp_path)
    if (self%owns_lock) call release_lock(self%path)
    self%owns_lock = .false.
  end subroutine writer_discard

  subroutine describe(self, dset, units, description)
    type(h5_writer_type), intent(inout) :: self
    integer(hid_t), intent(in) :: dset
    character(len=*), intent(in) :: units, description
    call put_str(self, dset, "units", units)
    call put_str(self, dset, "description", description)
    call put_str(self, dset, "long_name", description)
  end subroutine describe

  subroutine put_str(self, oid, name, value)
    type(h5_writer_type), intent(inout) :: self
    integer(hid_t), intent(in) :: oid
    character(len=*), intent(in) :: name, value
    integer(hid_t) :: atype, space, attr
    integer(hsize_t), parameter :: dims(1) = [1]
    integer :: hdferr
    call h5tcopy_f(H5T_FORTRAN_S1, atype, hdferr)
    call h5tset_size_f(atype, int(max(1, len(value)), size_t), hdferr)
    ! UTF-8: netCDF-4, h5netcdf and xarray decode it to text (h5py still gives bytes)
    call h5tset_cset_f(atype, H5T_CSET_UTF8_F, hdferr)
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

  !> Attach each axis of dataset `name` (open as `dset`, Fortran extents `extent`) to the
  !> scale of its dimension in `dims`; see the module comment. The HDF5 dimension-scale
  !> attributes are written as H5DS writes them, but each once: DIMENSION_LIST here and the
  !> scales' REFERENCE_LIST at close (H5DSattach_scale rewrites both at every call, which
  !> doubled the time to write a sweep summary).
  subroutine attach_dims(self, name, dset, dims, extent)
    type(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: name, dims
    integer(hid_t), intent(in) :: dset
    integer(hsize_t), intent(in) :: extent(:)
    character(len=:), allocatable :: group
    integer :: k, rank, hdferr, on(size(extent))
    group = parent_of(name)
    rank = size(extent)
    if (word_count(dims) /= rank) then
      call check(self, 1, name//" (dims '"//dims//"' for rank "//int_to_str(rank)//")")
      return
    end if
    if (rank == 1 .and. group_path(group, word(dims, 1)) == name) then
      call h5dsset_scale_f(dset, hdferr, word(dims, 1))
      call check(self, hdferr, "dimension scale "//name)
      call remember(self, group, word(dims, 1), extent(1))
      return
    end if
    do k = 1, rank
      on(k) = scale_index(self, group, word(dims, k), extent(k), name)
      if (on(k) == 0) return
      ! HDF5 numbers the axes in C order from 0, reversed from the Fortran array's (a
      ! Fortran (component, time) array is (time, component) there)
      self%attached = [self%attached, attachment_type(name, on(k), rank - k)]
    end do
    call write_dimension_list(self, name, dset, on(rank:1:-1))
  end subroutine attach_dims

  !> DIMENSION_LIST of `dset`: for each axis (C order) a reference to its scale.
  subroutine write_dimension_list(self, name, dset, on)
    type(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: name
    integer(hid_t), intent(in) :: dset
    integer, intent(in) :: on(:)
    integer(c_int64_t), target :: refs(size(on))
    type(vlen_type), target :: list(size(on))
    integer(hid_t) :: vtype, space, attr
    integer :: c, hdferr, status
    status = 0
    do c = 1, size(on)
      refs(c) = object_ref(self, scale_path(self, on(c)), hdferr)
      status = max(status, abs(hdferr))
      list(c) = vlen_type(1, c_loc(refs(c)))
    end do
    call h5tvlen_create_f(H5T_STD_REF_OBJ, vtype, hdferr)
    call h5screate_simple_f(1, [size(on, kind=hsize_t)], space, hdferr)
    call h5acreate_f(dset, "DIMENSION_LIST", vtype, space, attr, hdferr)
    status = max(status, abs(hdferr))
    if (hdferr == 0) then
      call h5awrite_f(attr, vtype, c_loc(list), hdferr)
      status = max(status, abs(hdferr))
      call h5aclose_f(attr, hdferr)
    end if
    call h5sclose_f(space, hdferr)
    call h5tclose_f(vtype, hdferr)
    call check(self, status, "dimensions of "//name)
  end subroutine write_dimension_list

  !> REFERENCE_LIST of every scale: (dataset, axis) of each axis attached to it.
  subroutine write_reference_lists(self)
    type(h5_writer_type), intent(inout) :: self
    type(reference_type), allocatable, target :: list(:)
    integer(hid_t) :: ctype, space, attr, scale
    integer :: k, j, n, hdferr, status
    do k = 1, size(self%scales)
      list = [(reference_type(0, self%attached(j)%axis), j = 1, size(self%attached))]
      list = pack(list, self%attached(:)%scale == k)
      if (size(list) == 0) cycle
      status = 0
      n = 0
      do j = 1, size(self%attached)
        if (self%attached(j)%scale /= k) cycle
        n = n + 1
        list(n)%dataset = object_ref(self, self%attached(j)%dataset, hdferr)
        status = max(status, abs(hdferr))
      end do
      call h5tcreate_f(H5T_COMPOUND_F, c_sizeof(list(1)), ctype, hdferr)
      call h5tinsert_f(ctype, "dataset", 0_size_t, H5T_STD_REF_OBJ, hdferr)
      call h5tinsert_f(ctype, "dimension", c_sizeof(list(1)%dataset), H5T_NATIVE_INTEGER, &
                       hdferr)
      call h5screate_simple_f(1, [size(list, kind=hsize_t)], space, hdferr)
      call h5dopen_f(self%file, scale_path(self, k), scale, hdferr)
      status = max(status, abs(hdferr))
      if (hdferr == 0) then
        call h5acreate_f(scale, "REFERENCE_LIST", ctype, space, attr, hdferr)
        status = max(status, abs(hdferr))
        if (hdferr == 0) call h5awrite_f(attr, ctype, c_loc(list), hdferr)
        status = max(status, abs(hdferr))
        call h5aclose_f(attr, hdferr)
        call h5dclose_f(scale, hdferr)
      end if
      call h5sclose_f(space, hdferr)
      call h5tclose_f(ctype, hdferr)
      call check(self, status, "dimension "//scale_path(self, k))
    end do
  end subroutine write_reference_lists

  !> An HDF5 object reference (hobj_ref_t) to `path`.
  integer(c_int64_t) function object_ref(self, path, hdferr) result(ref)
    type(h5_writer_type), intent(in) :: self
    character(len=*), intent(in) :: path
    integer, intent(out) :: hdferr
    type(hobj_ref_t_f) :: r
    call h5rcreate_f(self%file, path, r, hdferr)
    ref = int(r%ref, c_int64_t)
  end function object_ref

  pure function scale_path(self, k) result(path)
    type(h5_writer_type), intent(in) :: self
    integer, intent(in) :: k
    character(len=:), allocatable :: path
    path = group_path(self%scales(k)%group, self%scales(k)%name)
  end function scale_path

  !> Index in self%scales of dimension `dim` seen from `group` (its own, else the nearest
  !> parent's), creating a dimension-only one in `group` if there is none; 0 on failure
  !> (a length that disagrees with the dimension's fails the write).
  integer function scale_index(self, group, dim, length, user) result(k)
    type(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: group, dim, user
    integer(hsize_t), intent(in) :: length
    k = find_scale(self, group, dim)
    if (k == 0) then
      call create_dimension(self, group, dim, length)
      if (.not. self%failed) k = size(self%scales)
    else if (self%scales(k)%length /= length) then
      call check(self, 1, user//" (length "//int_to_str(int(length))//" along dimension "// &
                 dim//" of length "//int_to_str(int(self%scales(k)%length))//")")
      k = 0
    end if
  end function scale_index

  !> Index in self%scales of dimension `dim` as seen from `group`; 0 if none.
  integer function find_scale(self, group, dim) result(found)
    type(h5_writer_type), intent(in) :: self
    character(len=*), intent(in) :: group, dim
    character(len=:), allocatable :: g
    integer :: k
    g = group
    do
      found = 0
      do k = 1, size(self%scales)
        if (self%scales(k)%name == dim .and. self%scales(k)%group == g) found = k
      end do
      if (found > 0 .or. len(g) == 0) return
      g = parent_of(g)
    end do
  end function find_scale

  !> A netCDF-4 dimension-only scale `group/dim`: float, never written (no storage), with
  !> units and description like every dataset here.
  subroutine create_dimension(self, group, dim, length)
    type(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: group, dim
    integer(hsize_t), intent(in) :: length
    integer(hid_t) :: space, scale
    integer :: hdferr
    character(len=10) :: digits
    call h5screate_simple_f(1, [length], space, hdferr)
    call h5dcreate_f(self%file, group_path(group, dim), H5T_NATIVE_REAL, space, scale, hdferr)
    call h5sclose_f(space, hdferr)
    call check(self, hdferr, "dimension "//group_path(group, dim))
    if (hdferr /= 0) return
    write (digits, "(i10)") length
    call h5dsset_scale_f(scale, hdferr, not_a_variable//digits)
    call check(self, hdferr, "dimension "//group_path(group, dim))
    call describe(self, scale, "-", "Dimension "//dim//" (its length only; no data)")
    call h5dclose_f(scale, hdferr)
    call remember(self, group, dim, length)
  end subroutine create_dimension

  subroutine remember(self, group, dim, length)
    type(h5_writer_type), intent(inout) :: self
    character(len=*), intent(in) :: group, dim
    integer(hsize_t), intent(in) :: length
    type(dim_scale_type) :: s
    s%group = group
    s%name = dim
    s%length = length
    self%scales = [self%scales, s]
  end subroutine remember

  !> The group holding object `name` ("" for the root; a leading "/" is dropped).
  pure function parent_of(name) result(group)
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: group
    integer :: i
    i = index(name, "/", back=.true.)
    group = name(1:max(i - 1, 0))
    if (len(group) > 0) then
      if (group(1:1) == "/") group = group(2:)
    end if
  end function parent_of

  pure function group_path(group, name) result(path)
    character(len=*), intent(in) :: group, name
    character(len=:), allocatable :: path
    if (len(group) == 0) then
      path = name
    else
      path = group//"/"//name
    end if
  end function group_path

  !> Word k of the blank-separated `text` ("" past its last word).
  pure function word(text, k) result(w)
    character(len=*), intent(in) :: text
    integer, intent(in) :: k
    character(len=:), allocatable :: w
    integer :: i, n, first
    w = ""
    n = 0
    first = 0
    do i = 1, len(text)
      if (text(i:i) /= " " .and. first == 0) first = i
      if (first > 0 .and. (text(i:i) == " " .or. i == len(text))) then
        n = n + 1
        if (n == k) then
          w = trim(text(first:i))
          return
        end if
        first = 0
      end if
    end do
  end function word

  pure integer function word_count(text) result(n)
    character(len=*), intent(in) :: text
    n = 0
    do while (len(word(text, n + 1)) > 0)
      n = n + 1
    end do
  end function word_count

  subroutine check(self, hdferr, what)
    type(h5_writer_type), intent(inout) :: self
    integer, intent(in) :: hdferr
    character(len=*), intent(in) :: what
    if (hdferr /= 0 .and. .not. self%failed) then
      self%failed = .true.
      self%failed_what = what
    end if
  end subroutine check

  !> Remove `path` if it exists (never opened: a FIFO put under that name cannot block).
  subroutine delete_file(path)
    character(len=*), intent(in) :: path
    if (len(path) > 0) call remove_file(path)
  end subroutine delete_file

end module davit_io_hdf5_writer
