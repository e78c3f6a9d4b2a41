!> The netCDF-4 named dimensions of davit's HDF5 output (davit_io_hdf5_writer) and the
!> text attributes every dataset carries.
!>
!> A dataset written with `dims` (one name per axis, blank-separated, in the order of the
!> Fortran array's extents) has each axis attached to an HDF5 dimension scale (H5DS), which
!> netCDF-4, h5netcdf and xarray read as its named dimension. A 1-D dataset whose dims is
!> its own name (/time, /rao/omega) is the coordinate scale of that dimension; any other
!> name is looked up in the dataset's group and then its parents (netCDF's scoping), and
!> where none exists a dimension-only scale `group/name` is created as netCDF-4 does (no
!> data, NAME "This is a netCDF dimension but not a netCDF variable."), so datasets of a
!> group that share a name share one dimension. A dimension has one length: a second
!> dataset disagreeing with it fails the write.
!>
!> Failures are not errors here: each routine records the first one in the writer's
!> `failed` text (note_failure), which the writer reports when it closes the file.
module davit_io_hdf5_dims
  use, intrinsic :: iso_c_binding, only: c_int, c_loc, c_ptr, c_size_t, c_sizeof, c_int64_t
  use hdf5
  use h5ds, only: h5dsset_scale_f
  use davit_io_namelist, only: int_to_str
  implicit none
  private
  public :: dim_registry_type, describe, put_str, note_failure

  !> A dimension scale written so far: dataset `group/name` (group "" is the root).
  type :: dim_scale_type
    character(len=:), allocatable :: group, name
    integer(hsize_t) :: length = 0
  end type dim_scale_type

  !> One axis of a dataset on a scale: an entry of the scale's REFERENCE_LIST.
  type :: attachment_type
    character(len=:), allocatable :: dataset
    !> Index in the registry's scales; the axis in HDF5's (C) order, from 0.
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
  character(len=*), parameter :: not_a_variable = &
    "This is a netCDF dimension but not a netCDF variable."

  !> The dimension scales of one file and every axis attached to them so far; the scales'
  !> REFERENCE_LISTs are written once, at close (write_reference_lists).
  type :: dim_registry_type
    private
    type(dim_scale_type), allocatable :: scales(:)
    type(attachment_type), allocatable :: attached(:)
  contains
    procedure :: reset => registry_reset
    procedure :: attach => attach_dims
    procedure :: write_reference_lists
  end type dim_registry_type

