#!/usr/bin/env bash
# davit's two commands (the README's first lines), plus their shared set-up:
#   bash make.sh demo   install what is missing, build (release), install the commands
#                       davit and davit-post into ~/.local/bin (as install does), run the
#                       default scenario, write out/*.h5 and out/*.png
#   bash make.sh test   install what is missing, build, run every Fortran and Python test,
#                       closing with one line "N passed, N failed"
#   bash make.sh install [PREFIX]
#                       build, then install PREFIX/bin/davit (a wrapper around a copy of the
#                       binary in PREFIX/libexec/davit, with the project's data files from
#                       PREFIX/share/davit/input on DAVIT_PATH) and PREFIX/bin/davit-post
#                       (python -m postproc from any folder, with the project's Python);
#                       PREFIX defaults to ~/.local
#   bash make.sh paper  build, run every paper deck into out/, draw every figure and print
#                       the regression report (python -m postproc all / regress): minutes.
#                       PAPER_SWEEPS adds sweeps (a comma-separated list; see paper_sweeps):
#                         regular      Figs. 19-21 and the SOLAS sweeps (~30 min, 2 cores)
#                         operability  the launch assessment's sweeps and tables (~1 h)
#                         irregular    the irregular sweep of Figs. 22-23 (~1 h)
#                         all          all three (PAPER_IRREGULAR=1, the old switch, too)
#                       and closes with a summary: what ran, where it went, how long it took
#   bash make.sh operability  the operability sweeps, their tables and heat maps
#   bash make.sh docs   build, write the documentation's blocks made from the code (deck keys,
#                       command line) into doc/, build the site with FORD into build/doc/
#                       (open build/doc/index.html)
#   bash make.sh help   this text
#   bash make.sh mpi    install Open MPI if mpifort is missing, build the MPI binary (the
#                       sweep across MPI ranks: mpirun -np N build/davit-mpi sweep ...),
#                       print its path (test also builds it and runs its tests)
# Both are idempotent: a second run installs nothing and rebuilds only what changed.
set -euo pipefail
CALLER_DIR="$PWD"  # where a relative install PREFIX is meant from
cd "$(dirname "$0")"

APT_PACKAGES=(gfortran libhdf5-dev liblapack-dev libopenblas-dev pkg-config python3)
# capytaine (with xarray, scipy, pandas) and h5netcdf: the ship's BEM database
# (python -m postproc.bem build writes netCDF4/HDF5 through xarray's h5netcdf engine)
# ford: the documentation site (bash make.sh docs; test_docs builds it)
# fmpy: the FMI headers the FMU is compiled against, and the co-simulation master its test
# steps it with (python3 -m davit.fmu, test_fmu.py)
PY_PACKAGES=(fpm numpy h5py matplotlib pytest capytaine h5netcdf meshio imageio imageio-ffmpeg
             hypothesis fortitude-lint ford fmpy)
# netCDF's own tools (ncdump, nccopy): the tests read every kind of davit output with them
TEST_APT_PACKAGES=(netcdf-bin)
DEFAULT_DECK=input/iiib_level5_090.nml
# Release build tuned for this CPU (AVX2/FMA where present): the wave kernels vectorise
# 3x better than with the x86-64 baseline (davit bench); automatic arrays on the stack
# (-fstack-arrays) instead of malloc in the RHS: 7 % less CPU on the default scene;
# link-time optimisation (-flto=auto) inlines the right-hand side's small cross-module
# routines: 0.73 x the CPU of a regular launch (postproc/build_flags.py, the same string).
# DAVIT_MARCH picks another target (bash make.sh portable uses x86-64-v2: no FMA, SSE4.2).
DAVIT_MARCH="${DAVIT_MARCH:-native}"
release_flags() {
  echo "-march=$DAVIT_MARCH -fstack-arrays -flto=auto"
}
FPM_FLAGS=(--profile release --flag "$(release_flags)")

