!> Deck keys of the sea's level of detail for its kinematics (group "sea"): the exact
!> component sum of eq. (43), or the interpolated grid of davit_sea_wave_grid.
module davit_io_sea_keys
  use davit_kinds, only: wp
  use davit_io_deck_reader, only: deck_reader_type
  implicit none
  private
  public :: sea_grid_config, read_sea_grid

  !> 'sum' (exact, the reference) or 'grid'; the grid's spacing [m] (also between its depth
  !> levels), time step [s], margin around the boat [m] and deepest level [m].
  type :: sea_grid_config
    !> 'sum' (exact) or 'grid' (interpolated from a precomputed grid).
    character(len=:), allocatable :: kinematics
    !> Grid spacing [m], time step [s], margin around the boat [m], deepest level [m].
    real(wp) :: spacing = 1.0_wp, time_step = 0.1_wp, margin = 3.0_wp, depth = 3.0_wp
  end type sea_grid_config

contains

  subroutine read_sea_grid(r, s)
    !> The deck's reader, positioned at the &sea group.
    type(deck_reader_type), intent(inout) :: r
    !> The grid's values, defaults in, the deck's read over them.
    type(sea_grid_config), intent(inout) :: s
    character(len=*), parameter :: g = "sea"
    call r%choice(g, "kinematics", s%kinematics, "sum", [character(len=4) :: "sum", "grid"], &
                  "Irregular seas, the water the boat's strips and surface watch read: "// &
                  "'sum' = the exact component sum (eq. 43, the reference); 'grid' = "// &
                  "precomputed on an earth-fixed grid around the boat and interpolated "// &
                  "(Catmull-Rom in x, y, t and depth; exact sum outside the grid). The "// &
                  "ship's excitation, the boat's diffraction and the pressure integrals "// &
                  "over the sections keep the exact sum.")
    call r%real(g, "grid_spacing", s%spacing, 1.0_wp, 0.0_wp, 10.0_wp, "m", &
                "kinematics = 'grid': horizontal node spacing, and spacing of the depth "// &
                "levels.", lo_open=.true.)
    call r%real(g, "grid_time_step", s%time_step, 0.1_wp, 0.0_wp, 1.0_wp, "s", &
                "kinematics = 'grid': time between samples.", lo_open=.true.)
    call r%real(g, "grid_margin", s%margin, 3.0_wp, 0.0_wp, 50.0_wp, "m", &
                "kinematics = 'grid': margin of the grid around the boat's footprint "// &
                "(placed anew, the nodes it shares kept, when the boat leaves it).")
    call r%real(g, "grid_depth", s%depth, 3.0_wp, 0.0_wp, 20.0_wp, "m", &
                "kinematics = 'grid': deepest stretched depth of the velocity levels "// &
                "(deeper points take the exact sum).", lo_open=.true.)
  end subroutine read_sea_grid

end module davit_io_sea_keys
