!> Where davit looks for a file a deck names (a data file, a sweep's base deck, the bench
!> decks): a path as given if absolute; else the first folder given (the deck's own), then
!> each folder of the environment variable DAVIT_PATH (':'-separated; the installed
!> `davit` puts its share/davit/input there, so a deck copied anywhere still finds the
!> project's data). A miss reports every folder searched, for the message.
module davit_io_search_path
  implicit none
  private
  public :: find_file, folder_of

contains

  !> `path` looked up in `first` (a folder, "" = the current one, with or without its
  !> trailing "/"), then in each DAVIT_PATH folder. `full` is the file found, or `path`
  !> in `first` when none is (an open then fails naming it); `searched` lists the
  !> folders tried, comma-separated.
  subroutine find_file(first, path, full, found, searched)
    !> The folder tried first ("" = the current one) and the file's path.
    character(len=*), intent(in) :: first, path
    !> The file found, or path in first when none is.
    character(len=:), allocatable, intent(out) :: full
    !> Whether the file was found.
    logical, intent(out) :: found
    !> The folders tried, comma-separated.
    character(len=:), allocatable, intent(out), optional :: searched
    character(len=:), allocatable :: dirs, tried, dir
    character(len=4096) :: env
    integer :: n, status, colon
    full = in_folder(first, path)
    tried = display(first)
    if (len(path) > 0) then
      if (path(1:1) == "/") tried = display(folder_of(path))
    end if
    inquire (file=full, exist=found)
    if (present(searched)) searched = tried
    if (found .or. len(path) == 0) return
    if (path(1:1) == "/") return
    call get_environment_variable("DAVIT_PATH", env, n, status)
    dirs = ""
    if (status == 0) dirs = trim(env)
    do while (len(dirs) > 0)
      colon = index(dirs, ":")
      if (colon == 0) colon = len(dirs) + 1
      dir = dirs(1:colon - 1)
      dirs = dirs(min(colon + 1, len(dirs) + 1):)
      if (len(dir) == 0) cycle
      tried = tried//", "//display(dir)
      inquire (file=in_folder(dir, path), exist=found)
      if (found) then
        full = in_folder(dir, path)
        exit
      end if
    end do
    if (present(searched)) searched = tried
  end subroutine find_file

  !> The folder part of `path`, with its trailing "/" ("" for a bare name).
  pure function folder_of(path) result(folder)
    !> A file path.
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: folder
    folder = path(1:index(path, "/", back=.true.))
  end function folder_of

  !> `path` in `folder` (as given if absolute or if the folder is "").
  pure function in_folder(folder, path) result(full)
    character(len=*), intent(in) :: folder, path
    character(len=:), allocatable :: full
    full = path
    if (len(path) == 0 .or. len(folder) == 0) return
    if (path(1:1) == "/") return
    if (folder(len(folder):) == "/") then
      full = folder//path
    else
      full = folder//"/"//path
    end if
  end function in_folder

  !> A folder as a message shows it ("." for the current one).
  pure function display(folder) result(text)
    character(len=*), intent(in) :: folder
    character(len=:), allocatable :: text
    text = folder
    if (len(text) == 0) text = "."
    if (len(text) > 1 .and. text(len(text):) == "/") text = text(1:len(text) - 1)
  end function display

end module davit_io_search_path