# ParaView (Debian's, 5.11) and a virtual X server: test_scene renders the scene's state
# file with pvpython under xvfb-run (bash make.sh test installs them; the test skips, saying
# why, only where they cannot be installed; DAVIT_NO_PARAVIEW=1 leaves them out)
PARAVIEW_APT_PACKAGES=(paraview xvfb)

# Open MPI (Debian's): mpifort and mpirun, for the MPI build of `davit sweep`
MPI_APT_PACKAGES=(libopenmpi-dev openmpi-bin)
MPI_FLAGS=(--profile release --flag "$(release_flags) -DDAVIT_MPI")
MPI_BIN=build/davit-mpi

log() { printf '%s\n' "make.sh: $*" >&2; }

as_root() {
  if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi
}

setup_apt() {
  apt_install "${APT_PACKAGES[@]}"
}

# Install the Debian packages named that are missing.
apt_install() {
  local missing=()
  for p in "$@"; do
    dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    log "installing ${missing[*]}"
    as_root apt-get update -qq
    as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}" >/dev/null
  fi
}

# The MPI binary (fpm puts it under its own hashed folder; build/davit-mpi is a stable
# name), after installing Open MPI when mpifort is missing.
setup_mpi() {
  if ! command -v mpifort >/dev/null 2>&1; then
    log "installing ${MPI_APT_PACKAGES[*]}"
    as_root apt-get update -qq
    as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${MPI_APT_PACKAGES[@]}" >/dev/null
  fi
  log "building the MPI binary (release, mpifort -DDAVIT_MPI)"
  FPM_FC=mpifort fpm build "${MPI_FLAGS[@]}" >/dev/null 2>&1 || FPM_FC=mpifort fpm build "${MPI_FLAGS[@]}"
  local bin
  bin="$(FPM_FC=mpifort fpm run "${MPI_FLAGS[@]}" --runner echo 2>/dev/null | tail -n 1)"
  cp -f "$bin" "$MPI_BIN.tmp" && mv -f "$MPI_BIN.tmp" "$MPI_BIN"
  export DAVIT_MPI_BIN="$PWD/$MPI_BIN"
}

# Optional: a failed install leaves the scene's rendering test to skip with its reason.
setup_paraview() {
  [ "${DAVIT_NO_PARAVIEW:-0}" = 1 ] && return 0
  command -v pvpython >/dev/null 2>&1 && command -v xvfb-run >/dev/null 2>&1 && return 0
  log "installing ${PARAVIEW_APT_PACKAGES[*]} (the scene's rendering test)"
  { as_root apt-get update -qq &&
      as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq \
        "${PARAVIEW_APT_PACKAGES[@]}" >/dev/null; } ||
    log "could not install ParaView: the scene's rendering test will skip"
}

# Headless Chromium (Debian's chromium and chromium-driver) and Selenium (PyPI):
# test_live drives the live page in a real browser (bash make.sh test installs them; the
# test skips, saying why, only where they cannot be installed; DAVIT_NO_BROWSER=1 leaves
# them out)
BROWSER_APT_PACKAGES=(chromium chromium-driver)
setup_browser() {
  [ "${DAVIT_NO_BROWSER:-0}" = 1 ] && return 0
  if ! command -v chromedriver >/dev/null 2>&1; then
    log "installing ${BROWSER_APT_PACKAGES[*]} (the live page's browser test)"
    { as_root apt-get update -qq &&
        as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq \
          "${BROWSER_APT_PACKAGES[@]}" >/dev/null; } ||
      log "could not install Chromium: the live page's browser test will skip"
  fi
  python3 -c "import selenium" >/dev/null 2>&1 ||
    python3 -m pip install -q --disable-pip-version-check selenium ||
    log "could not install Selenium: the live page's browser test will skip"
}

mpi() {
  setup_apt
  setup_python
  setup_mpi
  echo "$DAVIT_MPI_BIN"
}

