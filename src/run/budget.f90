!> Refuse, before anything is built or written, a run that cannot finish or cannot fit
!> (issue 19, classes 1, 3, 4): the time grid (steps t_end/dt, recorded samples
!> t_end/output_interval; counted in reals and 64-bit integers, never a wrapped 32-bit
!> count) and an estimate of the memory the run holds: the recorded samples, the seat's
!> 1 kHz trace, and the wave components with their per-component tables. The limit is
!> &simulation max_memory, or 80 % of the machine's physical memory where it is 0.
!> Each refusal names the file, line, group and key, the value and what is allowed.
module davit_run_budget
  use davit_kinds, only: wp, i8
  use davit_error, only: error_type, fatal_error
  use davit_io_config, only: config_type
  use davit_io_deck_reader, only: fmt_real
  use davit_io_namelist, only: to_lower, line_end
  use davit_run_scene, only: scene_type, new_scene
  implicit none
  private
  public :: check_run_budget, run_memory_estimate, memory_limit
  public :: max_steps, max_contact_ratio, max_wave_ratio

  !> Steps of dt over t_end: at the fastest scenes' ~1 us per step, 1e10 steps are hours
  !> to days of CPU; beyond it the run cannot finish (dt = 1e-300 would never end).
  real(wp), parameter :: max_steps = 1.0e10_wp
  !> t_end/dt_contact: t + dt_contact stays at least ~4500 ulp above t.
  real(wp), parameter :: max_contact_ratio = 1.0e12_wp
  !> t_end/wave_update: the slow wave clock counts its intervals in a default integer.
  real(wp), parameter :: max_wave_ratio = 1.0e9_wp
  !> Recorded samples are indexed by default integers.
  real(wp), parameter :: max_samples = 2.0e9_wp
  !> Fixed part: the program, HDF5, the BEM databases.
  real(wp), parameter :: bytes_fixed = 200.0e6_wp
  real(wp), parameter :: gib = 1024.0_wp**3

