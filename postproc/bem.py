"""Ship hydrodynamics from a BEM database (Capytaine).

  python -m postproc.bem build [--hull box|ship|lifeboat | --mesh FILE] [--panels N]
                               [--omegas W ...] [--headings-deg B ...] [-o input/ship_bem.nc]
      mesh a hull, solve radiation (6 DOF) and diffraction with Capytaine, fit the radiation
      memory as state-space models, and write the database: Capytaine's dataset plus the
      davit_ variables (postproc.bem_db; davit's frame and conventions).
      Default: the paper's equivalent box l = sqrt(C_b) L_wl = 107.65 m, B = 20.8 m,
      d = 4.4 m, ~2,000 panels + lid, CG midship on the waterline (KG = d), mass = displaced
      mass, gyradii 0.38 B (roll) and 32.6375 m (pitch, yaw); 48 frequencies 0.1..2 rad/s
      (+ 0 and inf), headings 0..360 deg every 15 deg.
      --hull ship: L_pp 126 m, B 20.8 m, T 4.4 m, C_b 0.68 (postproc.bem_mesh.ship_hull).
      --hull lifeboat: the paper's III.B boat with review G25's plan shape
      b(x) = B (1 - |2x/L|^4.3), L 11.5 m, B 2.8 m, vertical sides, flat bottom, draught
      0.3175 m, CG 1.1 m above the keel, mass 8,500 kg, inertia 25,020 / 51,745 /
      51,745 kg m^2 (postproc.bem_mesh.lifeboat_hull); 87 frequencies 0.3..8 rad/s
      (postproc.bem_build.lifeboat_omegas), headings every 15 deg; -o input/boat_bem.nc.
      --mesh FILE: any mesh Capytaine or meshio reads, in Capytaine's frame (x forward,
      y port, z up, waterline z = 0); give --cg (and --mesh-format nemoh for .dat).
      Checked first (postproc.bem_checks): inward normals flipped with a message; a hole
      below the waterline, no waterplane, or GM_T or GM_L <= 0 refused (exit 1). Gyradii
      default to 0.38 B (roll) and 0.25 L (pitch, yaw) of the hull. Radiation pairs that
      the hull's symmetry makes zero are not fitted; the diagonal fits are passive, and the
      fitted damping matrix is made positive semi-definite by residue perturbation
      (postproc.bem_passive; --no-passive-matrix: not).

  python -m postproc.bem rao DATABASE [--roll-damping 0.05] [--gm GM] [--omegas W ...]
                             [--headings-deg B ...] [-o FILE.h5|FILE.csv]
      6-DOF frequency-domain RAOs from the database (postproc.bem_rao documents the
      conventions and the output layout); prints the undamped natural periods of heave,
      roll and pitch and their radiation damping ratios there. --gm replaces C44 by m g GM.

  python -m postproc.bem passive DATABASE [-o FILE] [--nmax N] [--fit-tol TOL]
      re-fit an existing database's radiation memory as `build` fits it today, the fitted
      damping matrix made positive semi-definite (postproc.bem_refit: the build's fitting
      stage on the stored frequency-domain data; no BEM solve, every other variable
      unchanged), each fitted pair's zero-frequency added mass held at the database's
      A(0). For databases built before `build` enforced it (the shipped
      input/boat_bem.nc and input/ship_bem.nc were re-fitted so). Prints the fits, the
      smallest eigenvalue before and after and each pair's cost; default: in place.

  python -m postproc.bem compare FINE COARSE
      mesh convergence: max change of A, B, the excitation and the RAO peak of heave, roll
      and pitch within 0.2 rad/s of their natural frequencies (postproc.bem_compare), as a
      Markdown table.

Exit status 0 on success, 1 on an unreadable input or a failed solve.
"""
import argparse
import shlex
import sys

import numpy as np

from . import bem_checks, bem_db, bem_mesh, bem_rao