python_ready() {
  command -v fpm >/dev/null 2>&1 && command -v fortitude >/dev/null 2>&1 &&
    command -v ford >/dev/null 2>&1 &&
    python3 -c "import numpy, h5py, matplotlib, pytest, capytaine, h5netcdf, meshio, imageio, imageio_ffmpeg, hypothesis, ford" >/dev/null 2>&1
}

# Use the Python packages already installed if all are there; otherwise a project venv
# (.venv), which also works on Debian's externally managed system Python.
setup_python() {
  if [ -x .venv/bin/python3 ]; then export PATH="$PWD/.venv/bin:$PATH"; fi
  python_ready && return 0
  if [ ! -x .venv/bin/python3 ]; then
    if ! python3 -m venv .venv >/dev/null 2>&1; then
      rm -rf .venv
      log "installing python3-venv"
      as_root apt-get update -qq
      as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq python3-venv >/dev/null
      python3 -m venv .venv
    fi
  fi
  export PATH="$PWD/.venv/bin:$PATH"
  log "installing ${PY_PACKAGES[*]} into .venv"
  python3 -m pip install -q --disable-pip-version-check "${PY_PACKAGES[@]}"
  python_ready
}

setup() {
  setup_apt
  setup_python
  log "building (release)"
  fpm build "${FPM_FLAGS[@]}" >/dev/null 2>&1 || fpm build "${FPM_FLAGS[@]}"
  DAVIT_BIN="$(fpm run "${FPM_FLAGS[@]}" --runner echo 2>/dev/null | tail -n 1)"
  export DAVIT_BIN="$PWD/$DAVIT_BIN"
  setup_library
}

# The library (include/davit.h, doc/howto/library.md): build/libdavit.so linked from the
# very archive fpm linked DAVIT_BIN from (same objects, so the library's runs equal davit
# run's bit for bit), and the Python package python/davit made importable: a .pth file in
# the Python's site-packages (.venv's, where setup made one) names python/. fpm prints the
# archive only when it links, so the binary is relinked (a second) when the archive is
# newer than the library or the library is missing.
DAVIT_LIB=build/libdavit.so
setup_library() {
  local archive site
  if [ ! -e "$DAVIT_LIB" ] || [ "$DAVIT_BIN" -nt "$DAVIT_LIB" ]; then
    rm -f "$DAVIT_BIN"
    archive="$(fpm build "${FPM_FLAGS[@]}" --verbose 2>&1 | grep -o '[^ ]*/libdavit\.a' | tail -n 1)"
    if [ -z "$archive" ] || [ ! -e "$archive" ]; then
      log "cannot find fpm's libdavit.a: $DAVIT_LIB not built"
      return 1
    fi
    log "linking $DAVIT_LIB from $archive"
    # shellcheck disable=SC2046  # pkg-config's flags are words
    # the archive holds link-time-optimisation objects: the link compiles them, with
    # fpm's release options and the build's flags
    # shellcheck disable=SC2046  # the flags are words
    gfortran -shared -O3 -funroll-loops -fPIC $(release_flags) -o "$DAVIT_LIB.tmp" \
      -Wl,--whole-archive "$archive" -Wl,--no-whole-archive \
      -fopenmp $(pkg-config --libs hdf5) -lhdf5hl_fortran -lhdf5_fortran -lhdf5_hl -llapack -lblas
    mv -f "$DAVIT_LIB.tmp" "$DAVIT_LIB"
  fi
  export DAVIT_LIB="$PWD/$DAVIT_LIB"
  site="$(python3 -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')"
  if [ -w "$site" ]; then
    printf '%s\n' "$PWD/python" >"$site/davit_library.pth"
  else
    log "$site is not writable: import davit needs PYTHONPATH=$PWD/python"
  fi
}

# Single-quoted for a generated shell script (any character, quotes included).
shell_quote() {
  printf "'%s'" "${1//\'/\'\\\'\'}"
}

