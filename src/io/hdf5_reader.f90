!> Reading back what davit_io_hdf5_writer wrote: 1-D real, integer and string (variable-
!> length, as davit writes them, or fixed-length, as older files and h5py's bytes do)
!> datasets and root string and integer attributes (a sweep resumes from its summary); and
!> numeric datasets of any rank as reals (a BEM database, netCDF4 = HDF5).
!> Every failure names the file and the dataset or attribute. Not thread-safe (Debian's
!> HDF5 is built without locking): call it from one thread at a time.
module davit_io_hdf5_reader
  use, intrinsic :: iso_c_binding, only: c_loc, c_ptr, c_int, c_null_ptr
  use hdf5
  use davit_kinds, only: wp, i8
  use davit_error, only: error_type, fatal_error
  use davit_io_files, only: file_kind, kind_name, kind_none, kind_regular
  use davit_io_text, only: int_text
  use davit_io_hdf5_text, only: extents_text, dataset_class, c_length, c_text, text_type
  implicit none
  private
  public :: h5_reader_type, h5_start

  interface
    !> Keeps HDF5 from registering its atexit cleanup: after a failed close (a full disk)
    !> that cleanup would flush a broken file and crash at exit. Every file davit opens is
    !> closed explicitly, so there is nothing left for it to do.
    function c_h5dont_atexit() bind(C, name="H5dont_atexit") result(status)
      import :: c_int
      integer(c_int) :: status
    end function c_h5dont_atexit
  end interface

  !> The most values davit reads from one dataset or text: 2^28 (2 GiB as reals, far
  !> beyond any database or summary davit writes); a file declaring more is refused
  !> before anything that size is allocated.
  integer(i8), parameter :: max_values = 2_i8**28

  type :: h5_reader_type
    !> HDF5 identifier of the open file (-1: none).
    integer(hid_t) :: file = -1
    !> Path of the file, for messages.
    character(len=:), allocatable :: path
    !> Whether a file is open.
    logical :: is_open = .false.
  contains
    procedure :: open => reader_open
    procedure :: close => reader_close
    procedure :: read_1d => reader_read_1d
    procedure :: read_1d_int => reader_read_1d_int
    procedure :: read_array => reader_read_array
    procedure :: read_strings => reader_read_strings
    procedure :: attr_str => reader_attr_str
    procedure :: attr_int => reader_attr_int
    procedure :: has_attr => reader_has_attr
    procedure :: has_dataset => reader_has_dataset
  end type h5_reader_type

contains

  !> Start HDF5 (once per process is enough; later calls are harmless) without its atexit
  !> cleanup and without its automatic error printing.
  subroutine h5_start()
    integer :: hdferr
    integer(c_int) :: status
    logical, save :: started = .false.
    if (.not. started) then
      status = c_h5dont_atexit()
      started = .true.
    end if
    call h5open_f(hdferr)
    call h5eset_auto_f(0, hdferr)
  end subroutine h5_start

  !> Open `path` for reading. Only a regular file: HDF5 seeks, and opening a FIFO would
  !> wait for a writer forever.
  subroutine reader_open(self, path, error)
    !> The reader.
    class(h5_reader_type), intent(inout) :: self
    !> Path of the file.
    character(len=*), intent(in) :: path
    !> Set when the path is not a readable HDF5 file.
    type(error_type), allocatable, intent(out) :: error
    integer :: hdferr, kind
    self%path = path
    kind = file_kind(path)
    if (kind /= kind_regular .and. kind /= kind_none) then
      call fatal_error(error, "cannot open '"//path//"' as an HDF5 file: it is "// &
                       kind_name(kind)//", not a regular file")
      return
    end if
    call h5_start()
    call h5fopen_f(path, H5F_ACC_RDONLY_F, self%file, hdferr)
    if (hdferr /= 0) then
      call fatal_error(error, "cannot open '"//path//"' as an HDF5 file")
      return
    end if
    self%is_open = .true.
  end subroutine reader_open

  subroutine reader_close(self)
    !> The reader, closed.
    class(h5_reader_type), intent(inout) :: self
    integer :: hdferr
    if (.not. self%is_open) return
    call h5fclose_f(self%file, hdferr)
    self%is_open = .false.
  end subroutine reader_close

  !> Open dataset `name` (rank 0-7) and return its extents in Fortran order, checked
  !> before anything of that size is made: every extent read in 64 bits and the values in
  !> all at most max_values (a crafted file may declare any extent, with no data behind).
  subroutine open_dataset(self, name, dset, dims, error)
    type(h5_reader_type), intent(in) :: self
    character(len=*), intent(in) :: name
    integer(hid_t), intent(out) :: dset
    integer, allocatable, intent(out) :: dims(:)
    type(error_type), allocatable, intent(out) :: error
    integer(hid_t) :: space
    integer(hsize_t) :: d(7), maxd(7)
    integer :: hdferr, rank, class
    allocate (dims(0))
    call h5dopen_f(self%file, name, dset, hdferr)
    if (hdferr /= 0) then
      call fatal_error(error, "'"//self%path//"': no dataset /"//name)
      return
    end if
    call h5dget_space_f(dset, space, hdferr)
    rank = -1
    class = -1
    if (hdferr == 0) then
      call h5sget_simple_extent_type_f(space, class, hdferr)
      call h5sget_simple_extent_ndims_f(space, rank, hdferr)
      d = 1
      if (rank > 0 .and. rank <= 7) call h5sget_simple_extent_dims_f(space, d(1:rank), &
                                                                     maxd(1:rank), hdferr)
      if (hdferr < 0) rank = -1
      call h5sclose_f(space, hdferr)
    end if
    if (class == H5S_NULL_F) then
      call fatal_error(error, "'"//self%path//"': dataset /"//name//" holds no data "// &
                       "(a null dataspace)")
    else if (rank < 0 .or. rank > 7) then
      call fatal_error(error, "'"//self%path//"': dataset /"//name//" has an unreadable rank")
    else
      ! the message lists the extents as h5py shows them (C order)
      call check_extents(self, "dataset /"//name, d(rank:1:-1), error)
    end if
    if (allocated(error)) then
      call h5dclose_f(dset, hdferr)
      return
    end if
    dims = int(d(1:rank))
  end subroutine open_dataset

  !> The extents `d` (any order) of `what` fit a default integer each, and max_values
  !> in all.
  subroutine check_extents(self, what, d, error)
    type(h5_reader_type), intent(in) :: self
    character(len=*), intent(in) :: what
    integer(hsize_t), intent(in) :: d(:)
    type(error_type), allocatable, intent(out) :: error
    integer(i8) :: total
    integer :: k
    total = 1
    do k = 1, size(d)
      if (d(k) > int(huge(1), hsize_t)) then
        call fatal_error(error, "'"//self%path//"': "//what//" declares an extent of "// &
                         int_text(int(d(k), i8))//", beyond 2^31 - 1")
        return
      end if
      if (d(k) > 0 .and. total > max_values/max(int(d(k), i8), 1_i8)) then
        call fatal_error(error, "'"//self%path//"': "//what//" declares more than "// &
                         int_text(max_values)//" values (extents "//extents_text(d)// &
                         "); davit reads no input that large")
        return
      end if
      total = total*int(d(k), i8)
    end do
  end subroutine check_extents

  !> `what` could not be allocated (the memory): a message instead of a crash.
  subroutine no_memory(self, what, n, error)
    type(h5_reader_type), intent(in) :: self
    character(len=*), intent(in) :: what
    integer(i8), intent(in) :: n
    type(error_type), allocatable, intent(out) :: error
    call fatal_error(error, "'"//self%path//"': not enough memory for the "// &
                     int_text(n)//" values of "//what)
  end subroutine no_memory

  !> Open 1-D dataset `name` and return its length.
  subroutine open_1d(self, name, dset, n, error)
    type(h5_reader_type), intent(in) :: self
    character(len=*), intent(in) :: name
    integer(hid_t), intent(out) :: dset
    integer, intent(out) :: n
    type(error_type), allocatable, intent(out) :: error
    integer, allocatable :: dims(:)
    integer :: hdferr
    n = 0
    call open_dataset(self, name, dset, dims, error)
    if (allocated(error)) return
    if (size(dims) /= 1) then
      call h5dclose_f(dset, hdferr)
      call fatal_error(error, "'"//self%path//"': dataset /"//name//" is not 1-D")
      return
    end if
    n = dims(1)
  end subroutine open_1d

  !> Refuse dataset `name` unless it holds numbers (integers_only: integers, as a real
  !> column would be silently truncated to integer codes); it is closed when refused.
  subroutine require_numbers(self, name, dset, error, integers_only)
    type(h5_reader_type), intent(in) :: self
    character(len=*), intent(in) :: name
    integer(hid_t), intent(in) :: dset
    type(error_type), allocatable, intent(out) :: error
    logical, intent(in), optional :: integers_only
    integer :: tclass, hdferr
    tclass = dataset_class(dset)
    if (present(integers_only)) then
      if (integers_only) then
        if (tclass == H5T_INTEGER_F) return
        call h5dclose_f(dset, hdferr)
        call fatal_error(error, "'"//self%path//"': dataset /"//name//" is not of integers")
        return
      end if
    end if
    if (tclass == H5T_INTEGER_F .or. tclass == H5T_FLOAT_F) return
    call h5dclose_f(dset, hdferr)
    call fatal_error(error, "'"//self%path//"': dataset /"//name//" does not hold numbers")
  end subroutine require_numbers

  !> Read the n values of the open dataset `dset` of `name`, converted by HDF5 to the
  !> memory type `mtype`, into `buf`, which the caller allocated with status alloc_status
  !> (not 0: out of memory, nothing read); dset is closed. A failure names the file, the
  !> dataset and what failed.
  subroutine read_values(self, name, dset, mtype, n, alloc_status, buf, error)
    type(h5_reader_type), intent(in) :: self
    character(len=*), intent(in) :: name
    integer(hid_t), intent(in) :: dset, mtype
    integer(i8), intent(in) :: n
    integer, intent(in) :: alloc_status
    type(c_ptr), intent(in) :: buf
    type(error_type), allocatable, intent(out) :: error
    type(c_ptr) :: target_buf  ! HDF5's interface takes the buffer's address inout
    integer :: hdferr, status
    if (alloc_status /= 0) then
      call h5dclose_f(dset, hdferr)
      call no_memory(self, "/"//name, n, error)
      return
    end if
    status = 0
    target_buf = buf
    if (n > 0) call h5dread_f(dset, mtype, target_buf, status)
    call h5dclose_f(dset, hdferr)
    if (status /= 0) call fatal_error(error, "'"//self%path//"': cannot read /"//name)
  end subroutine read_values

  subroutine reader_read_1d(self, name, x, error)
    !> The reader.
    class(h5_reader_type), intent(inout) :: self
    !> Path of the dataset.
    character(len=*), intent(in) :: name
    !> The values.
    real(wp), allocatable, target, intent(out) :: x(:)
    !> Set when the dataset is missing, not 1-D, not numeric or unreadable.
    type(error_type), allocatable, intent(out) :: error
    integer(hid_t) :: dset
    type(c_ptr) :: buf
    integer :: n, status
    call open_1d(self, name, dset, n, error)
    if (.not. allocated(error)) call require_numbers(self, name, dset, error)
    if (allocated(error)) return
    allocate (x(n), stat=status)
    buf = c_null_ptr
    if (status == 0) buf = c_loc(x)
    call read_values(self, name, dset, H5T_NATIVE_DOUBLE, int(n, i8), status, buf, error)
  end subroutine reader_read_1d

  subroutine reader_read_1d_int(self, name, x, error)
    !> The reader.
    class(h5_reader_type), intent(inout) :: self
    !> Path of the dataset.
    character(len=*), intent(in) :: name
    !> The values.
    integer(i8), allocatable, target, intent(out) :: x(:)
    !> Set when the dataset is missing, not 1-D, not integer or unreadable.
    type(error_type), allocatable, intent(out) :: error
    integer(hid_t) :: dset
    type(c_ptr) :: buf
    integer :: n, status
    call open_1d(self, name, dset, n, error)
    if (.not. allocated(error)) call require_numbers(self, name, dset, error, .true.)
    if (allocated(error)) return
    allocate (x(n), stat=status)
    buf = c_null_ptr
    if (status == 0) buf = c_loc(x)
    call read_values(self, name, dset, h5kind_to_type(i8, H5_INTEGER_KIND), int(n, i8), &
                     status, buf, error)
  end subroutine reader_read_1d_int

  !> Numeric dataset `name` of any rank (0-7) as reals (HDF5 converts integers), flattened
  !> in Fortran order, with its extents in Fortran order (the reverse of what h5py shows).
  subroutine reader_read_array(self, name, x, dims, error)
    !> The reader.
    class(h5_reader_type), intent(inout) :: self
    !> Path of the dataset.
    character(len=*), intent(in) :: name
    !> The values, flattened in Fortran order.
    real(wp), allocatable, target, intent(out) :: x(:)
    !> The extents in Fortran order.
    integer, allocatable, intent(out) :: dims(:)
    !> Set when the dataset is missing, not numeric, too large or unreadable.
    type(error_type), allocatable, intent(out) :: error
    integer(hid_t) :: dset
    type(c_ptr) :: buf
    integer :: status
    call open_dataset(self, name, dset, dims, error)
    if (.not. allocated(error)) call require_numbers(self, name, dset, error)
    if (allocated(error)) return
    allocate (x(product(dims)), stat=status)  ! product <= max_values (open_dataset)
    buf = c_null_ptr
    if (status == 0) buf = c_loc(x)
    call read_values(self, name, dset, H5T_NATIVE_DOUBLE, int(product(dims), i8), status, &
                     buf, error)
  end subroutine reader_read_array

  !> A string dataset, returned blank-padded to its longest entry (variable-length) or to
  !> its stored width (fixed-length).
  subroutine reader_read_strings(self, name, x, error)
    !> The reader.
    class(h5_reader_type), intent(inout) :: self
    !> Path of the dataset.
    character(len=*), intent(in) :: name
    !> The strings, blank-padded.
    character(len=:), allocatable, target, intent(out) :: x(:)
    !> Set when the dataset is missing, not text, too large or unreadable.
    type(error_type), allocatable, intent(out) :: error
    integer(hid_t) :: dset, ftype, mtype
    integer(size_t) :: width
    type(c_ptr) :: buf
    integer :: n, hdferr, status
    logical :: variable
    status = 0
    call open_1d(self, name, dset, n, error)
    if (allocated(error)) return
    call h5dget_type_f(dset, ftype, hdferr)
    variable = .false.
    if (hdferr == 0) call h5tis_variable_str_f(ftype, variable, hdferr)
    if (variable .and. hdferr == 0) then
      call read_vlen_strings(self, name, dset, ftype, n, x, error)
      call h5tclose_f(ftype, hdferr)
      call h5dclose_f(dset, hdferr)
      return
    end if
    call text_width(self, "dataset /"//name, ftype, int(n, i8), width, error)
    if (.not. allocated(error)) then
      allocate (character(len=int(width)) :: x(n), stat=status)
      if (status /= 0) call no_memory(self, "/"//name, int(n, i8)*int(width, i8), error)
    end if
    if (allocated(error)) then
      call h5tclose_f(ftype, hdferr)
      call h5dclose_f(dset, hdferr)
      return
    end if
    call text_type(ftype, width, mtype)
    call h5tclose_f(ftype, hdferr)
    buf = c_loc(x)
    if (n > 0) call h5dread_f(dset, mtype, buf, status)
    call h5tclose_f(mtype, hdferr)
    call h5dclose_f(dset, hdferr)
    if (status /= 0) call fatal_error(error, "'"//self%path//"': cannot read /"//name)
  end subroutine reader_read_strings

  !> The width of fixed-length text of type `ftype` (`n` strings of `what`): refused
  !> unless it is fixed-length text of at most max_values characters in all (the only
  !> text davit writes; a variable-length string's stored size is that of a pointer).
  subroutine text_width(self, what, ftype, n, width, error)
    type(h5_reader_type), intent(in) :: self
    character(len=*), intent(in) :: what
    integer(hid_t), intent(in) :: ftype
    integer(i8), intent(in) :: n
    integer(size_t), intent(out) :: width
    type(error_type), allocatable, intent(out) :: error
    integer :: tclass, hdferr
    logical :: variable
    width = 0
    call h5tget_class_f(ftype, tclass, hdferr)
    if (hdferr /= 0 .or. tclass /= H5T_STRING_F) then
      call fatal_error(error, "'"//self%path//"': cannot read "//what//": it is not text")
      return
    end if
    call h5tis_variable_str_f(ftype, variable, hdferr)
    if (hdferr /= 0 .or. variable) then
      call fatal_error(error, "'"//self%path//"': cannot read "//what//": it is "// &
                       "variable-length text where davit writes fixed-length text (attributes)")
      return
    end if
    call h5tget_size_f(ftype, width, hdferr)
    if (hdferr /= 0 .or. width < 1 .or. int(width, i8) > max_values/max(n, 1_i8)) then
      call fatal_error(error, "'"//self%path//"': cannot read "//what//": its text "// &
                       "width is unreadable or oversized")
    end if
  end subroutine text_width
  !> The `n` variable-length strings of dataset `dset` (type `ftype`), copied out of the
  !> C strings HDF5 allocates (freed here), blank-padded to the longest.
  subroutine read_vlen_strings(self, name, dset, ftype, n, x, error)
    type(h5_reader_type), intent(in) :: self
    character(len=*), intent(in) :: name
    integer(hid_t), intent(in) :: dset, ftype
    integer, intent(in) :: n
    character(len=:), allocatable, intent(out) :: x(:)
    type(error_type), allocatable, intent(out) :: error
    type(c_ptr), allocatable, target :: ptr(:)
    type(c_ptr) :: buf
    integer(hid_t) :: mtype, space
    integer :: i, width, cset, hdferr, status
    allocate (ptr(n))
    ptr = c_null_ptr
    ! the file's character set: HDF5 converts no text between ASCII and UTF-8
    call h5tcopy_f(H5T_STRING, mtype, hdferr)
    call h5tget_cset_f(ftype, cset, hdferr)
    if (hdferr == 0) call h5tset_cset_f(mtype, cset, hdferr)
    status = 0
    buf = c_loc(ptr)
    if (n > 0) call h5dread_f(dset, mtype, buf, status)
    if (status /= 0) then
      call h5tclose_f(mtype, hdferr)
      call fatal_error(error, "'"//self%path//"': cannot read /"//name)
      return
    end if
    width = 1
    do i = 1, n
      width = max(width, c_length(ptr(i)))
    end do
    allocate (character(len=width) :: x(n))
    do i = 1, n
      x(i) = c_text(ptr(i))
    end do
    call h5dget_space_f(dset, space, hdferr)
    if (n > 0) call h5dvlen_reclaim_f(mtype, space, H5P_DEFAULT_F, buf, hdferr)
    call h5sclose_f(space, hdferr)
    call h5tclose_f(mtype, hdferr)
  end subroutine read_vlen_strings

  !> Scalar string attribute `name` of the root group.
  subroutine reader_attr_str(self, name, value, error)
    !> The reader.
    class(h5_reader_type), intent(inout) :: self
    !> Name of the attribute.
    character(len=*), intent(in) :: name
    !> Its value.
    character(len=:), allocatable, intent(out) :: value
    !> Set when the attribute is missing, not a scalar string or unreadable.
    type(error_type), allocatable, intent(out) :: error
    integer(hid_t) :: attr, ftype, mtype
    integer(size_t) :: width
    integer(hsize_t) :: dims(1)
    integer :: hdferr
    value = ""
    call open_scalar_attr(self, name, attr, error)
    if (allocated(error)) return
    call h5aget_type_f(attr, ftype, hdferr)
    call text_width(self, "attribute "//name, ftype, 1_i8, width, error)
    if (allocated(error)) then
      call h5tclose_f(ftype, hdferr)
      call h5aclose_f(attr, hdferr)
      return
    end if
    deallocate (value)
    allocate (character(len=int(width)) :: value)
    call text_type(ftype, width, mtype)
    call h5tclose_f(ftype, hdferr)
    dims = 1
    call h5aread_f(attr, mtype, value, dims, hdferr)
    call h5tclose_f(mtype, hdferr)
    call h5aclose_f(attr, hdferr)
    if (hdferr /= 0) call fatal_error(error, "'"//self%path//"': cannot read attribute "//name)
  end subroutine reader_attr_str

  !> Scalar integer attribute `name` of the root group.
  subroutine reader_attr_int(self, name, value, error)
    !> The reader.
    class(h5_reader_type), intent(inout) :: self
    !> Name of the attribute.
    character(len=*), intent(in) :: name
    !> Its value.
    integer(i8), target, intent(out) :: value
    !> Set when the attribute is missing, not a scalar integer or unreadable.
    type(error_type), allocatable, intent(out) :: error
    integer(hid_t) :: attr, ftype
    type(c_ptr) :: buf
    integer :: hdferr, tclass
    value = 0
    call open_scalar_attr(self, name, attr, error)
    if (allocated(error)) return
    call h5aget_type_f(attr, ftype, hdferr)
    tclass = -1
    if (hdferr == 0) call h5tget_class_f(ftype, tclass, hdferr)
    call h5tclose_f(ftype, hdferr)
    if (tclass /= H5T_INTEGER_F) then
      call h5aclose_f(attr, hdferr)
      call fatal_error(error, "'"//self%path//"': attribute "//name//" is not an integer")
      return
    end if
    buf = c_loc(value)
    call h5aread_f(attr, h5kind_to_type(i8, H5_INTEGER_KIND), buf, hdferr)
    call h5aclose_f(attr, hdferr)
    if (hdferr /= 0) call fatal_error(error, "'"//self%path//"': cannot read attribute "//name)
  end subroutine reader_attr_int

  !> Open root attribute `name`, refused unless it holds exactly one value: HDF5 reads
  !> every element of an array attribute into the one value's memory.
  subroutine open_scalar_attr(self, name, attr, error)
    type(h5_reader_type), intent(in) :: self
    character(len=*), intent(in) :: name
    integer(hid_t), intent(out) :: attr
    type(error_type), allocatable, intent(out) :: error
    integer(hid_t) :: space
    integer(hsize_t) :: npoints
    integer :: hdferr, class
    call h5aopen_by_name_f(self%file, "/", name, attr, hdferr)
    if (hdferr /= 0) then
      call fatal_error(error, "'"//self%path//"': no root attribute "//name)
      return
    end if
    npoints = 0
    class = -1
    call h5aget_space_f(attr, space, hdferr)
    if (hdferr == 0) then
      call h5sget_simple_extent_type_f(space, class, hdferr)
      if (class /= H5S_NULL_F) call h5sget_simple_extent_npoints_f(space, npoints, hdferr)
      if (hdferr /= 0) npoints = 0
      call h5sclose_f(space, hdferr)
    end if
    if (npoints == 1 .and. class /= H5S_NULL_F) return
    call h5aclose_f(attr, hdferr)
    call fatal_error(error, "'"//self%path//"': attribute "//name//" holds "// &
                     int_text(int(npoints, i8))//" values, not one")
  end subroutine open_scalar_attr

  !> Whether the root group has attribute `name` (optional attributes: a sweep shard's).
  logical function reader_has_attr(self, name) result(exists)
    !> The reader.
    class(h5_reader_type), intent(in) :: self
    !> Name of the attribute.
    character(len=*), intent(in) :: name
    integer :: hdferr
    call h5aexists_by_name_f(self%file, "/", name, exists, hdferr)
    if (hdferr /= 0) exists = .false.
  end function reader_has_attr

  !> Whether the root group has a link `name` (optional datasets: a BEM database's drift).
  logical function reader_has_dataset(self, name) result(exists)
    !> The reader.
    class(h5_reader_type), intent(in) :: self
    !> Name of the link.
    character(len=*), intent(in) :: name
    integer :: hdferr
    call h5lexists_f(self%file, name, exists, hdferr)
    if (hdferr /= 0) exists = .false.
  end function reader_has_dataset

end module davit_io_hdf5_reader