contains

  !> Forget every scale and attachment (a new file).
  subroutine registry_reset(self)
    !> The registry, emptied.
    class(dim_registry_type), intent(inout) :: self
    if (allocated(self%scales)) deallocate (self%scales)
    if (allocated(self%attached)) deallocate (self%attached)
    allocate (self%scales(0), self%attached(0))
  end subroutine registry_reset

  !> Record `what` as the write's failure if hdferr reports one and none came before.
  subroutine note_failure(failed, hdferr, what)
    !> The first failure's description; unallocated while none.
    character(len=:), allocatable, intent(inout) :: failed
    !> HDF5's status of the call (0: success).
    integer, intent(in) :: hdferr
    !> What was being written (a dataset, group or attribute name).
    character(len=*), intent(in) :: what
    if (hdferr /= 0 .and. .not. allocated(failed)) failed = what
  end subroutine note_failure

  !> The units, description and long_name (the same text, the name netCDF/CF tools show)
  !> of dataset `dset`.
  subroutine describe(dset, units, description, failed)
    !> The open dataset.
    integer(hid_t), intent(in) :: dset
    !> Its units (UDUNITS form, "1" for none) and what it holds.
    character(len=*), intent(in) :: units, description
    !> The first failure's description (note_failure).
    character(len=:), allocatable, intent(inout) :: failed
    call put_str(dset, "units", units, failed)
    call put_str(dset, "description", description, failed)
    call put_str(dset, "long_name", description, failed)
  end subroutine describe

  !> A scalar UTF-8 string attribute `name` = `value` on the open object `oid`.
  subroutine put_str(oid, name, value, failed)
    !> The open object (file, group or dataset).
    integer(hid_t), intent(in) :: oid
    !> Name and value of the attribute.
    character(len=*), intent(in) :: name, value
    !> The first failure's description (note_failure).
    character(len=:), allocatable, intent(inout) :: failed
    integer(hid_t) :: atype, space, attr
    integer(hsize_t), parameter :: dims(1) = [1]
    integer :: hdferr
    call h5tcopy_f(H5T_FORTRAN_S1, atype, hdferr)
    call h5tset_size_f(atype, int(max(1, len(value)), size_t), hdferr)
    ! UTF-8: netCDF-4, h5netcdf and xarray decode it to text (h5py still gives bytes)
    call h5tset_cset_f(atype, H5T_CSET_UTF8_F, hdferr)
    call h5screate_f(H5S_SCALAR_F, space, hdferr)
    call h5acreate_f(oid, name, atype, space, attr, hdferr)
    call note_failure(failed, hdferr, "attribute "//name)
    if (hdferr == 0) then
      if (len(value) == 0) then
        call h5awrite_f(attr, atype, " ", dims, hdferr)
      else
        call h5awrite_f(attr, atype, value, dims, hdferr)
      end if
      call note_failure(failed, hdferr, "attribute "//name)
      call h5aclose_f(attr, hdferr)
    end if
    call h5sclose_f(space, hdferr)
    call h5tclose_f(atype, hdferr)
  end subroutine put_str

  !> Attach each axis of dataset `name` (open as `dset`, Fortran extents `extent`) in
  !> `file` to the scale of its dimension in `dims`; see the module comment. The HDF5
  !> dimension-scale attributes are written as H5DS writes them, but each once:
  !> DIMENSION_LIST here and the scales' REFERENCE_LIST at close (H5DSattach_scale
  !> rewrites both at every call, which doubled the time to write a sweep summary).
  subroutine attach_dims(self, file, name, dset, dims, extent, failed)
    !> The registry of the file's scales and attachments.
    class(dim_registry_type), intent(inout) :: self
    !> The open output file.
    integer(hid_t), intent(in) :: file
    !> Path of the dataset in the file; its dimensions' names, comma-separated, slowest first.
    character(len=*), intent(in) :: name, dims
    !> The open dataset.
    integer(hid_t), intent(in) :: dset
    !> The dataset's Fortran extents.
    integer(hsize_t), intent(in) :: extent(:)
    !> The first failure's description (note_failure).
    character(len=:), allocatable, intent(inout) :: failed
    character(len=:), allocatable :: group
    integer :: k, rank, hdferr, on(size(extent))
    group = parent_of(name)
    rank = size(extent)
    if (word_count(dims) /= rank) then
      call note_failure(failed, 1, name//" (dims '"//dims//"' for rank "// &
                        int_to_str(rank)//")")
      return
    end if
    if (rank == 1 .and. group_path(group, word(dims, 1)) == name) then
      call h5dsset_scale_f(dset, hdferr, word(dims, 1))
      call note_failure(failed, hdferr, "dimension scale "//name)
      call remember(self, group, word(dims, 1), extent(1))
      return
    end if
    do k = 1, rank
      on(k) = scale_index(self, file, group, word(dims, k), extent(k), name, failed)
      if (on(k) == 0) return
      ! HDF5 numbers the axes in C order from 0, reversed from the Fortran array's (a
      ! Fortran (component, time) array is (time, component) there)
      self%attached = [self%attached, attachment_type(name, on(k), rank - k)]
    end do
    call write_dimension_list(self, file, name, dset, on(rank:1:-1), failed)
  end subroutine attach_dims

  !> DIMENSION_LIST of `dset`: for each axis (C order) a reference to its scale.
  subroutine write_dimension_list(self, file, name, dset, on, failed)
    type(dim_registry_type), intent(in) :: self
    integer(hid_t), intent(in) :: file
    character(len=*), intent(in) :: name
    integer(hid_t), intent(in) :: dset
    integer, intent(in) :: on(:)
    character(len=:), allocatable, intent(inout) :: failed
    integer(c_int64_t), target :: refs(size(on))
    type(vlen_type), target :: list(size(on))
    integer(hid_t) :: vtype, space, attr
    integer :: c, hdferr, status
    status = 0
    do c = 1, size(on)
      refs(c) = object_ref(file, scale_path(self, on(c)), hdferr)
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
    call note_failure(failed, status, "dimensions of "//name)
  end subroutine write_dimension_list

  !> REFERENCE_LIST of every scale of `file`: (dataset, axis) of each axis attached to it.
  subroutine write_reference_lists(self, file, failed)
    !> The registry of the file's scales and attachments.
    class(dim_registry_type), intent(in) :: self
    !> The open output file, about to be closed.
    integer(hid_t), intent(in) :: file
    !> The first failure's description (note_failure).
    character(len=:), allocatable, intent(inout) :: failed
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
        list(n)%dataset = object_ref(file, self%attached(j)%dataset, hdferr)
        status = max(status, abs(hdferr))
      end do
      call h5tcreate_f(H5T_COMPOUND_F, c_sizeof(list(1)), ctype, hdferr)
      call h5tinsert_f(ctype, "dataset", 0_size_t, H5T_STD_REF_OBJ, hdferr)
      call h5tinsert_f(ctype, "dimension", c_sizeof(list(1)%dataset), H5T_NATIVE_INTEGER, &
                       hdferr)
      call h5screate_simple_f(1, [size(list, kind=hsize_t)], space, hdferr)
      call h5dopen_f(file, scale_path(self, k), scale, hdferr)
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
      call note_failure(failed, status, "dimension "//scale_path(self, k))
    end do
  end subroutine write_reference_lists

  !> An HDF5 object reference (hobj_ref_t) to `path` in `file`.
  integer(c_int64_t) function object_ref(file, path, hdferr) result(ref)
    integer(hid_t), intent(in) :: file
    character(len=*), intent(in) :: path
    integer, intent(out) :: hdferr
    type(hobj_ref_t_f) :: r
    call h5rcreate_f(file, path, r, hdferr)
    ref = int(r%ref, c_int64_t)
  end function object_ref

  pure function scale_path(self, k) result(path)
    type(dim_registry_type), intent(in) :: self
    integer, intent(in) :: k
    character(len=:), allocatable :: path
    path = group_path(self%scales(k)%group, self%scales(k)%name)
  end function scale_path

  !> Index in self%scales of dimension `dim` seen from `group` (its own, else the nearest
  !> parent's), creating a dimension-only one in `group` if there is none; 0 on failure
  !> (a length that disagrees with the dimension's fails the write).
  integer function scale_index(self, file, group, dim, length, user, failed) result(k)
    type(dim_registry_type), intent(inout) :: self
    integer(hid_t), intent(in) :: file
    character(len=*), intent(in) :: group, dim, user
    integer(hsize_t), intent(in) :: length
    character(len=:), allocatable, intent(inout) :: failed
    k = find_scale(self, group, dim)
    if (k == 0) then
      call create_dimension(self, file, group, dim, length, failed)
      if (.not. allocated(failed)) k = size(self%scales)
    else if (self%scales(k)%length /= length) then
      call note_failure(failed, 1, user//" (length "//int_to_str(int(length))// &
                        " along dimension "//dim//" of length "// &
                        int_to_str(int(self%scales(k)%length))//")")
      k = 0
    end if
  end function scale_index

  !> Index in self%scales of dimension `dim` as seen from `group`; 0 if none.
  integer function find_scale(self, group, dim) result(found)
    type(dim_registry_type), intent(in) :: self
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
  subroutine create_dimension(self, file, group, dim, length, failed)
    type(dim_registry_type), intent(inout) :: self
    integer(hid_t), intent(in) :: file
    character(len=*), intent(in) :: group, dim
    integer(hsize_t), intent(in) :: length
    character(len=:), allocatable, intent(inout) :: failed
    integer(hid_t) :: space, scale
    integer :: hdferr
    character(len=10) :: digits
    call h5screate_simple_f(1, [length], space, hdferr)
    call h5dcreate_f(file, group_path(group, dim), H5T_NATIVE_REAL, space, scale, hdferr)
    call h5sclose_f(space, hdferr)
    call note_failure(failed, hdferr, "dimension "//group_path(group, dim))
    if (hdferr /= 0) return
    write (digits, "(i10)") length
    call h5dsset_scale_f(scale, hdferr, not_a_variable//digits)
    call note_failure(failed, hdferr, "dimension "//group_path(group, dim))
    call describe(scale, "-", "Dimension "//dim//" (its length only; no data)", failed)
    call h5dclose_f(scale, hdferr)
    call remember(self, group, dim, length)
  end subroutine create_dimension

  subroutine remember(self, group, dim, length)
    type(dim_registry_type), intent(inout) :: self
    character(len=*), intent(in) :: group, dim
    integer(hsize_t), intent(in) :: length
    self%scales = [self%scales, dim_scale_type(group, dim, length)]
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

end module davit_io_hdf5_dims