# Write a file through a temporary beside it, so a command running from it stays whole.
install_script() {
  local dest="$1" text="$2"
  printf '%s\n' "$text" >"$dest.tmp"
  chmod 755 "$dest.tmp"
  mv -f "$dest.tmp" "$dest"
}

# The commands after setup (the binary in DAVIT_BIN): PREFIX/bin/davit is a wrapper that
# puts the installed copy of input/ (the BEM databases that decks name, e.g. &ship model =
# 'bem') after the caller's DAVIT_PATH, so a deck copied anywhere finds them, and runs a copy
# of the binary (a rebuild or a clean checkout does not break it; install again to update);
# PREFIX/bin/davit-post runs python -m postproc of this checkout with the Python that setup
# found ready (.venv's where it made one), from any folder and whatever PATH says.
install_files() {
  local prefix="$1" py
  case "$prefix" in /*) ;; *) prefix="$CALLER_DIR/$prefix" ;; esac
  mkdir -p "$prefix/bin" "$prefix/libexec/davit" "$prefix/share/davit" || {
    log "cannot write to $prefix: choose another PREFIX (bash make.sh install PREFIX) or run as root"
    return 1
  }
  prefix="$(cd "$prefix" && pwd)"
  cp -f "$DAVIT_BIN" "$prefix/libexec/davit/davit.tmp"
  mv -f "$prefix/libexec/davit/davit.tmp" "$prefix/libexec/davit/davit"
  rm -rf "$prefix/share/davit/input.tmp"
  cp -R input "$prefix/share/davit/input.tmp"
  rm -rf "$prefix/share/davit/input"
  mv "$prefix/share/davit/input.tmp" "$prefix/share/davit/input"
  py="$(python3 -c 'import sys; print(sys.executable)')"
  install_script "$prefix/bin/davit" "#!/bin/sh
# davit, installed by bash make.sh install from $PWD
DAVIT_PATH=\"\${DAVIT_PATH:+\$DAVIT_PATH:}\"$(shell_quote "$prefix/share/davit/input")
export DAVIT_PATH
# davit live: the launch in a browser (python3 -m davit.live over build/libdavit.so)
if [ \"\${1:-}\" = live ]; then
  shift
  PYTHONPATH=$(shell_quote "$PWD/python")\"\${PYTHONPATH:+:\$PYTHONPATH}\" exec $(shell_quote "$py") -m davit.live \"\$@\"
fi
exec $(shell_quote "$prefix/libexec/davit/davit") \"\$@\""
  install_script "$prefix/bin/davit-post" "#!/bin/sh
# davit-post: python -m postproc of the davit checkout $PWD
# (installed by bash make.sh install; the study and fender tools run \$DAVIT)
PYTHONPATH=$(shell_quote "$PWD")\"\${PYTHONPATH:+:\$PYTHONPATH}\"
[ -n \"\${DAVIT:-}\" ] || DAVIT=$(shell_quote "$prefix/bin/davit")
export PYTHONPATH DAVIT
py=$(shell_quote "$py")
[ -x \"\$py\" ] || py=python3
exec \"\$py\" -m postproc \"\$@\""
  log "installed $prefix/bin/davit (binary in $prefix/libexec/davit, data in $prefix/share/davit/input)"
  log "installed $prefix/bin/davit-post (python -m postproc with $py)"
  case ":$PATH:" in
    *":$prefix/bin:"*) log "$prefix/bin is on PATH: davit --help, davit-post --help" ;;
    *) log "$prefix/bin is not on PATH; add it (then open a new shell):"
       log "  echo 'export PATH=\"$prefix/bin:\$PATH\"' >> ~/.bashrc" ;;
  esac
}

install_cmd() {
  setup
  install_files "${1:-$HOME/.local}"
}

demo() {
  setup
  install_files "$HOME/.local"
  mkdir -p out
  local stem
  stem="$(basename "$DEFAULT_DECK" .nml)"
  "$DAVIT_BIN" run "$DEFAULT_DECK" -o "out/$stem.h5"
  python3 -m postproc run "out/$stem.h5" -o out
  python3 -m postproc animate "out/$stem.h5" -o "out/$stem.mp4" --every 10
}

# The decks behind the paper's figures and facts: Section III.B regular runs with and
# without wind (Figs. 15-19, F7-F9), the frozen-ship run (F9), the III.A experiments
# (Figs. 11-13, F2), the Fig. 13 transient (F2), the lowering, the Level 4/5 seas (Fig. 6)
# and the ship's RAOs, and the irregular III.B decks (~4 s each with the slow clocks).
paper_decks() {
  ls input/iiib_level?_???.nml input/iiib_level?_???_nowind.nml input/iiib_level5_090_frozen.nml \
     input/iiia_model_scale_?.nml input/fig13_tension.nml input/lowering.nml \
     input/sea_level?_irregular.nml input/ship_rao.nml input/iiib_level?_???_irregular.nml
}

# One deck to out/<deck name>.h5, skipped when that file is newer than the deck and the
# binary (FORCE=1 reruns everything); the log goes to out/<deck name>.log.
run_paper_deck() {
  local deck="$1" stem out mode=run
  stem="$(basename "$deck" .nml)"
  out="out/$stem.h5"
  if [ "${FORCE:-0}" != 1 ] && [ "$out" -nt "$deck" ] && [ "$out" -nt "$DAVIT_BIN" ]; then
    log "up to date: $out"
    echo "$deck" >>"$PAPER_FRESH"
    return 0
  fi
  grep -q '^ *&rao' "$deck" && mode=rao
  if OMP_NUM_THREADS=1 "$DAVIT_BIN" "$mode" "$deck" -o "$out" >"out/$stem.log" 2>&1; then
    log "$(tail -n 1 "out/$stem.log")"
    echo "$deck" >>"$PAPER_RAN"
  else
    log "FAILED: $deck (see out/$stem.log)"
    echo "$deck" >>"$PAPER_FAILED"
    return 1
  fi
}

# Which sweeps `bash make.sh paper` runs: PAPER_SWEEPS, a comma-separated list of classes
# (sweep_class), or all; none by default, for the decks and figures in minutes. The old
# switch PAPER_IRREGULAR=1 means all. Prints the classes chosen, one a line; exits 2 on an
# unknown one.
PAPER_SWEEP_CLASSES="regular operability irregular"
paper_sweeps() {
  local choice="${PAPER_SWEEPS:-}" c
  [ "${PAPER_IRREGULAR:-0}" = 1 ] && choice=all
  for c in ${choice//,/ }; do
    case "$c" in
      all) printf '%s\n' $PAPER_SWEEP_CLASSES ;;
      none) ;;
      regular|operability|irregular) echo "$c" ;;
      *) log "PAPER_SWEEPS: unknown '$c' (none, regular, operability, irregular, all)"
         return 2 ;;
    esac
  done | sort -u
}

# A sweep deck's class: operability (input/sweep_operability*.nml, the launch assessment,
# irregular seas, ~1 h on 2 cores), irregular (wave_types = 'irregular': Figs. 22-23, ~1 h), or
# regular (Figs. 19-21 ~30 min, and the SOLAS list/trim/headway sweeps, ~1 min, which need
# no class of their own).
sweep_class() {
  case "$(basename "$1")" in
    sweep_operability*) echo operability ;;
    *) if grep -q "^ *wave_types *= *'irregular'" "$1"; then echo irregular; else echo regular; fi ;;
  esac
}

# The sweep decks (input/sweep*.nml) of the classes chosen (paper_sweeps) through
# `davit sweep DECK -o out/DECK.h5`, if this build has it. Appends "ran|failed|skipped
# DECK SECONDS CLASS" lines to $PAPER_SWEEP_LOG for the summary.
run_sweeps() {
  local chosen="$1" deck class start failed=0
  if ! "$DAVIT_BIN" --help 2>&1 | grep -qw sweep; then
    log "no 'davit sweep' in this build: sweeps skipped"
    return 0
  fi
  for deck in input/sweep*.nml; do
    [ -e "$deck" ] || continue
    class="$(sweep_class "$deck")"
    if ! grep -qx "$class" <<<"$chosen"; then
      echo "skipped $deck 0 $class" >>"$PAPER_SWEEP_LOG"
      continue
    fi
    log "sweep $deck ($class)"
    start=$SECONDS
    if "$DAVIT_BIN" sweep "$deck" -o "out/$(basename "$deck" .nml).h5"; then
      echo "ran $deck $((SECONDS - start)) $class" >>"$PAPER_SWEEP_LOG"
    else
      echo "failed $deck $((SECONDS - start)) $class" >>"$PAPER_SWEEP_LOG"
      failed=1
    fi
  done
  return $failed
}

# The launch assessment (issue 16): the operability sweeps (Levels 3-5 x headings x
# clearances, 12 irregular seas each, at the paper's and at the LSA Code's lowering speed),
# their tables, heat maps and the paper's conclusion with intervals
# (out/sweep_operability{,_lsa}_operability.{csv,md,png}).
OPERABILITY_SWEEPS="sweep_operability sweep_operability_lsa"

operability_tables() {
  local stem failed=0
  for stem in $OPERABILITY_SWEEPS; do
    [ -e "out/$stem.h5" ] || continue
    python3 -m postproc operability "out/$stem.h5" -o out >"out/$stem.operability.log" || failed=1
    log "operability: out/${stem}_operability.md"
  done
  return $failed
}

operability() {
  setup
  mkdir -p out
  local stem
  for stem in $OPERABILITY_SWEEPS; do
    "$DAVIT_BIN" sweep "input/$stem.nml" -o "out/$stem.h5"
  done
  operability_tables
}

paper() {
  local sweeps
  sweeps="$(paper_sweeps)" || exit 2
  setup
  mkdir -p out
  local start=$SECONDS jobs="${JOBS:-2}" deck failed=0 t_runs t_sweeps t_figures tmp
  tmp="$(mktemp -d)"
  PAPER_FAILED="$tmp/failed" PAPER_RAN="$tmp/ran" PAPER_FRESH="$tmp/fresh"
  PAPER_SWEEP_LOG="$tmp/sweeps"
  touch "$PAPER_FAILED" "$PAPER_RAN" "$PAPER_FRESH" "$PAPER_SWEEP_LOG" "$tmp/stamp"
  log "paper decks ($jobs at a time)"
  for deck in $(paper_decks); do
    while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
    run_paper_deck "$deck" &
  done
  wait
  if [ -s "$PAPER_FAILED" ]; then failed=1; log "failed decks: $(tr '\n' ' ' <"$PAPER_FAILED")"; fi
  t_runs=$((SECONDS - start))
  run_sweeps "$sweeps" || failed=1
  t_sweeps=$((SECONDS - start - t_runs))
  python3 -m postproc all out -o out || failed=1
  operability_tables || failed=1
  python3 -m postproc regress out | tee out/regress.md
  t_figures=$((SECONDS - start - t_runs - t_sweeps))
  paper_summary "$tmp" "$sweeps" "$t_runs" "$t_sweeps" "$t_figures" "$((SECONDS - start))"
  rm -rf "$tmp"
  return $failed
}

# What paper ran and where it went: counts from the lists in folder $1 (ran, fresh, failed,
# sweeps) and the PNGs newer than its stamp; $2 the sweep classes; $3-$6 the timings (s).
paper_summary() {
  local tmp="$1" sweeps="$2" n_ran n_fresh n_failed n_png n_new line what deck secs class
  n_ran=$(wc -l <"$tmp/ran")
  n_fresh=$(wc -l <"$tmp/fresh")
  n_failed=$(wc -l <"$tmp/failed")
  n_png=$(find out -name '*.png' | wc -l)
  n_new=$(find out -name '*.png' -newer "$tmp/stamp" | wc -l)
  echo "paper: summary"
  echo "  decks: $n_ran run, $n_fresh up to date (FORCE=1 reruns them), $n_failed failed" \
       "-> out/<deck>.h5, logs out/<deck>.log"
  echo "  sweeps (PAPER_SWEEPS=${PAPER_SWEEPS:-none}${PAPER_IRREGULAR:+, PAPER_IRREGULAR=$PAPER_IRREGULAR}):" \
       "${sweeps:-no class chosen}" | tr '\n' ' '
  echo
  while read -r what deck secs class; do
    case "$what" in
      skipped) ;;
      *) echo "    $what $deck ($class) in ${secs} s -> out/$(basename "$deck" .nml).h5" ;;
    esac
  done <"$tmp/sweeps"
  line="$(awk '$1 == "skipped" {print $4}' "$tmp/sweeps" | sort | uniq -c |
          awk '{printf "%s%d %s", (NR > 1 ? ", " : ""), $1, $2}')"
  if [ -n "$line" ]; then
    echo "    not run: $line (PAPER_SWEEPS=regular,operability,irregular or all adds them)"
  fi
  echo "  figures: $n_new drawn now, $n_png in all -> out/*.png; regression report out/regress.md"
  if [ -e out/sweep_operability_operability.md ]; then
    echo "  operability tables: out/sweep_operability{,_lsa}_operability.{csv,md,png}"
  fi
  echo "  time: decks $3 s, sweeps $4 s, figures and report $5 s, total $6 s"
}

run_tests() {
  setup
  apt_install "${TEST_APT_PACKAGES[@]}"
  setup_mpi
  setup_paraview
  setup_browser
  local flog plog fpass=0 ffail=1 ppass=0 pfail=0 status=0 line
  flog="$(mktemp)"
  plog="$(mktemp)"
  # fpm 0.12 does not always recompile test objects when a module they use changes (stale
  # .mod vtables); the test objects are cheap, so rebuild them every time
  find build -path '*/davit/test_*' -delete 2>/dev/null || true
  log "Fortran tests (fpm test ${FPM_FLAGS[*]})"
  fpm test "${FPM_FLAGS[@]}" 2>&1 | grep -v '^\[' | tee "$flog" || status=1
  line="$(grep -E '^[0-9]+ passed, [0-9]+ failed$' "$flog" | tail -n 1 || true)"
  if [ -n "$line" ]; then
    fpass="${line%% passed*}"
    ffail="${line#*passed, }"; ffail="${ffail%% failed*}"
  fi
  # the Fortran linter, with the rules fortitude.toml keeps (a finding fails the suite)
  log "lint (fortitude check src app test)"
  if ! fortitude check src app test; then
    status=1
    ffail=$((ffail + 1))
  fi
  log "Python tests (pytest test/python)"
  python3 -m pytest -q -p no:cacheprovider test/python 2>&1 | tee "$plog" || status=1
  line="$(tail -n 1 "$plog")"
  [[ "$line" =~ ([0-9]+)\ passed ]] && ppass="${BASH_REMATCH[1]}"
  [[ "$line" =~ ([0-9]+)\ failed ]] && pfail="${BASH_REMATCH[1]}"
  [[ "$line" =~ ([0-9]+)\ error ]] && pfail=$((pfail + BASH_REMATCH[1]))
  rm -f "$flog" "$plog"
  local pass=$((fpass + ppass)) fail=$((ffail + pfail))
  if [ "$pass" -eq 0 ] || [ "$fail" -gt 0 ]; then status=1; fi
  echo "fortran: $fpass passed, $ffail failed"
  echo "python: $ppass passed, $pfail failed"
  echo "total: $pass passed, $fail failed"
  return $status
}

