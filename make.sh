#!/usr/bin/env bash
# davit's two commands (the README's first lines), plus their shared set-up:
#   bash make.sh demo   install what is missing, build (release), run the default scenario,
#                       write out/*.h5 and out/*.png
#   bash make.sh test   install what is missing, build, run every Fortran and Python test,
#                       closing with one line "N passed, N failed"
#   bash make.sh paper  build, run every paper deck (and the sweeps, where `davit sweep`
#                       exists) into out/, then draw every figure and print the regression
#                       report (python -m postproc all / regress)
#   bash make.sh mpi    install Open MPI if mpifort is missing, build the MPI binary (the
#                       sweep across MPI ranks: mpirun -np N build/davit-mpi sweep ...),
#                       print its path (test also builds it and runs its tests)
# Both are idempotent: a second run installs nothing and rebuilds only what changed.
set -euo pipefail
cd "$(dirname "$0")"

APT_PACKAGES=(gfortran libhdf5-dev liblapack-dev libopenblas-dev pkg-config python3)
# capytaine (with xarray, scipy, pandas) and h5netcdf: the ship's BEM database
# (python -m postproc.bem build writes netCDF4/HDF5 through xarray's h5netcdf engine)
PY_PACKAGES=(fpm numpy h5py matplotlib pytest capytaine h5netcdf meshio imageio imageio-ffmpeg)
DEFAULT_DECK=input/iiib_level5_090.nml
# Release build tuned for this CPU (AVX2/FMA where present): the wave kernels vectorise
# 3x better than with the x86-64 baseline (davit bench); automatic arrays on the stack
# (-fstack-arrays) instead of malloc in the RHS: 7 % less CPU on the default scene.
FPM_FLAGS=(--profile release --flag "-march=native -fstack-arrays")

# Open MPI (Debian's): mpifort and mpirun, for the MPI build of `davit sweep`
MPI_APT_PACKAGES=(libopenmpi-dev openmpi-bin)
MPI_FLAGS=(--profile release --flag "-march=native -fstack-arrays -DDAVIT_MPI")
MPI_BIN=build/davit-mpi

log() { printf '%s\n' "make.sh: $*" >&2; }

as_root() {
  if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi
}

setup_apt() {
  local missing=()
  for p in "${APT_PACKAGES[@]}"; do
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

mpi() {
  setup_apt
  setup_python
  setup_mpi
  echo "$DAVIT_MPI_BIN"
}

python_ready() {
  command -v fpm >/dev/null 2>&1 &&
    python3 -c "import numpy, h5py, matplotlib, pytest, capytaine, h5netcdf, meshio, imageio, imageio_ffmpeg" >/dev/null 2>&1
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
}

demo() {
  setup
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
    return 0
  fi
  grep -q '^ *&rao' "$deck" && mode=rao
  if OMP_NUM_THREADS=1 "$DAVIT_BIN" "$mode" "$deck" -o "$out" >"out/$stem.log" 2>&1; then
    log "$(tail -n 1 "out/$stem.log")"
  else
    log "FAILED: $deck (see out/$stem.log)"
    echo "$deck" >>"$PAPER_FAILED"
    return 1
  fi
}

# Every sweep deck (input/sweep*.nml) through `davit sweep`, if this build has it; the
# irregular-sea sweeps (hours on 2 cores) only with PAPER_IRREGULAR=1.
run_sweeps() {
  if ! "$DAVIT_BIN" --help 2>&1 | grep -qw sweep; then
    log "no 'davit sweep' in this build: sweeps skipped"
    return 0
  fi
  local deck failed=0
  for deck in input/sweep*.nml; do
    [ -e "$deck" ] || continue
    if [ "${PAPER_IRREGULAR:-0}" != 1 ] && grep -q "^ *wave_types *= *'irregular'" "$deck"; then
      log "irregular sweep $deck skipped (PAPER_IRREGULAR=1 runs it)"
      continue
    fi
    log "sweep $deck"
    "$DAVIT_BIN" sweep "$deck" -o "out/$(basename "$deck" .nml).h5" || failed=1
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
  setup
  mkdir -p out
  local start=$SECONDS jobs="${JOBS:-2}" deck failed=0 t_runs t_sweeps
  PAPER_FAILED="$(mktemp)"
  log "paper decks ($jobs at a time)"
  for deck in $(paper_decks); do
    while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
    run_paper_deck "$deck" &
  done
  wait
  if [ -s "$PAPER_FAILED" ]; then failed=1; log "failed decks: $(tr '\n' ' ' <"$PAPER_FAILED")"; fi
  rm -f "$PAPER_FAILED"
  t_runs=$((SECONDS - start))
  run_sweeps || failed=1
  t_sweeps=$((SECONDS - start - t_runs))
  python3 -m postproc all out -o out || failed=1
  operability_tables || failed=1
  python3 -m postproc regress out | tee out/regress.md
  log "paper: runs ${t_runs} s, sweeps ${t_sweeps} s, figures and report" \
      "$((SECONDS - start - t_runs - t_sweeps)) s, total $((SECONDS - start)) s"
  return $failed
}

run_tests() {
  setup
  setup_mpi
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

case "${1:-}" in
  demo) demo ;;
  test) run_tests ;;
  paper) paper ;;
  operability) operability ;;
  mpi) mpi ;;
  setup) setup ;;
  *) echo "usage: bash make.sh demo|test|paper|operability|mpi|setup" >&2; exit 2 ;;
esac
