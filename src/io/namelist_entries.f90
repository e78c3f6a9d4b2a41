!> The entries of a namelist deck (group, key, value text, line) and the open-addressing
!> hash of (group, key) -> entry that keeps parsing and every lookup linear in the deck's
!> size (davit_io_namelist builds and reads it).
module davit_io_namelist_entries
  use davit_kinds, only: i8
  implicit none
  private
  public :: nml_entry, probe, rehash, move_entry, str_hash


  type :: nml_entry
    !> Group, key (lower case) and the value's text.
    character(len=:), allocatable :: group, key, value
    !> Line of the deck the key is on.
    integer :: line = 0
    !> Whether the reader has read the key (unused keys are refused).
    logical :: used = .false.
  end type nml_entry

contains

  !> Linear probing: the entry index of (group, key), or 0 with `h` the free slot.
  integer function probe(slot, entries, group, key, h) result(k)
    !> The hash table: entry index per slot (0: empty), size a power of two.
    integer, intent(in) :: slot(:)
    !> The entries.
    type(nml_entry), intent(in) :: entries(:)
    !> Group and key.
    character(len=*), intent(in) :: group, key
    !> The free slot where the key would go, when it is not found.
    integer, intent(out) :: h
    k = 0
    h = iand(str_hash(group, key), size(slot) - 1) + 1
    do while (slot(h) /= 0)
      if (entries(slot(h))%key == key) then
        if (entries(slot(h))%group == group) then
          k = slot(h)
          return
        end if
      end if
      h = merge(1, h + 1, h == size(slot))
    end do
  end function probe

  !> Rebuild the hash of `entries` with `n` slots (a power of two).
  subroutine rehash(slot, entries, n)
    !> The hash table, rebuilt.
    integer, allocatable, intent(inout) :: slot(:)
    !> The entries.
    type(nml_entry), intent(in) :: entries(:)
    !> Number of slots wanted (rounded up to a power of two).
    integer, intent(in) :: n
    integer :: k, h, m
    m = 1
    do while (m < n)
      m = 2*m
    end do
    deallocate (slot)
    allocate (slot(m))
    slot = 0
    do k = 1, size(entries)
      if (probe(slot, entries(1:k - 1), entries(k)%group, entries(k)%key, h) == 0) slot(h) = k
    end do
  end subroutine rehash

  subroutine move_entry(from, to)
    !> The entry moved from, and the one moved into.
    type(nml_entry), intent(inout) :: from, to
    call move_alloc(from%group, to%group)
    call move_alloc(from%key, to%key)
    call move_alloc(from%value, to%value)
    to%line = from%line
    to%used = from%used
  end subroutine move_entry

  !> FNV-1a hash of group, a separator and key, as a non-negative integer.
  pure integer function str_hash(group, key) result(h)
    !> Group and key.
    character(len=*), intent(in) :: group, key
    integer(i8) :: x
    integer :: i
    x = 2166136261_i8
    do i = 1, len_trim(group)
      x = iand(ieor(x, int(iachar(group(i:i)), i8))*16777619_i8, 4294967295_i8)
    end do
    x = iand(ieor(x, 0_i8)*16777619_i8, 4294967295_i8)
    do i = 1, len(key)
      x = iand(ieor(x, int(iachar(key(i:i)), i8))*16777619_i8, 4294967295_i8)
    end do
    h = int(iand(x, 2147483647_i8))
  end function str_hash

end module davit_io_namelist_entries
