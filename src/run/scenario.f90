!> The scenario a run actually simulates, in words: printed at the start of `davit run` and
!> stored as attributes of /scenario in every run file (sweep series files too). A deck
!> copied and edited keeps whatever it pins, so the run states the values it uses and where
!> each came from (the deck, a level preset, a sweep), and the directions with their
!> convention: direction_deg is the direction the waves (or the wind) travel towards,
!> measured from N1 towards N2; the ship heads along N1 at heading_deg = 0 and its s2 axis
!> points to starboard, so 0 deg is a following sea, 90 deg comes from port, 180 deg is a
!> head sea and 270 deg comes from starboard. The run's root attributes (version, deck,
!> integrator statistics, completion) are written here with it.
module davit_run_scenario
  use davit_kinds, only: wp, i8, pi, davit_version
  use davit_error, only: error_type
  use davit_io_config, only: config_type
  use davit_io_hdf5_writer, only: h5_writer_type
  use davit_run_run_summary, only: run_summary
  use davit_run_scene, only: scene_type, new_scene
  use davit_sea_spectrum, only: spectrum_m0, spectrum_peak_omega
  implicit none
  private
  public :: scenario_text, write_scenario, write_root_attributes, coming_from

  character(len=*), parameter :: convention = "direction travelled towards, from N1 "// &
    "towards N2 (the ship heads along N1 at heading_deg 0; N2 is to starboard): "// &
    "0 = following, 90 = from port, 180 = head, 270 = from starboard"

