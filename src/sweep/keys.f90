!> The sweep deck: one `&sweep` group that names a base run deck and lists values for the
!> swept inputs (`davit sweep`). The base deck gives every other key. A list left out keeps
!> the base deck's value, so an empty list never means "no cases".
!>
!> The sweep owns the sea state: when `levels` is given, each case takes the level's preset
!> wave height and wind speed (review G19) and the peak period of that height (G18);
!> `heights` and `periods` override the height and the period. When `angles_deg` is given
!> the wind blows along the waves (paper III.B). Keys are read and range-checked by the same
!> deck reader as run decks, so errors name the file, line, group, key and allowed range.
!>
!> Adaptive realisations (issue 16): with target_halfwidth > 0 each cell (a combination of
!> the swept inputs other than the realisation) gets `realisations`, then batches of
!> `realisation_batch` more until the 95 % Wilson half-width of its collision probability
!> is at most the target or it has max_realisations (davit_sweep_adaptive).
module davit_sweep_keys
  use davit_kinds, only: wp, i8
  use davit_error, only: error_type, fatal_error
  use davit_io_namelist, only: nml_deck, read_deck, parse_deck, key_at, int_to_str
  use davit_io_deck_reader, only: deck_reader_type, key_doc, fmt_real
  use davit_io_config, only: config_type, read_config
  use davit_io_shared_keys, only: read_integrator
  use davit_io_text, only: int_text, fmt_fixed
  use davit_run_budget, only: memory_limit
  use davit_run_scene, only: scene_type, new_scene
  use davit_io_search_path, only: find_file, folder_of
  implicit none
  private
  public :: sweep_config, read_sweep, parse_sweep, document_sweep_keys, wave_type_names
  public :: case_count, max_cases

  !> Wave types a sweep may list; their position minus one is the summary's code
  !> (0 calm, 1 airy, 2 stokes2, 3 irregular).
  character(len=9), parameter :: wave_type_names(0:3) = [character(len=9) :: "calm", &
    "airy", "stokes2", "irregular"]
  integer, parameter :: max_values = 1000
  !> Most cases a sweep may list. Each case is a launch (~0.1 s to minutes of CPU), so 10^6
  !> cases are days to years of computing and a summary of ~0.5 GB; the lists' product
  !> reaches 8e21, far past what any run could hold (case indices are default integers).
  integer(i8), parameter :: max_cases = 1000000_i8
  !> Memory a case holds while the sweep runs [bytes]: its inputs and row, the rows' texts
  !> and the summary's column buffers (~530 B measured for 1e5 and 1e6 cases), with margin.
  real(wp), parameter :: bytes_per_case = 1000.0_wp

  type :: sweep_config
    !> The sweep deck and its text (stored in the summary; a resume checks it).
    character(len=:), allocatable :: filename, deck_text
    !> The base deck as written in the sweep deck, and as opened (relative to the sweep
    !> deck's folder unless absolute).
    character(len=:), allocatable :: base_deck, base_path
    !> The base deck's run configuration.
    type(config_type) :: base
    !> Swept values; `has_*` tells whether the deck lists them (else the base deck's).
    integer, allocatable :: levels(:)
    !> Wave heights [m], periods [s], directions [deg] (0 from port), initial clearances in
    !> boat beams, and time steps [s].
    real(wp), allocatable :: heights(:), periods(:), angles_deg(:), clearances_b(:), dts(:)
    !> Wind on or off.
    logical, allocatable :: winds(:)
    !> Wave types (names from wave_type_names).
    character(len=9), allocatable :: wave_types(:)
    !> Whether the deck lists levels, heights and periods.
    logical :: has_levels = .false., has_heights = .false., has_periods = .false.
    !> Whether the deck lists wave directions and clearances.
    logical :: has_angles = .false., has_clearances = .false.
    !> Realisations per cell (the first round when adaptive), and the seed from which each
    !> case's seed derives.
    integer :: realisations = 1, base_seed = 0
    !> Adaptive realisations: target 95 % half-width of a cell's collision probability
    !> (0 = off: every cell runs `realisations`), the cap per cell and the batch per round.
    !> The case list always holds max_realisations per cell (= realisations when off).
    real(wp) :: target_halfwidth = 0.0_wp
    !> Realisations per cell at most, and realisations added per open cell each round.
    integer :: max_realisations = 1, realisation_batch = 1
    !> Draw each regular wave's phase from the case seed; end each run when the lowering is over.
    logical :: random_phase = .true., stop_at_release = .true.
    !> The time integrator and its fast substeps of every case (default: the base deck's).
    character(len=:), allocatable :: integrator
    !> Fast substeps per macro step of the multirate integrators.
    integer :: substeps = 10
  end type sweep_config

contains

  !> Read and validate sweep deck `filename` and its base deck.
  subroutine read_sweep(filename, sweep, error)
    !> Path of the sweep deck.
    character(len=*), intent(in) :: filename
    !> The sweep's settings, with its base deck.
    type(sweep_config), intent(out) :: sweep
    !> Set when a deck cannot be read or a key is out of range.
    type(error_type), allocatable, intent(out) :: error
    type(nml_deck) :: deck
    call read_deck(filename, deck, error)
    if (allocated(error)) return
    call sweep_from_deck(deck, sweep, error)
  end subroutine read_sweep

  !> Same as read_sweep for sweep deck text in memory (tests); the base deck is a file.
  subroutine parse_sweep(filename, text, sweep, error)
    !> Name of the sweep deck (for messages and the base deck's folder), and its text.
    character(len=*), intent(in) :: filename, text
    !> The sweep's settings, with its base deck.
    type(sweep_config), intent(out) :: sweep
    !> Set when a deck cannot be parsed or a key is out of range.
    type(error_type), allocatable, intent(out) :: error
    type(nml_deck) :: deck
    call parse_deck(filename, text, deck, error)
    if (allocated(error)) return
    call sweep_from_deck(deck, sweep, error)
  end subroutine parse_sweep

  !> The documentation of every &sweep key (`davit keys`, README).
  subroutine document_sweep_keys(docs)
    !> One entry per &sweep key.
    type(key_doc), allocatable, intent(out) :: docs(:)
    type(deck_reader_type) :: reader
    type(sweep_config) :: sweep
    call reader%init_defaults()
    call read_keys(reader, sweep)
    docs = reader%docs
  end subroutine document_sweep_keys

  subroutine sweep_from_deck(deck, sweep, error)
    !> The parsed sweep deck.
    type(nml_deck), intent(in) :: deck
    !> The sweep's settings, read from the deck.
    type(sweep_config), intent(inout) :: sweep
    !> Set when a key is out of range or the base deck cannot be read.
    type(error_type), allocatable, intent(out) :: error
    type(deck_reader_type) :: reader
    call reader%init(deck)
    call read_keys(reader, sweep)
    call reader%finish(error)
    if (allocated(error)) return
    sweep%filename = deck%filename
    sweep%deck_text = deck%text
    if (len(sweep%base_deck) == 0) then
      call fatal_error(error, key_at(deck, "sweep", ["base_deck"])// &
                       "&sweep: base_deck is required (the run "// &
                       "deck every case starts from)")
      return
    end if
    call find_base_deck(deck, sweep, error)
    if (allocated(error)) return
    call read_config(sweep%base_path, sweep%base, error)
    if (allocated(error)) return
    call complete_defaults(reader, sweep)
    call check_sweep(sweep, deck, error)
  end subroutine sweep_from_deck

  subroutine read_keys(r, s)
    !> The deck reader, recording each key read.
    type(deck_reader_type), intent(inout) :: r
    !> The sweep's settings, read from the reader.
    type(sweep_config), intent(inout) :: s
    character(len=*), parameter :: g = "sweep"
    call r%string(g, "base_deck", s%base_deck, "", "Run deck every case starts from "// &
                  "(in the sweep deck's folder, else a DAVIT_PATH folder); required. Sweep "// &
                  "decks only hold "// &
                  "&sweep.")
    call r%int_list(g, "levels", s%levels, [5], 3, 5, "-", "Sea-state levels; each sets "// &
                    "the level's preset wave height and wind speed and the "// &
                    "peak period of the height.", 1, 10, default_text="base deck")
    call r%real_list(g, "heights", s%heights, [4.0_wp], 0.0_wp, 20.0_wp, "m", &
                     "Wave heights H (regular 2a, irregular H of eq. 44), instead of the "// &
                     "level preset; the period follows unless periods is given.", 1, &
                     max_values, default_text="level preset or base deck", lo_open=.true.)
    call r%real_list(g, "periods", s%periods, [12.72_wp], 1.0_wp, 40.0_wp, "s", &
                     "Regular-wave periods, instead of the peak period of the height.", 1, &
                     max_values, default_text="peak period or base deck")
    call r%real_list(g, "angles_deg", s%angles_deg, [90.0_wp], -360.0_wp, 360.0_wp, "deg", &
                     "Encounter angles chi (&sea direction_deg: travelled towards, 90 = "// &
                     "from port); the wind blows along the waves.", 1, max_values, &
                     default_text="base deck")
    call r%logical_list(g, "wind", s%winds, [.true.], "Wind on (the level preset speed, "// &
                        "or the base deck's) or off (speed 0).", 1, 2, &
                        default_text="base deck (on if its speed > 0)")
    call r%real_list(g, "clearances_b", s%clearances_b, [0.5_wp], 0.0_wp, 20.0_wp, "-", &
                     "Initial fender-to-ship-side distance in boat widths (&boat beam); boat "// &
                     "and davit heads move together, so the boat still hangs plumb.", 1, &
                     max_values, default_text="base deck")
    call r%choice_list(g, "wave_types", s%wave_types, ["stokes2"], wave_type_names, &
                       "Wave types (&sea wave_type).", 1, 4, default_text="base deck")
    call r%real_list(g, "dts", s%dts, [2.0e-4_wp], 0.0_wp, 1.0_wp, "s", &
                     "Time steps (&simulation dt), e.g. a step-size study.", 1, max_values, &
                     default_text="base deck", lo_open=.true.)
    call read_integrator(r, g, s%integrator, s%substeps, &
                         "Time integrator of every case (&simulation integrator), e.g. "// &
                         "'mri2' with dts = 0.01 and substeps = 5 for long sweeps "// &
                         "(Benchmarks, Multirate).", &
                         "Fast RK4 substeps per step of the multirate integrators "// &
                         "(&simulation substeps).", default_text="base deck")
    call r%int(g, "realisations", s%realisations, 1, 1, 100000, "-", &
               "Random realisations of every combination: random phase (regular waves) "// &
               "or random component phases (irregular).")
    call r%real(g, "target_halfwidth", s%target_halfwidth, 0.0_wp, 0.0_wp, 0.5_wp, "-", &
                "Adaptive realisations: add realisation_batch realisations to a cell (a "// &
                "combination of the other swept values) until the 95 % Wilson half-width "// &
                "of its collision probability (status-ok cases) is at most this, or it has "// &
                "max_realisations; realisations is the first round. 0 = off. Not with "// &
                "--shard or MPI.")
    call r%int(g, "max_realisations", s%max_realisations, s%realisations, 1, 100000, "-", &
               "Adaptive realisations: most realisations of a cell (>= realisations).", &
               default_text="realisations")
    call r%int(g, "realisation_batch", s%realisation_batch, s%realisations, 1, 100000, "-", &
               "Adaptive realisations: realisations added to each open cell per round.", &
               default_text="realisations")
    call r%int(g, "base_seed", s%base_seed, 0, 0, huge(1), "-", "Seed from which each "// &
               "case's seed derives (SplitMix64 of base seed and case index).", &
               default_text="base deck's seed")
    call r%logical(g, "random_phase", s%random_phase, .true., &
                   "Regular waves: draw the phase epsilon from the case seed (uniform in "// &
                   "0-360 deg); .false. keeps the base deck's phase_deg.")
    call r%logical(g, "stop_at_release", s%stop_at_release, .true., &
                   "End each run when the lowering is over (hooks released, or waterborne "// &
                   "when release is off): the results cover only the lowering.")
  end subroutine read_keys

  !> Defaults that depend on the base deck, for the keys the sweep deck leaves out.
  subroutine complete_defaults(r, s)
    !> The deck reader (which keys the deck gave).
    type(deck_reader_type), intent(in) :: r
    !> The sweep's settings, completed with the base deck's values.
    type(sweep_config), intent(inout) :: s
    character(len=*), parameter :: g = "sweep"
    s%has_levels = r%has(g, "levels")
    s%has_heights = r%has(g, "heights")
    s%has_periods = r%has(g, "periods")
    s%has_angles = r%has(g, "angles_deg")
    s%has_clearances = r%has(g, "clearances_b")
    associate (b => s%base)
      if (.not. s%has_levels) s%levels = [b%sea%level]
      if (.not. s%has_heights) s%heights = [b%sea%height]
      if (.not. s%has_periods) s%periods = [b%sea%period]
      if (.not. s%has_angles) s%angles_deg = [b%sea%direction*180.0_wp/acos(-1.0_wp)]
      if (.not. r%has(g, "wind")) s%winds = [b%wind%speed > 0.0_wp]
      if (.not. s%has_clearances) s%clearances_b = [-1.0_wp]
      if (.not. r%has(g, "wave_types")) s%wave_types = [character(len=9) :: b%sea%wave_type]
      if (.not. r%has(g, "dts")) s%dts = [b%simulation%dt]
      if (.not. r%has(g, "integrator")) s%integrator = b%simulation%integrator
      if (.not. r%has(g, "substeps")) s%substeps = b%simulation%substeps
      if (.not. r%has(g, "base_seed")) s%base_seed = b%simulation%seed
    end associate
  end subroutine complete_defaults

  !> Checks across the sweep and its base deck.
  !> Each message names the line of the &sweep key involved.
  subroutine check_sweep(s, deck, error)
    !> The sweep's settings.
    type(sweep_config), intent(in) :: s
    !> The parsed sweep deck (for the keys' lines).
    type(nml_deck), intent(in) :: deck
    !> Set when the sweep and its base deck disagree.
    type(error_type), allocatable, intent(out) :: error
    integer :: i
    class(scene_type), allocatable :: scene
    call new_scene(s%base%simulation%scene, scene, error)
    if (allocated(error)) return
    if (.not. scene%has_boat()) then
      call fatal_error(error, key_at(deck, "sweep", ["base_deck"])//"&sweep: base deck '"// &
                       s%base_deck// &
                       "' has scene '"//s%base%simulation%scene//"'; sweeps run the boat "// &
                       "scenes 'hanging_boat', 'lowering' and 'launch'")
      return
    end if
    do i = 1, size(s%dts)
      if (s%dts(i) > s%base%simulation%output_interval .or. &
          s%dts(i) > s%base%simulation%t_end) then
        call fatal_error(error, key_at(deck, "sweep", ["dts"])//"&sweep: dts = "// &
                         fmt_real(s%dts(i))// &
                         " s must be <= the base deck's output_interval ("// &
                         fmt_real(s%base%simulation%output_interval)//" s) and t_end")
        return
      end if
    end do
    call check_adaptive(s, deck, error)
    if (allocated(error)) return
    call check_case_count(s, deck, error)
    if (allocated(error)) return
    if (s%has_clearances .and. .not. scene%on_davit() .and. .not. s%base%slings%attached) then
      call fatal_error(error, key_at(deck, "sweep", ["clearances_b"])// &
                       "&sweep: clearances_b needs a hanging boat "// &
                       "(the base deck's slings are detached)")
    end if
  end subroutine check_sweep

  !> The adaptive keys agree: the cap holds the first round, and without a target the cap
  !> and batch would be silently ignored.
  subroutine check_adaptive(s, deck, error)
    !> The sweep's settings.
    type(sweep_config), intent(in) :: s
    !> The parsed sweep deck (for the keys' lines).
    type(nml_deck), intent(in) :: deck
    !> Set when the adaptive keys disagree.
    type(error_type), allocatable, intent(out) :: error
    if (s%target_halfwidth <= 0.0_wp .and. s%max_realisations /= s%realisations) then
      call fatal_error(error, key_at(deck, "sweep", ["max_realisations"])// &
                       "&sweep: max_realisations needs target_halfwidth > 0 (adaptive "// &
                       "realisations); without it every cell runs realisations")
    else if (s%target_halfwidth <= 0.0_wp .and. s%realisation_batch /= s%realisations) then
      call fatal_error(error, key_at(deck, "sweep", ["realisation_batch"])// &
                       "&sweep: realisation_batch needs target_halfwidth > 0 (adaptive "// &
                       "realisations)")
    else if (s%max_realisations < s%realisations) then
      call fatal_error(error, key_at(deck, "sweep", ["max_realisations"])// &
                       "&sweep: max_realisations = "//int_to_str(s%max_realisations)// &
                       " must be >= realisations = "//int_to_str(s%realisations))
    end if
  end subroutine check_adaptive

  !> The number of cases: the product of the lists' lengths (realisations: the cap per
  !> cell), in 64 bits and saturating at huge(1_i8) (the product reaches 8e21).
  pure integer(i8) function case_count(s) result(n)
    !> The sweep's settings.
    type(sweep_config), intent(in) :: s
    integer(i8) :: sizes(9)
    integer :: k
    sizes = list_sizes(s)
    n = 1
    do k = 1, size(sizes)
      if (n > huge(n)/max(sizes(k), 1_i8)) then
        n = huge(n)
        return
      end if
      n = n*sizes(k)
    end do
  end function case_count

  !> The lengths of the swept lists, in the mixed radix of the case order (davit_sweep_cases).
  pure function list_sizes(s) result(sizes)
    !> The sweep's settings.
    type(sweep_config), intent(in) :: s
    integer(i8) :: sizes(9)
    sizes = int([size(s%wave_types), size(s%levels), size(s%heights), size(s%periods), &
                 size(s%winds), size(s%angles_deg), size(s%clearances_b), size(s%dts), &
                 s%max_realisations], i8)
  end function list_sizes

  !> Refuse a case list beyond max_cases or the memory limit (the base deck's
  !> &simulation max_memory), before anything of its size is made.
  subroutine check_case_count(s, deck, error)
    !> The sweep's settings.
    type(sweep_config), intent(in) :: s
    !> The parsed sweep deck (for the keys' lines).
    type(nml_deck), intent(in) :: deck
    !> Set when the sweep has too many cases or needs too much memory.
    type(error_type), allocatable, intent(out) :: error
    character(len=*), parameter :: keys(9) = [character(len=16) :: "wave_types", "levels", &
      "heights", "periods", "wind", "angles_deg", "clearances_b", "dts", "max_realisations"]
    integer(i8) :: n
    real(wp) :: bytes, limit
    n = case_count(s)
    bytes = real(n, wp)*bytes_per_case
    limit = memory_limit(s%base)
    if (n <= max_cases .and. bytes <= limit) return
    if (n > max_cases) then
      call fatal_error(error, key_at(deck, "sweep", [keys, "realisations    "])// &
                       "&sweep: "//count_text(s, n)//" exceed the cap of "// &
                       int_text(max_cases)//" cases; sweep fewer values or split the "// &
                       "sweep into several decks")
    else
      call fatal_error(error, key_at(deck, "sweep", [keys, "realisations    "])// &
                       "&sweep: "//count_text(s, n)//" would hold about "// &
                       fmt_fixed(bytes/1024.0_wp**3, 2)//" GiB, more than the memory "// &
                       "limit of "//fmt_fixed(limit/1024.0_wp**3, 2)//" GiB (the base "// &
                       "deck's &simulation max_memory, 0: 80 % of physical memory)")
    end if
  end subroutine check_case_count

  !> "N cases (a x b x ...)": the count and the lengths of the lists longer than one.
  function count_text(s, n) result(text)
    !> The sweep's settings.
    type(sweep_config), intent(in) :: s
    !> The number of cases.
    integer(i8), intent(in) :: n
    character(len=:), allocatable :: text, factors
    character(len=*), parameter :: names(9) = [character(len=12) :: "wave types", "levels", &
      "heights", "periods", "wind values", "angles", "clearances", "dts", "realisations"]
    integer(i8) :: sizes(9)
    integer :: k
    sizes = list_sizes(s)
    text = int_text(n)//" cases"
    if (n == huge(n)) text = "more than "//int_text(n)//" cases"
    factors = ""
    do k = 1, size(sizes)
      if (sizes(k) <= 1) cycle
      if (len(factors) > 0) factors = factors//" x "
      factors = factors//int_text(sizes(k))//" "//trim(names(k))
    end do
    if (len(factors) > 0) text = text//" ("//factors//")"
  end function count_text

  !> The base deck: in the sweep deck's folder, else in a DAVIT_PATH folder
  !> (davit_io_search_path); a miss names the sweep deck's line and every folder searched.
  subroutine find_base_deck(deck, sweep, error)
    !> The parsed sweep deck (for the line of the base key).
    type(nml_deck), intent(in) :: deck
    !> The sweep's settings, receiving the base deck's path.
    type(sweep_config), intent(inout) :: sweep
    !> Set when the base deck is found in no folder searched.
    type(error_type), allocatable, intent(out) :: error
    character(len=:), allocatable :: searched
    logical :: found
    call find_file(folder_of(deck%filename), sweep%base_deck, sweep%base_path, found, &
                   searched)
    if (.not. found) call fatal_error(error, key_at(deck, "sweep", ["base_deck"])// &
      "&sweep: base_deck = '"//sweep%base_deck//"': no such file in "//searched// &
      " (the sweep deck's folder, then DAVIT_PATH)")
  end subroutine find_base_deck

end module davit_sweep_keys