contains

  !> An error naming the first key whose value the run cannot finish or fit with.
  !> in_sweep: the values may come from the sweep's keys, not from the base deck's lines.
  subroutine check_run_budget(cfg, error, in_sweep)
    !> The checked configuration of the run.
    type(config_type), intent(in) :: cfg
    !> Set for the first key the run cannot finish or fit with.
    type(error_type), allocatable, intent(out) :: error
    !> The values may come from a sweep's keys (the message says so).
    logical, intent(in), optional :: in_sweep
    real(wp) :: ratio, bytes, limit, parts(3)
    character(len=:), allocatable :: problem, allowed
    associate (s => cfg%simulation)
      ratio = s%t_end/s%dt
      if (.not. (ratio <= max_steps)) then
        call refuse(cfg, "simulation", "dt", s%dt, "t_end/dt = "//num(ratio)// &
                    " steps (t_end = "//num(s%t_end)//" s) exceed the bound of "// &
                    num(max_steps)//" steps, a run that cannot finish", &
                    "dt >= t_end/"//num(max_steps)//" = "// &
                    num(s%t_end/max_steps)//" s", error, in_sweep)
        return
      end if
      if (s%dt_contact > 0.0_wp) then
        ratio = s%t_end/s%dt_contact
        if (.not. (ratio <= max_contact_ratio)) then
          call refuse(cfg, "simulation", "dt_contact", s%dt_contact, "t_end/dt_contact = "// &
                      num(ratio)//" (t_end = "//num(s%t_end)//" s): a step this "// &
                      "small is not resolved in the time t", "0 or dt_contact >= t_end/"// &
                      num(max_contact_ratio)//" = "// &
                      num(s%t_end/max_contact_ratio)//" s", error, in_sweep)
          return
        end if
      end if
      if (s%wave_update > 0.0_wp) then
        ratio = s%t_end/s%wave_update
        if (.not. (ratio <= max_wave_ratio)) then
          call refuse(cfg, "simulation", "wave_update", s%wave_update, "t_end/wave_update = "// &
                      num(ratio)//" intervals of the slow wave clock (t_end = "// &
                      num(s%t_end)//" s) exceed "//num(max_wave_ratio), &
                      "0 or wave_update >= t_end/"//num(max_wave_ratio)//" = "// &
                      num(s%t_end/max_wave_ratio)//" s", error, in_sweep)
          return
        end if
      end if
      ratio = s%t_end/s%output_interval
      if (.not. (ratio <= max_samples)) then
        call refuse(cfg, "simulation", "output_interval", s%output_interval, &
                    "t_end/output_interval = "//num(ratio)//" samples (t_end = "// &
                    num(s%t_end)//" s) exceed "//num(max_samples), &
                    "output_interval >= t_end/"//num(max_samples)//" = "// &
                    num(s%t_end/max_samples)//" s", error, in_sweep)
        return
      end if
      bytes = run_memory_estimate(cfg)
      limit = memory_limit(cfg)
      if (bytes > limit) then
        parts = memory_parts(cfg)
        problem = "the run would hold about "//gib_text(bytes)//" ("// &
                  memory_terms(cfg)//"), more than the limit of "//gib_text(limit)// &
                  " (&simulation max_memory"
        if (s%max_memory <= 0.0_wp) problem = problem//" = 0: 80 % of physical memory"
        problem = problem//")"
        allowed = "a run within max_memory: raise output_interval, lower t_end, use fewer "// &
                  "&sea components (n_frequencies x n_directions) or raise max_memory [GiB]"
        if (parts(3) >= max(parts(1), parts(2))) then
          call refuse(cfg, "sea", "n_frequencies", real(cfg%sea%n_frequencies, wp), &
                      problem//" with n_directions = "// &
                      num(real(cfg%sea%n_directions, wp)), allowed, error, in_sweep)
        else if (parts(2) > parts(1)) then
          call refuse(cfg, "simulation", "t_end", s%t_end, problem, allowed, error, in_sweep)
        else
          call refuse(cfg, "simulation", "output_interval", s%output_interval, &
                      problem//" with t_end = "//num(s%t_end)//" s", allowed, error, in_sweep)
        end if
        return
      end if
    end associate
  end subroutine check_run_budget

  !> Memory the run holds [bytes]: samples x fields recorded, the seat trace, the waves.
  real(wp) function run_memory_estimate(cfg) result(bytes)
    !> The run's configuration.
    type(config_type), intent(in) :: cfg
    real(wp) :: terms(3)
    terms = memory_parts(cfg)
    bytes = bytes_fixed + sum(terms)
  end function run_memory_estimate

  !> (recorded samples, seat trace, wave components) [bytes], as the deck's scene holds
  !> them (none for a scene the deck reader would have refused).
  function memory_parts(cfg) result(parts)
    type(config_type), intent(in) :: cfg
    real(wp) :: parts(3)
    class(scene_type), allocatable :: scene
    type(error_type), allocatable :: error
    real(wp) :: samples, n_comp
    parts = 0.0_wp
    call new_scene(cfg%simulation%scene, scene, error)
    if (allocated(error)) return
    samples = cfg%simulation%t_end/cfg%simulation%output_interval + 1.0_wp
    n_comp = 1.0_wp
    if (cfg%sea%wave_type == "irregular") then
      n_comp = real(cfg%sea%n_frequencies, wp)
      if (cfg%sea%summation == "double") n_comp = n_comp*real(cfg%sea%n_directions, wp)
    end if
    parts = scene%memory_parts(cfg, samples, n_comp)
  end function memory_parts

  !> The estimate's terms in words.
  function memory_terms(cfg) result(s)
    type(config_type), intent(in) :: cfg
    character(len=:), allocatable :: s
    real(wp) :: parts(3)
    parts = memory_parts(cfg)
    s = "recorded samples "//gib_text(parts(1))//": t_end/output_interval = "// &
        num(cfg%simulation%t_end/cfg%simulation%output_interval)//" samples"
    if (parts(2) > 0.0_wp) s = s//", seat trace at 1 kHz "//gib_text(parts(2))//""
    s = s//", wave components "//gib_text(parts(3))//""
  end function memory_terms

  !> The memory limit [bytes]: max_memory [GiB], or 80 % of MemTotal (/proc/meminfo;
  !> 16 GiB where it cannot be read).
  real(wp) function memory_limit(cfg) result(limit)
    !> The run's configuration (&simulation max_memory).
    type(config_type), intent(in) :: cfg
    if (cfg%simulation%max_memory > 0.0_wp) then
      limit = cfg%simulation%max_memory*gib
    else
      limit = 0.8_wp*physical_memory()
    end if
  end function memory_limit

  !> Physical memory [bytes] from /proc/meminfo (MemTotal, kB); 16 GiB if unreadable.
  real(wp) function physical_memory() result(bytes)
    character(len=256) :: line
    integer :: u, ios
    integer(i8) :: kb
    bytes = 16.0_wp*gib
    open (newunit=u, file="/proc/meminfo", action="read", status="old", iostat=ios)
    if (ios /= 0) return
    do
      read (u, "(a)", iostat=ios) line
      if (ios /= 0) exit
      if (line(1:9) == "MemTotal:") then
        read (line(10:), *, iostat=ios) kb
        if (ios == 0 .and. kb > 0) bytes = 1024.0_wp*real(kb, wp)
        exit
      end if
    end do
    close (u)
  end function physical_memory

  !> The error "file:line: &group: key = value: problem; allowed: allowed".
  subroutine refuse(cfg, group, key, value, problem, allowed, error, in_sweep)
    type(config_type), intent(in) :: cfg
    character(len=*), intent(in) :: group, key, problem, allowed
    real(wp), intent(in) :: value
    type(error_type), allocatable, intent(out) :: error
    logical, intent(in), optional :: in_sweep
    integer :: line
    character(len=32) :: buf
    line = 0
    if (present(in_sweep)) then
      if (in_sweep) then
        call fatal_error(error, cfg%filename//" (this sweep case): &"//group//": "//key// &
                         " = "//num(value)//": "//problem//"; allowed: "//allowed)
        return
      end if
    end if
    if (allocated(cfg%deck_text)) line = key_line(cfg%deck_text, group, key)
    if (line > 0) then
      write (buf, "(i0)") line
      call fatal_error(error, cfg%filename//":"//trim(buf)//": &"//group//": "//key//" = "// &
                       num(value)//": "//problem//"; allowed: "//allowed)
    else
      call fatal_error(error, cfg%filename//": &"//group//": "//key//" = "//num(value)// &
                       " (default): "//problem//"; allowed: "//allowed)
    end if
  end subroutine refuse

  !> Line of `key = ...` inside namelist group `group` of the deck text; 0 if absent.
  pure integer function key_line(text, group, key) result(line)
    character(len=*), intent(in) :: text, group, key
    integer :: i0, i1, lineno, j, k
    logical :: inside
    character(len=:), allocatable :: s
    line = 0
    lineno = 0
    inside = .false.
    i0 = 1
    do while (i0 <= len(text))
      i1 = line_end(text, i0)
      lineno = lineno + 1
      s = to_lower(text(i0:i1 - 1))
      k = index(s, "!")
      if (k > 0) s = s(:k - 1)
      s = adjustl(s)
      if (len_trim(s) > 0) then
        if (s(1:1) == "&") then
          inside = trim(s(2:)) == group .or. index(s(2:), group//" ") == 1 .or. &
                   (len_trim(s) == len(group) + 1 .and. s(2:len(group) + 1) == group)
        else if (s(1:1) == "/") then
          inside = .false.
        end if
        if (inside) then
          j = index(s, key)
          do while (j > 0)
            if (is_start(s, j) .and. next_is_equals(s, j + len(key))) then
              line = lineno
            end if
            k = index(s(j + 1:), key)
            if (k == 0) exit
            j = j + k
          end do
        end if
      end if
      i0 = i1 + 1
    end do
  contains
    pure logical function is_start(s, j)
      character(len=*), intent(in) :: s
      integer, intent(in) :: j
      is_start = j == 1
      if (.not. is_start) then
        is_start = index("abcdefghijklmnopqrstuvwxyz0123456789_%", s(j - 1:j - 1)) == 0
      end if
    end function is_start
    pure logical function next_is_equals(s, j)
      character(len=*), intent(in) :: s
      integer, intent(in) :: j
      character(len=:), allocatable :: rest
      next_is_equals = .false.
      if (j > len(s)) return
      rest = adjustl(s(j:))
      next_is_equals = rest(1:1) == "="
    end function next_is_equals
  end function key_line

  !> fmt_real, or an exponent of three digits where fmt_real has no room for it.
  function num(x) result(s)
    real(wp), intent(in) :: x
    character(len=:), allocatable :: s
    character(len=32) :: buf
    if (x == 0.0_wp .or. (abs(x) >= 1.0e-99_wp .and. abs(x) < 1.0e99_wp)) then
      s = fmt_real(x)
    else
      write (buf, "(es12.4e3)") x
      s = trim(adjustl(buf))
    end if
  end function num

  !> bytes as "12.3 GiB" (three significant digits).
  pure function gib_text(bytes) result(s)
    real(wp), intent(in) :: bytes
    character(len=:), allocatable :: s
    character(len=32) :: buf
    real(wp) :: x
    x = bytes/gib
    if (x >= 100.0_wp) then
      write (buf, "(f0.0)") x
    else if (x >= 0.01_wp) then
      write (buf, "(f0.2)") x
    else
      write (buf, "(es9.2)") x
    end if
    s = trim(adjustl(buf))
    if (s(1:1) == ".") s = "0"//s
    if (s(len(s):len(s)) == ".") s = s(:len(s) - 1)
    s = s//" GiB"
  end function gib_text

end module davit_run_budget
