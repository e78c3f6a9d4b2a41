!> Deck reading: a table of malformed decks, each with the message it must produce, and a
!> well-formed deck using the full namelist syntax.
module test_deck
  use davit_kinds, only: wp
  use davit_error, only: error_type
  use davit_io_config, only: config_type, parse_config, read_config, document_keys
  use davit_io_deck_reader, only: key_doc
  use davit_io_namelist_entries, only: nml_entry, str_hash, probe, rehash
  use harness, only: suite_type, case_state, new_case, check, check_true
  implicit none
  private
  public :: collect_deck

  character(len=*), parameter :: nl = new_line("a")

  type :: bad_deck
    character(len=:), allocatable :: text, expected
  end type bad_deck

contains

  function collect_deck() result(suite)
    type(suite_type) :: suite
    suite%name = "deck"
    suite%cases = [new_case("malformed_decks_table", malformed_decks), &
                   new_case("number_forms", number_forms), &
                   new_case("missing_file", missing_file), &
                   new_case("full_syntax", full_syntax), &
                   new_case("defaults_documented_and_valid", defaults_documented), &
                   new_case("contact_side_from_beam", contact_side_from_beam), &
                   new_case("entry_hash_fnv1a_and_probing", entry_hash)]
  end function collect_deck

  function bad(text, expected) result(b)
    character(len=*), intent(in) :: text, expected
    type(bad_deck) :: b
    b%text = text
    b%expected = expected
  end function bad

  subroutine malformed_decks(state)
    type(case_state), intent(inout) :: state
    type(bad_deck), allocatable :: table(:)
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    integer :: i
    table = [ &
      bad("&simulation"//nl//"  dtt = 0.001"//nl//"/", &
          "t.nml:2: &simulation: unknown key 'dtt'; allowed keys: t_end after_release dt "// &
          "dt_contact wave_update scene integrator"), &
      bad("&simulation dt = 'abc' /", &
          "t.nml:1: &simulation: dt = 'abc': not a real number; allowed: 0 < dt <= 1 [s]"), &
      bad("&simulation"//nl//nl//" dt = -1.0 /", &
          "t.nml:3: &simulation: dt = -1.0: out of range; allowed: 0 < dt <= 1 [s]"), &
      bad("&simulaton t_end = 1 /", &
          "t.nml:1: unknown namelist group &simulaton; allowed groups: &simulation, "// &
          "&boat, &slings"), &
      bad("&boat mass = 1.0"//nl//"! no slash", "t.nml:1: group &boat is not closed"), &
      bad("&boat position = 1.0, 2.0 /", &
          "&boat: position = 1.0, 2.0: expects 3 real value(s), got 2"), &
      bad("&simulation integrator = 'euler' /", &
          "&simulation: integrator = 'euler': unknown choice; allowed: one of 'rk4'"), &
      bad("&slings length = 2.0,"//nl//" length = 3.0 /", &
          "t.nml:2: &slings: length is given twice (first at line 1)"), &
      bad("&simulation seed = 1.5 /", "&simulation: seed = 1.5: not an integer"), &
      bad("t_end = 3"//nl//"&simulation /", "t.nml:1: text outside a namelist group"), &
      bad("&simulation dt = 0.01, output_interval = 0.001 /", &
          "&simulation: output_interval = 0.001 must be >= dt = 0.01"), &
      bad("&simulation"//nl//" dt = /", "t.nml:2: &simulation: dt has no value"), &
      bad("&boat mass = 0 /", "mass = 0: out of range; allowed: 0 < mass <= 1e6 [kg]"), &
      bad("&slings damping = NaN /", "&slings: damping = NaN: not a real number"), &
      bad("&simulation fixed_step = 1 /", &
          "&simulation: fixed_step = 1: not a logical; allowed: .true. or .false."), &
      ! expressions and malformed numbers that list-directed READ would misread
      bad("&simulation dt = 1-3 /", &
          "t.nml:1: &simulation: dt = 1-3: not a real number; allowed: 0 < dt <= 1 [s]"), &
      bad("&boat"//nl//" position = 0.0, 13.3, -15-1 /", &
          "t.nml:2: &boat: position = 0.0, 13.3, -15-1: item 3 ('-15-1') is not a real number"), &
      bad("&simulation dt = 1e /", "t.nml:1: &simulation: dt = 1e: not a real number"), &
      bad("&simulation dt = 1..2 /", "t.nml:1: &simulation: dt = 1..2: not a real number"), &
      bad("&simulation dt = 0x10 /", "t.nml:1: &simulation: dt = 0x10: not a real number"), &
      bad("&simulation dt = 1e-3e1 /", "&simulation: dt = 1e-3e1: not a real number"), &
      bad("&simulation dt = +-1e-3 /", "&simulation: dt = +-1e-3: not a real number"), &
      bad("&simulation dt = . /", "&simulation: dt = .: not a real number"), &
      bad("&simulation dt = 2*1e-3 /", "&simulation: dt = 2*1e-3: not a real number"), &
      bad("&simulation dt = Inf /", "&simulation: dt = Inf: not a real number"), &
      bad("&simulation seed = 1-3 /", "&simulation: seed = 1-3: not an integer"), &
      bad("&simulation seed = +-3 /", "&simulation: seed = +-3: not an integer"), &
      bad("&simulation seed = 1e3 /", "&simulation: seed = 1e3: not an integer"), &
      bad("&simulation fixed_step = .true.x /", "fixed_step = .true.x: not a logical"), &
      ! cross-key checks name the line of a key involved
      bad("&simulation"//nl//" dt = 0.5"//nl//"/", &
          "t.nml:2: &simulation: output_interval = 0.01 must be >= dt = 0.5"), &
      bad("&simulation"//nl//" dt = 0.01,"//nl//" output_interval = 0.001 /", &
          "t.nml:3: &simulation: output_interval = 0.001 must be >= dt = 0.01"), &
      bad("&sea"//nl//nl//" probes_x = 1.0, 2.0, probes_y = 3.0 /", &
          "t.nml:3: &sea: probes_x and probes_y must have the same number of values"), &
      bad("&slings"//nl//" hook_aft = 4.6, 0.0, -1.55 /", &
          "t.nml:2: &slings: hook_fore and hook_aft must differ") ]
    do i = 1, size(table)
      call parse_config("t.nml", table(i)%text, cfg, error)
      call check_true(state, allocated(error), "deck "//table(i)%text//" must be rejected")
      if (.not. allocated(error)) cycle
      call check_true(state, index(error%message, table(i)%expected) > 0, &
                      "message '"//error%message//"' must contain '"//table(i)%expected//"'")
    end do
  end subroutine malformed_decks

  !> &contact side_y defaults to half the &ship beam plus 0.1 m: the paper's y1 = 10.5 m
  !> (III.B) for its 20.8 m beam, 15.1 m for a 30 m one; a deck's side_y wins; a
  !> restitution outside (0, 1] is refused naming the group, key and range.
  subroutine contact_side_from_beam(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    call parse_config("t.nml", "", cfg, error)
    call check_true(state, .not. allocated(error), "empty deck accepted")
    call check(state, cfg%contact%side_y, 10.5_wp, "side_y of the paper's ship", &
               abs_tol=1.0e-12_wp)
    call parse_config("t.nml", "&ship beam = 30.0 /", cfg, error)
    call check(state, cfg%contact%side_y, 15.1_wp, "side_y, 30 m beam", abs_tol=1.0e-12_wp)
    call parse_config("t.nml", "&ship beam = 30.0 /"//nl//"&contact side_y = 9.0 /", cfg, &
                      error)
    call check(state, cfg%contact%side_y, 9.0_wp, "side_y from the deck", abs_tol=0.0_wp)
    call parse_config("t.nml", "&contact restitution = 1.5 /", cfg, error)
    call check_true(state, allocated(error), "restitution 1.5 refused")
    if (allocated(error)) call check_true(state, index(error%message, "&contact: "// &
      "restitution = 1.5: out of range; allowed: 0 < restitution <= 1") > 0, error%message)
  end subroutine contact_side_from_beam

  !> The real forms Fortran and namelists write are all read exactly.
  subroutine number_forms(state)
    type(case_state), intent(inout) :: state
    character(len=12), parameter :: forms(9) = [character(len=12) :: "1e-3", "1.0e-3", &
      "1.0d-3", "1.0D-3", ".1e-2", "1.e-3", "+1E-3", "0.001", "1e-03"]
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    integer :: i
    do i = 1, size(forms)
      call parse_config("t.nml", "&simulation dt = "//trim(forms(i))//", seed = +7, "// &
                        "fixed_step = T, t_end = 5. /", cfg, error)
      call check_true(state, .not. allocated(error), "dt = "//trim(forms(i))//" accepted")
      if (allocated(error)) cycle
      call check(state, cfg%simulation%dt, 1.0e-3_wp, "dt = "//trim(forms(i)), abs_tol=0.0_wp)
      call check_true(state, cfg%simulation%seed == 7, "seed = +7")
    end do
  end subroutine number_forms

  subroutine missing_file(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    call read_config("no/such/deck.nml", cfg, error)
    call check_true(state, allocated(error), "missing deck must be an error")
    if (allocated(error)) call check_true(state, error%message == &
      "cannot open input deck 'no/such/deck.nml': no such file", error%message)
  end subroutine missing_file

  !> Comments, several groups, multi-line arrays, upper case, '&end', double quotes.
  subroutine full_syntax(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    character(len=*), parameter :: text = &
      "! a comment line"//nl// &
      "&SIMULATION  T_END = 12.5, dt = 2e-3 ! trailing comment"//nl// &
      "   integrator = ""RK4"", output_interval=0.05 /"//nl// &
      "&boat"//nl//"  position = 1.0,"//nl//"  2.0  -3.5"//nl//"  mass = 4.2d3"//nl//"&end"
    call parse_config("t.nml", text, cfg, error)
    call check_true(state, .not. allocated(error), "valid deck accepted")
    if (allocated(error)) then
      call check_true(state, .false., error%message)
      return
    end if
    call check(state, cfg%simulation%t_end, 12.5_wp, "t_end", abs_tol=0.0_wp)
    call check(state, cfg%simulation%dt, 2.0e-3_wp, "dt", abs_tol=0.0_wp)
    call check(state, cfg%simulation%output_interval, 0.05_wp, "output_interval", abs_tol=0.0_wp)
    call check_true(state, cfg%simulation%integrator == "rk4", "integrator")
    call check(state, cfg%boat%position(3), -3.5_wp, "position(3)", abs_tol=0.0_wp)
    call check(state, cfg%boat%mass, 4200.0_wp, "mass", abs_tol=0.0_wp)
    call check(state, cfg%boat%inertia(1), 25020.0_wp, "default inertia", abs_tol=0.0_wp)
    call check_true(state, index(cfg%deck_text, "! a comment line") == 1, "deck text kept")
  end subroutine full_syntax

  !> Every key documented with a default, range, units and a description.
  subroutine defaults_documented(state)
    type(case_state), intent(inout) :: state
    type(key_doc), allocatable :: docs(:)
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    integer :: i
    call document_keys(docs)
    call check_true(state, size(docs) >= 19, "at least 19 documented keys")
    do i = 1, size(docs)
      call check_true(state, len(docs(i)%default) > 0 .and. len(docs(i)%allowed) > 0 .and. &
                      len(docs(i)%units) > 0 .and. len(docs(i)%description) > 10, &
                      "documentation of "//docs(i)%group//"/"//docs(i)%key)
    end do
    call parse_config("empty.nml", "", cfg, error)
    call check_true(state, .not. allocated(error), "an empty deck (all defaults) is valid")
  end subroutine defaults_documented

  !> The deck's hash is 32-bit FNV-1a (Fowler, Noll, Vo) of group, a NUL byte and key, kept
  !> to 31 bits. Expected values from an independent FNV-1a (Python, offset basis 2166136261,
  !> prime 16777619) that reproduces the published vectors "" -> 0x811c9dc5, "a" ->
  !> 0xe40c292c, "foobar" -> 0xbf9cf968: one NUL byte -> 0x050c5d1f = 84696351, and so on.
  !> Linear probing after a rehash finds every entry at its index and a missing key nowhere,
  !> with an empty slot for it.
  subroutine entry_hash(state)
    type(case_state), intent(inout) :: state
    type(nml_entry), allocatable :: entries(:)
    integer, allocatable :: slot(:)
    character(len=10), parameter :: groups(5) = [character(len=10) :: "boat", "sea", &
                                                 "simulation", "boat", "sea"]
    character(len=8), parameter :: keys(5) = [character(len=8) :: "mass", "height", "t_end", &
                                              "beam", "period"]
    integer :: k, h
    call check_true(state, str_hash("", "") == 84696351, "hash of one NUL byte")
    call check_true(state, str_hash("boat", "mass") == 1492314453, "hash of boat/mass")
    call check_true(state, str_hash("sea", "height") == 1912905879, "hash of sea/height")
    call check_true(state, str_hash("simulation", "t_end") == 1376828948, &
                    "hash of simulation/t_end")
    allocate (entries(size(keys)), slot(1))
    do k = 1, size(keys)
      entries(k)%group = trim(groups(k))
      entries(k)%key = trim(keys(k))
    end do
    call rehash(slot, entries, 5)
    call check_true(state, size(slot) == 8, "slots rounded up to a power of two")
    do k = 1, size(keys)
      call check_true(state, probe(slot, entries, trim(groups(k)), trim(keys(k)), h) == k, &
                      "found: "//trim(groups(k))//"/"//trim(keys(k)))
    end do
    call check_true(state, probe(slot, entries, "boat", "height", h) == 0, "missing key")
    call check_true(state, slot(h) == 0, "missing key: an empty slot")
  end subroutine entry_hash

end module test_deck
