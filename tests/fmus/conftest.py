"""Shared, session-scoped FMU builds: building an FMU with pythonfmu takes about a second, so each is built once."""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

from tests.helpers.fmus import build_python_fmu, export_toy, model_description, set_attributes, with_model_description


@pytest.fixture(scope="session")
def fmu_dir(tmp_path_factory) -> Path:
    return tmp_path_factory.mktemp("fmus")


@pytest.fixture(scope="session")
def toy_fmus(fmu_dir) -> dict[str, Path]:
    """The toy thermo-mechanical scenario's components (osc, node) as FMUs with its parameters."""
    return export_toy(fmu_dir / "toy")


@pytest.fixture(scope="session")
def mass_fmu(fmu_dir) -> Path:
    from rotorcosim.fmus.export import export_component

    return export_component("testing.mass", fmu_dir / "mass.fmu", instance_name="m1",
                            parameters={"m": 1.0, "k": 40.0, "x0": 0.1})


@pytest.fixture(scope="session")
def damper_fmu(fmu_dir) -> Path:
    from rotorcosim.fmus.export import export_component

    # a coarse film mesh: the table of the fast damper is then built in about a second
    return export_component("damper.fast", fmu_dir / "damper5.fmu", instance_name="damper5",
                            parameters={"damper": 5, "n_theta": 32, "n_z": 8})


_TYPES2_DEFINITIONS = """<UnitDefinitions>
    <Unit name="degC"><BaseUnit K="1" offset="273.15"/></Unit>
    <Unit name="mm"><BaseUnit m="1" factor="0.001"/></Unit>
  </UnitDefinitions>
  <TypeDefinitions>
    <SimpleType name="Mode"><Enumeration><Item name="low" value="1"/><Item name="mid" value="2"/>
      <Item name="high" value="3"/></Enumeration></SimpleType>
  </TypeDefinitions>
  <LogCategories>"""


@pytest.fixture(scope="session")
def types2_fmu(fmu_dir) -> Path:
    """FMI 2.0 (pythonfmu): every FMI 2.0 type, units K/degC and m/mm, ranges, an enumeration, a settable state,
    an output computed at initialisation, a stop request at t_stop. pythonfmu 0.7 declares neither units nor
    ranges nor enumerations: they are added to its model description here (the binary is not concerned)."""
    built = build_python_fmu("types2", fmu_dir / "build2", fmi3=False)
    xml = model_description(built).replace("<LogCategories>", _TYPES2_DEFINITIONS, 1)
    xml = set_attributes(xml, "u", "Real", 'unit="degC"')
    xml = set_attributes(xml, "y", "Real", 'unit="mm"')
    xml = set_attributes(xml, "gain", "Real", 'min="0" max="10"')
    xml = set_attributes(xml, "n", "Integer", 'min="1" max="5"')
    for name in ("mode", "ue", "ye"):
        xml = set_attributes(xml, name, "Integer", 'declaredType="Mode"', new_tag="Enumeration")
    # outputs computed at initialisation are InitialUnknowns (fmpy's validation asks for them)
    unknowns = "".join(f'<Unknown index="{i}"/>' for i in range(13, 19))
    xml = xml.replace("</Outputs>", f"</Outputs><InitialUnknowns>{unknowns}</InitialUnknowns>", 1)
    return with_model_description(built, fmu_dir / "types2.fmu", xml)


@pytest.fixture(scope="session")
def types3_fmu(fmu_dir) -> Path:
    """FMI 3.0 (pythonfmu3): Float64, Int32, Int64, UInt64, Boolean, String, Enumeration ports, Float64 arrays,
    units degC and mm with their definitions, ranges (added to the model description: pythonfmu3 0.3 cannot
    declare them), a settable state, an output computed at initialisation, a terminate request at t_stop."""
    built = build_python_fmu("types3", fmu_dir / "build3", fmi3=True)
    xml = model_description(built)
    xml = set_attributes(xml, "gain", "Float64", 'min="0" max="10"')
    xml = set_attributes(xml, "n", "Int32", 'min="1" max="5"')
    return with_model_description(built, fmu_dir / "types3.fmu", xml)


