"""davit as an FMI 2.0 co-simulation FMU: `python3 -m davit.fmu DECK [-o davit.fmu]`.

The FMU wraps the C ABI (build/libdavit.so, `bash make.sh demo`) with fmu/davit_fmu.c,
compiled here by the C compiler against the FMI 2.0 headers FMPy ships (pip install fmpy).
It carries the deck as resources/deck.nml beside the data files it names or defaults to
(the BEM databases), and the library beside its own binary (rpath $ORIGIN); the system
libraries libdavit needs (gfortran, HDF5, LAPACK) must be on the machine that runs it.
Variables: see fmu/davit_fmu.c and the modelDescription.xml written here."""
import argparse
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile
import uuid
import zipfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
OUTPUTS = [(0, "boat_x", "m", "boat CG x, inertial frame (z down)"),
           (1, "boat_y", "m", "boat CG y, inertial frame"),
           (2, "boat_z", "m", "boat CG z, inertial frame, down"),
           (3, "sling_tension_fore", "N", "sling tension at the fore hook"),
           (4, "sling_tension_aft", "N", "sling tension at the aft hook"),
           (5, "waterborne_time", "s", "time the boat became waterborne (-1 before)"),
           (6, "release_time", "s", "time the hooks were released (-1 before)")]
DEFAULT_DATA = ("ship_bem.nc", "boat_bem.nc")


def fmi_headers():
    import fmpy
    return pathlib.Path(fmpy.__file__).parent / "c-code"


def model_description(guid, stop_time):
    rows = []
    for vr, name, unit, text in OUTPUTS:
        rows.append(f'    <ScalarVariable name="{name}" valueReference="{vr}" '
                    f'causality="output" variability="continuous" initial="calculated" '
                    f'description="{text} [{unit}]"><Real unit="{unit}"/></ScalarVariable>')
    rows.append('    <ScalarVariable name="winch_speed" valueReference="10" causality="input" '
                'variability="continuous" description="drum speed set-point, pay-out > 0 '
                '[m/s]; below 0: the deck\'s own profile"><Real unit="m/s" start="-1"/>'
                '</ScalarVariable>')
    rows.append('    <ScalarVariable name="release" valueReference="11" causality="input" '
                'variability="discrete" description="open the hooks"><Boolean start="false"/>'
                '</ScalarVariable>')
    outs = "\n".join(f'      <Unknown index="{i + 1}"/>' for i in range(len(OUTPUTS)))
    return f"""<?xml version="1.0" encoding="UTF-8"?>
<fmiModelDescription fmiVersion="2.0" modelName="davit" guid="{{{guid}}}"
    description="lifeboat launch from a ship's davit (davit, C ABI)" generationTool="davit.fmu"
    variableNamingConvention="flat" numberOfEventIndicators="0">
  <CoSimulation modelIdentifier="davit" canHandleVariableCommunicationStepSize="true"
      canBeInstantiatedOnlyOncePerProcess="false" needsExecutionTool="false"
      canGetAndSetFMUstate="true" canSerializeFMUstate="true"/>
  <UnitDefinitions>
    <Unit name="m"><BaseUnit m="1"/></Unit>
    <Unit name="N"><BaseUnit kg="1" m="1" s="-2"/></Unit>
    <Unit name="s"><BaseUnit s="1"/></Unit>
    <Unit name="m/s"><BaseUnit m="1" s="-1"/></Unit>
  </UnitDefinitions>
  <DefaultExperiment startTime="0" stopTime="{stop_time}" stepSize="0.02"/>
  <ModelVariables>
{chr(10).join(rows)}
  </ModelVariables>
  <ModelStructure>
    <Outputs>
{outs}
    </Outputs>
    <InitialUnknowns>
{outs}
    </InitialUnknowns>
  </ModelStructure>
</fmiModelDescription>
"""


def data_files(deck_path):
    """The data files a deck names ('*.nc', '*.h5', '*.obj' strings) or defaults to,
    found beside it or on DAVIT_PATH."""
    text = pathlib.Path(deck_path).read_text()
    names = set(re.findall(r"'([^'/]+\.(?:nc|h5|obj))'", text)) | set(DEFAULT_DATA)
    folders = [pathlib.Path(deck_path).parent] + \
        [pathlib.Path(p) for p in os.environ.get("DAVIT_PATH", "").split(os.pathsep) if p] + \
        [ROOT / "input"]
    found = []
    for name in sorted(names):
        for folder in folders:
            if (folder / name).is_file():
                found.append(folder / name)
                break
    return found


def build(deck, out, library=None, stop_time=120.0, cc="cc"):
    """Write the FMU for `deck` to `out`; returns its path."""
    library = pathlib.Path(library or ROOT / "build" / "libdavit.so")
    if not library.is_file():
        raise FileNotFoundError(f"{library}: no C library (bash make.sh demo builds it)")
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        binaries = tmp / "binaries" / "linux64"
        resources = tmp / "resources"
        binaries.mkdir(parents=True)
        resources.mkdir()
        shutil.copy(library, binaries / "libdavit.so")
        subprocess.run([cc, "-std=c11", "-O2", "-shared", "-fPIC", f"-I{fmi_headers()}",
                        f"-I{ROOT / 'include'}", str(ROOT / "fmu" / "davit_fmu.c"),
                        "-o", str(binaries / "davit.so"), f"-L{binaries}", "-ldavit",
                        "-Wl,-rpath,$ORIGIN"], check=True)
        shutil.copy(deck, resources / "deck.nml")
        for f in data_files(deck):
            shutil.copy(f, resources / f.name)
        (tmp / "modelDescription.xml").write_text(model_description(uuid.uuid4(), stop_time))
        out = pathlib.Path(out)
        with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as z:
            for p in sorted(tmp.rglob("*")):
                if p.is_file():
                    z.write(p, p.relative_to(tmp).as_posix())
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m davit.fmu", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("deck")
    parser.add_argument("-o", "--output", default="davit.fmu")
    parser.add_argument("--library", default=None, help="default build/libdavit.so")
    args = parser.parse_args(argv)
    try:
        path = build(args.deck, args.output, args.library)
    except (OSError, subprocess.CalledProcessError, ImportError) as exc:
        print(f"davit.fmu: error: {exc}", file=sys.stderr)
        return 1
    print(f"davit.fmu: wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
