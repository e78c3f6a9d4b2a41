#!/usr/bin/env bash
# davit's two commands (the README's first lines), plus their shared set-up:
#   bash make.sh demo   install what is missing, build (release), run the default scenario,
#                       write out/*.h5 and out/*.png
#   bash make.sh test   install what is missing, build, run every Fortran and Python test,
#                       closing with one line "N passed, N failed"
# Both are idempotent: a second run installs nothing and rebuilds only what changed.
set -euo pipefail
cd "$(dirname "$0")"

APT_PACKAGES=(gfortran libhdf5-dev liblapack-dev libopenblas-dev pkg-config python3)
PY_PACKAGES=(fpm numpy h5py matplotlib pytest)
DEFAULT_DECK=input/iiib_level5_090.nml
# Release build tuned for this CPU (AVX2/FMA where present): the wave kernels vectorise
# 3x better than with the x86-64 baseline (davit bench).
FPM_FLAGS=(--profile release --flag "-march=native")

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

python_ready() {
  command -v fpm >/dev/null 2>&1 &&
    python3 -c "import numpy, h5py, matplotlib, pytest" >/dev/null 2>&1
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
}

run_tests() {
  setup
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
  setup) setup ;;
  *) echo "usage: bash make.sh demo|test|setup" >&2; exit 2 ;;
esac