@pytest.fixture(scope="session")
def widths3_fmu(fmu_dir) -> Path:
    """FMI 3.0 in C (models/widths3): Float32 scalar and array, Int8, UInt8, Int16, UInt16, UInt32, a Binary
    output, for the types pythonfmu3 cannot declare; compiled here with the system's C compiler."""
    import shutil
    import subprocess
    import zipfile

    cc = shutil.which("cc") or shutil.which("gcc")
    if cc is None or not sys.platform.startswith("linux"):
        pytest.skip("no C compiler (or not Linux): the FMI 3.0 test FMU in C cannot be built")
    src = Path(__file__).with_name("models") / "widths3"
    build = fmu_dir / "widths3"
    binary = build / "binaries" / "x86_64-linux" / "widths3.so"
    binary.parent.mkdir(parents=True, exist_ok=True)
    out = subprocess.run([cc, "-shared", "-fPIC", "-O2", "-o", str(binary), str(src / "widths3.c")],
                         capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr[-2000:]
    fmu = fmu_dir / "widths3.fmu"
    with zipfile.ZipFile(fmu, "w", zipfile.ZIP_DEFLATED) as zf:
        zf.write(src / "modelDescription.xml", "modelDescription.xml")
        zf.write(binary, "binaries/x86_64-linux/widths3.so")
    return fmu


#: the FMI 3.0 test models after the Modelica Reference FMUs (models/reference3): name -> the entries an archive
#: carries besides modelDescription.xml and the binary; roberts3's manifest is written twice with the same bytes,
#: as the Reference FMUs' own build writes Roberts.fmu
REFERENCE3 = {"feedthrough3": [], "statespace3": [],
              "roberts3": [("extra/org.modelica.fmi-ls-dae/fmi-ls-manifest.xml", "fmi-ls-manifest.xml")] * 2}


@pytest.fixture(scope="session")
def reference3_fmus(fmu_dir) -> dict[str, Path]:
    """The models of models/reference3 (after the Reference FMUs' Feedthrough, StateSpace and Roberts) as FMI 3.0
    co-simulation FMUs, compiled here with the system's C compiler."""
    import shutil
    import subprocess
    import warnings
    import zipfile

    cc = shutil.which("cc") or shutil.which("gcc")
    if cc is None or not sys.platform.startswith("linux"):
        pytest.skip("no C compiler (or not Linux): the FMI 3.0 test FMUs in C cannot be built")
    src = Path(__file__).with_name("models") / "reference3"
    out = {}
    for name, extra in REFERENCE3.items():
        binary = fmu_dir / name / "binaries" / "x86_64-linux" / f"{name}.so"
        binary.parent.mkdir(parents=True, exist_ok=True)
        built = subprocess.run([cc, "-shared", "-fPIC", "-O2", "-o", str(binary), str(src / f"{name}.c"),
                                str(src / "fmi3_stubs.c")], capture_output=True, text=True, timeout=120)
        assert built.returncode == 0, built.stderr[-2000:]
        fmu = fmu_dir / f"{name}.fmu"
        with warnings.catch_warnings(), zipfile.ZipFile(fmu, "w", zipfile.ZIP_DEFLATED) as zf:
            warnings.simplefilter("ignore", UserWarning)   # zipfile's "Duplicate name": meant here
            zf.write(src / f"{name}.xml", "modelDescription.xml")
            zf.write(binary, f"binaries/x86_64-linux/{name}.so")
            for entry, file in extra:
                zf.write(src / file, entry)
        out[name] = fmu
    return out


#: the FMI 1.0 co-simulation test models after the Modelica Reference FMUs (models/reference1)
REFERENCE1 = ("dahlquist1", "feedthrough1")


@pytest.fixture(scope="session")
def reference1_fmus(fmu_dir) -> dict[str, Path]:
    """The models of models/reference1 (after the Reference FMUs' Dahlquist and Feedthrough) as FMI 1.0
    co-simulation FMUs, compiled here with the system's C compiler (FMI 1.0 names the platform ``linux64``)."""
    import shutil
    import subprocess
    import zipfile

    cc = shutil.which("cc") or shutil.which("gcc")
    if cc is None or not sys.platform.startswith("linux"):
        pytest.skip("no C compiler (or not Linux): the FMI 1.0 test FMUs in C cannot be built")
    src = Path(__file__).with_name("models") / "reference1"
    out = {}
    for name in REFERENCE1:
        binary = fmu_dir / name / "binaries" / "linux64" / f"{name}.so"
        binary.parent.mkdir(parents=True, exist_ok=True)
        built = subprocess.run([cc, "-shared", "-fPIC", "-O2", "-o", str(binary), str(src / f"{name}.c"), "-lm"],
                               capture_output=True, text=True, timeout=120)
        assert built.returncode == 0, built.stderr[-2000:]
        fmu = fmu_dir / f"{name}.fmu"
        with zipfile.ZipFile(fmu, "w", zipfile.ZIP_DEFLATED) as zf:
            zf.write(src / f"{name}.xml", "modelDescription.xml")
            zf.write(binary, f"binaries/linux64/{name}.so")
        out[name] = fmu
    return out