def _parser():
    parser = argparse.ArgumentParser(prog="python -m postproc.bem", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    b = sub.add_parser("build", help="mesh, solve and write a BEM database")
    b.add_argument("--hull", choices=("box", "ship", "lifeboat"), default="box")
    b.add_argument("--mesh", default=None, help="mesh file (overrides --hull)")
    b.add_argument("--mesh-format", default=None,
                   help="format of --mesh when its extension is ambiguous (e.g. nemoh for "
                        ".dat; Capytaine's load_mesh names)")
    b.add_argument("--panels", type=int, default=2000,
                   help="approximate number of hull panels (default 2000)")
    b.add_argument("--length", type=float, default=None,
                   help="waterline length [m] (box: 107.65, ship: L_pp 126)")
    b.add_argument("--beam", type=float, default=None, help="[m] (box, ship: 20.8; "
                   "lifeboat: 2.8)")
    b.add_argument("--draught", type=float, default=None, help="[m] (box, ship: 4.4; "
                   "lifeboat: 0.3175)")
    b.add_argument("--breadth-exponent", type=float, default=bem_mesh.BOAT_BREADTH_EXPONENT,
                   help="lifeboat only: p of b(x) = B (1 - |2x/L|^p) (default 4.3)")
    b.add_argument("--block-coefficient", type=float, default=bem_mesh.BLOCK_COEFFICIENT,
                   help="ship hull only")
    b.add_argument("--no-lid", action="store_true", help="no irregular-frequency lid")
    b.add_argument("--cg", type=float, nargs=3, default=None,
                   metavar=("X", "Y", "Z"),
                   help="CG = rotation centre in the mesh frame (z up; default 0 0 0: "
                        "midship, centreline, on the waterline; lifeboat: 1.1 m above the "
                        "keel, 0 0 0.7825)")
    b.add_argument("--mass", type=float, default=None, help="[kg] (default: displaced mass; "
                   "lifeboat: 8500)")
    b.add_argument("--inertia", type=float, nargs=3, default=None,
                   metavar=("IXX", "IYY", "IZZ"),
                   help="[kg m^2] about the CG (overrides the gyradii; lifeboat default "
                        "25020 51745 51745)")
    b.add_argument("--roll-gyradius", type=float, default=None,
                   help="[m] (default 0.38 B of the hull)")
    b.add_argument("--pitch-gyradius", type=float, default=None,
                   help="[m] (default 0.25 L of the hull; the default box: the paper's "
                        "0.25 L_wl = 32.6375 m)")
    b.add_argument("--yaw-gyradius", type=float, default=None,
                   help="[m] (default as --pitch-gyradius)")
    b.add_argument("--rho", type=float, default=1025.0)
    b.add_argument("--omegas", type=float, nargs="+", default=None, help="[rad/s]")
    b.add_argument("--headings-deg", type=float, nargs="+", default=None,
                   help="relative headings, davit's convention (0 following, 90 waves to "
                        "starboard, 180 head seas)")
    b.add_argument("--nmax", type=int, default=12, help="largest state-space order")
    b.add_argument("--fit-tol", type=float, default=0.02,
                   help="target max relative error of the fitted A and B")
    b.add_argument("--no-passive-matrix", action="store_true",
                   help="leave the fitted damping matrix as the pair-by-pair fits give it "
                        "(default: made positive semi-definite, postproc.bem_passive)")
    b.add_argument("-o", "--output", default=None,
                   help="default input/ship_bem.nc (lifeboat: input/boat_bem.nc)")
    b.add_argument("-q", "--quiet", action="store_true")

    r = sub.add_parser("rao", help="frequency-domain RAOs from a database")
    r.add_argument("database")
    r.add_argument("--roll-damping", type=float, default=0.05,
                   help="linear roll damping ratio zeta (default 0.05)")
    r.add_argument("--gm", type=float, default=None,
                   help="[m] replace the database's roll stiffness C44 by m g GM (e.g. the "
                        "paper's h_m = 2 m for the lifeboat)")
    r.add_argument("--omegas", type=float, nargs="+", default=None,
                   help="[rad/s] (default: the database's)")
    r.add_argument("--headings-deg", type=float, nargs="+", default=None,
                   help="default: 0, 45, 90, 135, 180")
    r.add_argument("-o", "--output", default=None, help="FILE.h5 or FILE.csv")

    p = sub.add_parser("passive", help="make an existing database's fitted damping "
                       "matrix positive semi-definite (no BEM solve)")
    p.add_argument("database")
    p.add_argument("-o", "--output", default=None, help="default: DATABASE itself")
    p.add_argument("--nmax", type=int, default=12, help="largest state-space order")
    p.add_argument("--fit-tol", type=float, default=0.02,
                   help="target max relative error of the fitted A and B")

    c = sub.add_parser("compare", help="mesh convergence between two databases")
    c.add_argument("fine")
    c.add_argument("coarse")
    return parser


def _error(message):
    print(f"bem: error: {message}", file=sys.stderr)
    return 1


def _build(args, argv):
    import logging
    logging.getLogger("capytaine").setLevel(logging.ERROR)
    from . import bem_build
    lifeboat = args.hull == "lifeboat" and not args.mesh
    if args.omegas is not None:
        omega_max = max(args.omegas)
    else:
        omega_max = float(bem_build.lifeboat_omegas()[-1]) if lifeboat else 2.0
    beam = args.beam or (bem_mesh.BOAT_BEAM if lifeboat else bem_mesh.BEAM)
    draught = args.draught or (bem_mesh.BOAT_DRAUGHT if lifeboat else bem_mesh.DRAUGHT)
    cg, mass = args.cg, args.mass
    if args.mesh:
        try:
            hull = bem_mesh.file_hull(args.mesh, omega_max=omega_max, lid=not args.no_lid,
                                      file_format=args.mesh_format)
        except (OSError, ValueError) as exc:
            return _error(f"{args.mesh}: {exc}")
        print(f"bem: {args.mesh}: {hull.extra['mesh_checks']}", file=sys.stderr)
    elif lifeboat:
        hull = bem_mesh.lifeboat_hull(length=args.length or bem_mesh.BOAT_LENGTH, beam=beam,
                                      draught=draught, exponent=args.breadth_exponent,
                                      panels=args.panels, omega_max=omega_max,
                                      lid=not args.no_lid)
        if cg is None:
            cg = (0.0, 0.0, bem_mesh.BOAT_KEEL_TO_CG - draught)
        if mass is None:
            mass = bem_mesh.BOAT_MASS
        if args.inertia is None:
            args.inertia = bem_mesh.BOAT_INERTIA
    elif args.hull == "ship":
        hull = bem_mesh.ship_hull(length=args.length or bem_mesh.L_PP, beam=beam,
                                  draught=draught,
                                  block_coefficient=args.block_coefficient,
                                  panels=args.panels, omega_max=omega_max,
                                  lid=not args.no_lid)
    else:
        hull = bem_mesh.box_hull(length=args.length or bem_mesh.BOX_LENGTH, beam=beam,
                                 draught=draught, panels=args.panels,
                                 omega_max=omega_max, lid=not args.no_lid)
    if cg is None:
        cg = (0.0, 0.0, 0.0)
    if args.inertia is not None:
        if mass is None:
            return _error("--inertia needs --mass")
        gyradii = tuple(float(np.sqrt(i / mass)) for i in args.inertia)
    else:
        gyradii, sources = bem_build.default_gyradii(
            hull, (args.roll_gyradius, args.pitch_gyradius, args.yaw_gyradius),
            paper_box=args.hull == "box" and not args.mesh and args.length is None)
        print("bem: gyradii " + ", ".join(f"{n} {r:.4g} m ({s})" for n, r, s in
                                          zip(("roll", "pitch", "yaw"), gyradii, sources)),
              file=sys.stderr)
    if len(args.headings_deg or (0, 1)) < 2:
        print("bem: note: a one-heading database answers `bem rao` at that heading only; "
              "davit's time-domain ship needs at least 2 headings (--headings-deg)",
              file=sys.stderr)
    output = args.output or ("input/boat_bem.nc" if lifeboat else "input/ship_bem.nc")
    command = "python -m postproc.bem " + " ".join(shlex.quote(a) for a in argv)
    try:
        bem_build.build(hull, output, cg=cg, mass=mass, gyradii=gyradii,
                        omegas=args.omegas, headings_deg=args.headings_deg, rho=args.rho,
                        nmax=args.nmax, tol=args.fit_tol, command=command,
                        progress=not args.quiet, passive_matrix=not args.no_passive_matrix)
    except bem_checks.MeshError as exc:
        return _error(f"{args.mesh or args.hull}: {exc}")
    return 0


def _rao(args):
    try:
        base = bem_db.Database(args.database)
    except (OSError, ValueError) as exc:
        return _error(exc)
    if args.gm is not None:
        base = bem_rao.with_roll_gm(base, args.gm)
    headings = np.radians(args.headings_deg if args.headings_deg is not None
                          else [0.0, 45.0, 90.0, 135.0, 180.0])
    omegas = base.omega if args.omegas is None else np.asarray(args.omegas)
    try:
        bem_rao.check_restoring(base)
        xi, b44 = bem_rao.raos(base, omegas, headings, args.roll_damping)
    except ValueError as exc:
        return _error(f"{args.database}: {exc}")
    periods = bem_rao.natural_periods(base)
    ratios = bem_rao.damping_ratios(base)
    c44, gm = float(base.stiffness[3, 3]), bem_rao.roll_gm(base)
    for dof in bem_rao.RESTORED:
        print(f"bem: undamped natural period {bem_db.DOFS[dof]:>5s}: {periods[dof]:.3f} s "
              f"(omega {2 * np.pi / periods[dof]:.4f} rad/s), radiation damping ratio there "
              f"{ratios[dof]:.4f}")
    print(f"bem: C44 = {c44:.6g} N m (GM_T {gm:.4f} m"
          f"{', set by --gm' if args.gm is not None else ''})")
    print(f"bem: roll damping zeta {args.roll_damping:g}: B44_visc = {b44:.4g} N m s")
    if args.output:
        bem_rao.write(args.output, omegas, headings, xi, periods, args.database,
                      args.roll_damping, b44, ratios, c44, gm)
        print(f"bem: wrote {args.output}")
    else:
        print("omega  heading  |heave| |roll|/k |pitch|/k  (amplitude per unit wave amplitude)")
        for n, w in enumerate(omegas):
            k = w**2 / 9.81
            for m, h in enumerate(headings):
                print(f"{w:6.3f} {np.degrees(h):6.1f}  {abs(xi[n, m, 2]):7.4f} "
                      f"{abs(xi[n, m, 3]) / k:8.4f} {abs(xi[n, m, 4]) / k:8.4f}")
    return 0


def _passive(args, argv):
    import logging
    logging.getLogger("capytaine").setLevel(logging.ERROR)
    from . import bem_refit
    command = "python -m postproc.bem " + " ".join(shlex.quote(a) for a in argv)
    try:
        hydro = bem_refit.refit_file(args.database, args.output or args.database,
                                     nmax=args.nmax, tol=args.fit_tol, command=command,
                                     progress=True)
    except (OSError, ValueError, KeyError) as exc:
        return _error(f"{args.database}: {exc}")
    result = hydro["passive_result"]
    if not result.converged:
        return _error(f"{args.database}: the smallest eigenvalue is still "
                      f"{result.min_eigenvalue_after:.3g} after {result.iterations} iterations")
    print(f"bem: wrote {args.output or args.database}")
    return 0


def _compare(args):
    from . import bem_compare
    try:
        fine, coarse = bem_db.Database(args.fine), bem_db.Database(args.coarse)
        rows = bem_compare.compare(fine, coarse)
    except (OSError, ValueError) as exc:
        return _error(exc)
    print(bem_compare.markdown(
        rows, f"{int(np.ravel(fine.attrs[bem_db.ATTR_PANELS])[0])} panels",
        f"{int(np.ravel(coarse.attrs[bem_db.ATTR_PANELS])[0])} panels"))
    return 0


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    args = _parser().parse_args(argv)
    if args.command == "build":
        return _build(args, argv)
    if args.command == "compare":
        return _compare(args)
    if args.command == "passive":
        return _passive(args, argv)
    return _rao(args)


if __name__ == "__main__":
    sys.exit(main())