# The suite's numbers must not hang on this CPU's rounding (FMA, vector widths): the
# Fortran tests and the documentation's generated tables again with a portable x86-64-v2 build
# (CI runs it after the test command). The tables compare numbers at their printed
# precision (postproc/readme_tables.py differences), never bitwise.
portable() {
  DAVIT_MARCH=x86-64-v2
  FPM_FLAGS=(--profile release --flag "$(release_flags)")
  setup
  local flog status=0 line
  flog="$(mktemp)"
  find build -path '*/davit/test_*' -delete 2>/dev/null || true
  log "portable build (-march=$DAVIT_MARCH): Fortran tests"
  fpm test "${FPM_FLAGS[@]}" 2>&1 | grep -v '^\[' | tee "$flog" || status=1
  line="$(grep -E '^[0-9]+ passed, [0-9]+ failed$' "$flog" | tail -n 1 || true)"
  rm -f "$flog"
  [[ "$line" =~ ^[0-9]+\ passed,\ 0\ failed$ ]] || status=1
  log "portable build (-march=$DAVIT_MARCH): the documentation's generated tables"
  python3 -m pytest -q -p no:cacheprovider test/python/test_readme_tables.py || status=1
  echo "portable (-march=$DAVIT_MARCH): fortran ${line:-no result}; doc tables $([ $status -eq 0 ] && echo pass || echo FAIL)"
  return $status
}