contains

  !> davit_version, input file and deck text, seed, integrator statistics, completion;
  !> and /scenario (what the run simulated, davit_run_scenario) unless `scenario` is false
  !> (the RAO runs, which sweep their own waves).
  subroutine write_root_attributes(w, cfg, summary, integrator, run_error, scenario)
    !> The open output file.
    type(h5_writer_type), intent(inout) :: w
    !> The run's configuration.
    type(config_type), intent(in) :: cfg
    !> The run's statistics.
    type(run_summary), intent(in) :: summary
    !> Name of the integrator used.
    character(len=*), intent(in) :: integrator
    !> Why the run ended early (unallocated: it did not).
    type(error_type), allocatable, intent(in) :: run_error
    !> Write /scenario (default: yes).
    logical, intent(in), optional :: scenario
    call w%attr_str("/", "davit_version", davit_version)
    call w%attr_str("/", "input_file", cfg%filename)
    call w%attr_str("/", "input_namelist", cfg%deck_text)
    call w%attr_str("/", "scene", cfg%simulation%scene)
    call w%attr_int("/", "seed", int(cfg%simulation%seed, i8))
    call w%attr_str("/", "integrator", integrator)
    call w%attr_real("/", "dt", cfg%simulation%dt)
    call w%attr_int("/", "steps", summary%steps)
    call w%attr_int("/", "rhs_evaluations", summary%rhs_evaluations)
    call w%attr_real("/", "wall_time", summary%wall_time)
    call w%attr_real("/", "worst_step_wall", summary%worst_step%wall)
    call w%attr_real("/", "worst_step_at", summary%worst_step%at)
    call w%attr_real("/", "worst_interval_wall", summary%worst_interval%wall)
    call w%attr_real("/", "worst_interval_at", summary%worst_interval%at)
    call w%attr_int("/", "complete", merge(1_i8, 0_i8, summary%complete))
    if (allocated(run_error)) then
      call w%attr_str("/", "status", run_error%message)
    else
      call w%attr_str("/", "status", "ok")
    end if
    if (.not. present(scenario)) then
      call write_scenario(w, cfg)
    else if (scenario) then
      call write_scenario(w, cfg)
    end if
  end subroutine write_root_attributes

  !> The scenario as a short block of lines (no trailing newline).
  function scenario_text(cfg) result(text)
    !> The run's configuration.
    type(config_type), intent(in) :: cfg
    character(len=:), allocatable :: text
    character(len=*), parameter :: nl = new_line("a")
    class(scene_type), allocatable :: scene
    type(error_type), allocatable :: error
    logical :: boat, wind
    ! the deck reader admits only the scenes; were it another, the text says no boat
    call new_scene(cfg%simulation%scene, scene, error)
    boat = .false.
    wind = .true.
    if (allocated(scene)) then
      boat = scene%has_boat()
      wind = scene%feels_wind()
    end if
    text = "scenario of '"//cfg%filename//"' (scene "//cfg%simulation%scene//")"//nl// &
           "sea:   "//sea_words(cfg)
    if (cfg%sea%wave_type /= "calm") text = text//nl//"waves: travel towards "// &
      fixed(deg(cfg%sea%direction), 1)//" deg (from N1 towards N2; 0 = following, 90 = "// &
      "from port, 180 = head): "//coming_from(relative(cfg, cfg%sea%direction))// &
      boat_side(cfg, boat)
    text = text//nl//"wind:  "//wind_words(cfg, wind)//nl// &
           "model: ship "//cfg%ship%model//", heading "//fixed(deg(cfg%ship%heading), 1)// &
           " deg; boat water model "//cfg%boat%water_model//"; integrator "// &
           cfg%simulation%integrator//", dt = "//trimmed(cfg%simulation%dt)//" s"
    if (cfg%simulation%dt_contact > 0.0_wp) text = text//" (dt_contact = "// &
      trimmed(cfg%simulation%dt_contact)//" s)"
  end function scenario_text

  !> /scenario: the values used, their sources and the conventions, one attribute each,
  !> plus the printed block (`summary`).
  subroutine write_scenario(w, cfg)
    !> The open output file.
    type(h5_writer_type), intent(inout) :: w
    !> The run's configuration.
    type(config_type), intent(in) :: cfg
    character(len=*), parameter :: g = "scenario"
    call w%group(g)
    call w%attr_str(g, "summary", scenario_text(cfg))
    call w%attr_str(g, "scene", cfg%simulation%scene)
    call w%attr_int(g, "sea_level", int(cfg%sea%level, i8))
    call w%attr_str(g, "wave_type", cfg%sea%wave_type)
    call w%attr_real(g, "wave_height_m", cfg%sea%height)
    call w%attr_str(g, "wave_height_source", cfg%sea%height_source)
    call w%attr_real(g, "wave_period_s", period(cfg))
    call w%attr_str(g, "wave_period_kind", period_kind(cfg))
    call w%attr_str(g, "wave_period_source", period_source(cfg))
    call w%attr_real(g, "wave_direction_deg", deg(cfg%sea%direction))
    call w%attr_str(g, "wave_direction_convention", convention)
    call w%attr_str(g, "waves_from", coming_from(relative(cfg, cfg%sea%direction)))
    call w%attr_real(g, "wind_speed_m_s", cfg%wind%speed)
    call w%attr_str(g, "wind_speed_source", cfg%wind%speed_source)
    call w%attr_real(g, "wind_direction_deg", deg(cfg%wind%direction))
    call w%attr_str(g, "wind_direction_source", cfg%wind%direction_source)
    call w%attr_str(g, "wind_from", coming_from(relative(cfg, cfg%wind%direction)))
    call w%attr_real(g, "ship_heading_deg", deg(cfg%ship%heading))
    call w%attr_str(g, "ship_model", cfg%ship%model)
    call w%attr_str(g, "boat_water_model", cfg%boat%water_model)
    call w%attr_str(g, "integrator", cfg%simulation%integrator)
    call w%attr_real(g, "dt_s", cfg%simulation%dt)
  end subroutine write_scenario

  function sea_words(cfg) result(text)
    type(config_type), intent(in) :: cfg
    character(len=:), allocatable :: text
    text = "level "//fixed(real(cfg%sea%level, wp), 0)//", "
    select case (cfg%sea%wave_type)
    case ("calm")
      text = text//"calm water (wave_type = 'calm')"
    case ("irregular")
      text = text//"irregular waves, H = "//fixed(cfg%sea%height, 3)//" m (Hs = "// &
             fixed(4.0_wp*sqrt(spectrum_m0(cfg%sea%height)), 3)//" m; "// &
             cfg%sea%height_source//"), Tp = "//fixed(period(cfg), 2)//" s ("// &
             period_source(cfg)//")"
    case default
      text = text//"regular "//cfg%sea%wave_type//" waves, H = "// &
             fixed(cfg%sea%height, 3)//" m ("//cfg%sea%height_source//"), T = "// &
             fixed(period(cfg), 2)//" s ("//period_source(cfg)//")"
    end select
  end function sea_words

  !> The wind in words; `wind`: whether the scene feels it.
  function wind_words(cfg, wind) result(text)
    type(config_type), intent(in) :: cfg
    logical, intent(in) :: wind
    character(len=:), allocatable :: text
    if (.not. wind) then
      text = "not used by the '"//cfg%simulation%scene//"' scene"
    else if (cfg%wind%speed <= 0.0_wp) then
      text = "none, 0 m/s ("//cfg%wind%speed_source//")"
    else
      text = fixed(cfg%wind%speed, 2)//" m/s ("//cfg%wind%speed_source// &
             "), blowing towards "//fixed(deg(cfg%wind%direction), 1)//" deg ("// &
             cfg%wind%direction_source//"): "//coming_from(relative(cfg, cfg%wind%direction))
    end if
  end function wind_words

  !> The wave period the sea uses [s]: an irregular sea's is the spectrum's peak period.
  real(wp) function period(cfg)
    type(config_type), intent(in) :: cfg
    period = cfg%sea%period
    if (cfg%sea%wave_type == "irregular") period = 2.0_wp*pi/spectrum_peak_omega(cfg%sea%height)
  end function period

  function period_kind(cfg) result(text)
    type(config_type), intent(in) :: cfg
    character(len=:), allocatable :: text
    text = merge("peak period Tp", "period T      ", cfg%sea%wave_type == "irregular")
    text = trim(text)
  end function period_kind

  function period_source(cfg) result(text)
    type(config_type), intent(in) :: cfg
    character(len=:), allocatable :: text
    text = cfg%sea%period_source
    if (cfg%sea%wave_type == "irregular") text = "eq. 44's peak for H"
  end function period_source

  !> ", the boat hangs on the starboard side" for scenes with a boat (`boat`) at the ship's
  !> side.
  function boat_side(cfg, boat) result(text)
    type(config_type), intent(in) :: cfg
    logical, intent(in) :: boat
    character(len=:), allocatable :: text
    text = ""
    if (.not. boat) return
    text = "; the boat hangs on the "//trim(merge("starboard", "port     ", &
           cfg%contact%side_y >= 0.0_wp))//" side"
  end function boat_side

  !> Direction `direction` [rad] (travelled towards, from N1) relative to the ship's bow [deg].
  real(wp) function relative(cfg, direction)
    type(config_type), intent(in) :: cfg
    real(wp), intent(in) :: direction
    relative = deg(direction - cfg%ship%heading)
  end function relative

  !> Where something travelling towards `towards_deg` (relative to the bow, towards
  !> starboard) comes from, in a seafarer's words (eight sectors of 45 deg).
  function coming_from(towards_deg) result(text)
    !> Direction of travel relative to the bow, towards starboard [deg].
    real(wp), intent(in) :: towards_deg
    character(len=:), allocatable :: text
    character(len=*), parameter :: names(0:7) = [character(len=38) :: &
      "from ahead (head seas)", "from the starboard bow", "from starboard (on the beam)", &
      "from the starboard quarter", "from astern (following seas)", &
      "from the port quarter", "from port (on the beam)", "from the port bow"]
    real(wp) :: from
    from = modulo(towards_deg + 180.0_wp, 360.0_wp)
    text = trim(names(modulo(nint(from/45.0_wp), 8)))
  end function coming_from

  elemental real(wp) function deg(radians)
    real(wp), intent(in) :: radians
    deg = radians*180.0_wp/pi
  end function deg

  !> x with `decimals` digits after the point (none and no point for 0).
  function fixed(x, decimals) result(text)
    real(wp), intent(in) :: x
    integer, intent(in) :: decimals
    character(len=:), allocatable :: text
    character(len=32) :: buf, form
    write (form, "(a,i0,a)") "(f0.", decimals, ")"
    if (decimals == 0) then
      write (buf, "(i0)") nint(x)
    else
      write (buf, form) x
    end if
    text = trim(buf)
    if (text(1:1) == ".") text = "0"//text
    if (len(text) > 1) then
      if (text(1:2) == "-.") text = "-0"//text(2:)
    end if
  end function fixed

  !> x in at most 8 significant decimals, trailing zeros dropped (1e-3: "0.001").
  function trimmed(x) result(text)
    real(wp), intent(in) :: x
    character(len=:), allocatable :: text
    character(len=32) :: buf
    if (abs(x) >= 1.0e-6_wp .and. abs(x) < 1.0e6_wp) then
      text = fixed(x, 9)
      do while (text(len(text):len(text)) == "0")
        text = text(1:len(text) - 1)
      end do
      if (text(len(text):len(text)) == ".") text = text(1:len(text) - 1)
    else
      write (buf, "(es12.4)") x
      text = trim(adjustl(buf))
    end if
  end function trimmed

end module davit_run_scenario