# The documentation site: the blocks of doc/ made from the code (postproc/doc_blocks.py:
# `davit keys`, `davit --help`, `davit-post --help`), then FORD (fpm.toml [extra.ford]:
# README.md the front page, doc/ the user pages, src/ and app/ the API) into build/doc/.
docs() {
  setup
  python3 -m postproc.doc_blocks --write --davit "$DAVIT_BIN"
  python3 -m postproc.doc_blocks --site build/doc
}

usage() {
  cat <<'EOF'
usage: bash make.sh COMMAND
  demo               install what is missing, build, install davit and davit-post into
                     ~/.local/bin, run the default scenario into out/ (h5 and PNGs)
  test               build and run every Fortran and Python test ("N passed, N failed")
  install [PREFIX]   build and install PREFIX/bin/davit and PREFIX/bin/davit-post
                     (default PREFIX ~/.local, as root too); says whether PREFIX/bin is on
                     PATH and the line for ~/.bashrc if not
  paper              the paper decks, every figure and the regression report (minutes);
                     PAPER_SWEEPS=regular,operability,irregular (any of them) or all adds
                     sweeps: regular = Figs. 19-21 and SOLAS (~30 min on 2 cores),
                     operability = the launch assessment (~1 h), irregular = Figs. 22-23
                     (~1 h); PAPER_IRREGULAR=1 is all; JOBS=n decks at a time, FORCE=1
                     reruns decks whose outputs are up to date
  operability        the operability sweeps, their tables and heat maps
  mpi                build the MPI binary (installs Open MPI if missing)
  portable           the Fortran tests and the documentation tables with an x86-64-v2 build
                     (CI: results must not hang on this CPU's FMA or vector width)
  docs               the documentation site (FORD) -> build/doc/index.html; the deck-key
                     and command-line pages regenerated from the code first
  setup              install what is missing and build (the binary, build/libdavit.so,
                     import davit: doc/howto/library.md)
  help               this text
EOF
}

case "${1:-}" in
  demo) demo ;;
  test) run_tests ;;
  portable) portable ;;
  paper) paper ;;
  install) install_cmd "${2:-}" ;;
  help|-h|--help) usage ;;
  operability) operability ;;
  mpi) mpi ;;
  setup) setup ;;
  docs) docs ;;
  *) usage >&2; exit 2 ;;
esac
