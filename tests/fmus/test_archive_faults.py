"""Malformed or hostile FMU and SSP archives: each refused with a clear error, no temporary folder left."""
from __future__ import annotations

import re
import tempfile
import zipfile
from pathlib import Path

import pytest

from rotorcosim.fmus import safezip
from rotorcosim.fmus.importer import FMUError, load_fmu_component
from rotorcosim.master.scenario.ssp import SSPError, read_ssp, write_ssp
from rotorcosim.master.scenario.build import load_scenario

from tests.helpers.fmus import TOY, rebuild


@pytest.fixture(scope="module")
def toy_ssp(fmu_dir) -> Path:
    return write_ssp(load_scenario(TOY), fmu_dir / "toy_faults.ssp")


@pytest.fixture
def private_tmp(tmp_path, monkeypatch):
    t = tmp_path / "t"
    t.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(t))
    return t


def edit_ssd(fn):
    return lambda name, data: fn(data) if name == "SystemStructure.ssd" else data


# -- caps ---------------------------------------------------------------------------------------------
def test_zip_bomb_refused_before_writing(mass_fmu, tmp_path, private_tmp, monkeypatch):
    # a 40 MB entry of zeros compresses ~1000x: the ratio cap stops it without writing anything
    bomb = rebuild(mass_fmu, tmp_path / "bomb.fmu", extra=[("resources/zeros.bin", bytes(40 * 1024 ** 2))])
    assert bomb.stat().st_size < 1024 ** 2
    with pytest.raises(FMUError, match=r"resources/zeros.bin' expands \d+ times .*zip bomb"):
        load_fmu_component(bomb, "c")
    assert list(private_tmp.iterdir()) == []


def test_total_size_and_entry_caps(mass_fmu, tmp_path, monkeypatch, private_tmp):
    monkeypatch.setattr(safezip, "MAX_TOTAL_BYTES", 10_000)
    with pytest.raises(FMUError, match=r"would extract more than 0 MiB"):
        load_fmu_component(mass_fmu, "c")
    monkeypatch.setattr(safezip, "MAX_TOTAL_BYTES", 512 * 1024 ** 2)
    monkeypatch.setattr(safezip, "MAX_ENTRIES", 3)
    with pytest.raises(FMUError, match=r"entries, more than the 3"):
        load_fmu_component(mass_fmu, "c")
    assert list(private_tmp.iterdir()) == []


def test_size_counted_while_writing(mass_fmu, tmp_path, monkeypatch, private_tmp):
    """Even when the directory's sizes pass, the bytes written are counted."""
    real = safezip.check_entries
    monkeypatch.setattr(safezip, "check_entries", lambda zf, source: None)
    monkeypatch.setattr(safezip, "MAX_TOTAL_BYTES", 10_000)
    with pytest.raises(safezip.ArchiveError, match="went beyond"):
        safezip.safe_extract(mass_fmu)
    assert list(private_tmp.iterdir()) == []
    monkeypatch.setattr(safezip, "check_entries", real)


# -- malformed archives ----------------------------------------------------------------------------------
def test_bad_crc(mass_fmu, tmp_path, private_tmp):
    data = bytearray(mass_fmu.read_bytes())
    with zipfile.ZipFile(mass_fmu) as zf:
        info = next(i for i in zf.infolist() if i.filename.endswith(".py") and i.compress_size > 200)
    # flip a byte inside that entry's compressed data (after its local header)
    start = info.header_offset + 30 + len(info.filename.encode()) + len(info.extra) + 50
    data[start] ^= 0xFF
    bad = tmp_path / "crc.fmu"
    bad.write_bytes(bytes(data))
    with pytest.raises(FMUError, match=rf"entry '{re.escape(info.filename)}' is damaged"):
        load_fmu_component(bad, "c")
    assert list(private_tmp.iterdir()) == []


def test_file_and_folder_of_one_name(mass_fmu, tmp_path, private_tmp):
    bad = rebuild(mass_fmu, tmp_path / "clash.fmu", extra=[("resources", b"a file named like the folder")])
    with pytest.raises(FMUError, match="'resources' is both a file and a folder"):
        load_fmu_component(bad, "c")
    twice = rebuild(mass_fmu, tmp_path / "twice.fmu", extra=[("documentation/x.txt", b"1"), ("documentation/x.txt", b"2")])
    with pytest.raises(FMUError, match="'documentation/x.txt' appears twice with different contents"):
        load_fmu_component(twice, "c")
    # the same size is not enough: the bytes must be the same
    same_size = rebuild(mass_fmu, tmp_path / "size.fmu", extra=[("documentation/y.txt", b"ab"),
                                                               ("documentation/y.txt", b"ba")])
    with pytest.raises(FMUError, match="appears twice with different contents"):
        load_fmu_component(same_size, "c")


def test_an_entry_twice_with_the_same_bytes_is_one_entry(mass_fmu, tmp_path, private_tmp):
    """As the Modelica Reference FMUs' build writes Roberts.fmu (its layered standard's manifest twice), and as
    fmpy runs it: here the model description and a resource are each written twice, identically."""
    with zipfile.ZipFile(mass_fmu) as zf:
        xml = zf.read("modelDescription.xml")
    manifest = b"<fmiLayeredStandardManifest/>"
    twice = rebuild(mass_fmu, tmp_path / "twice.fmu", extra=[("modelDescription.xml", xml),
                                                             ("extra/org.example/manifest.xml", manifest),
                                                             ("extra/org.example/manifest.xml", manifest)])
    with zipfile.ZipFile(twice) as zf:
        names = [i.filename for i in zf.infolist()]
    assert names.count("modelDescription.xml") == 2 and names.count("extra/org.example/manifest.xml") == 2
    c = load_fmu_component(twice, "c")
    try:
        c.setup(0.0)
        c.set_inputs({"F": [0.0]})
        c.do_step(0.0, 1e-3)
        assert c.time == 1e-3
    finally:
        c.terminate()
    assert list(private_tmp.iterdir()) == []
    folder = safezip.safe_extract(twice)
    try:
        assert (folder / "extra/org.example/manifest.xml").read_bytes() == manifest
    finally:
        import shutil

        shutil.rmtree(folder)


def test_an_fmi_version_not_imported(mass_fmu, tmp_path):
    bad = rebuild(mass_fmu, tmp_path / "v4.fmu", lambda n, d: d.replace(b'fmiVersion="2.0"', b'fmiVersion="4.0"')
                  if n == "modelDescription.xml" else d)
    with pytest.raises(FMUError, match="FMI 4.0 FMU: rotorcosim imports FMI 1.0, 2.0 and 3.0 co-simulation FMUs"):
        load_fmu_component(bad, "c")


def test_an_fmi_2_0_description_labelled_1_0(mass_fmu, tmp_path):
    bad = rebuild(mass_fmu, tmp_path / "v1.fmu", lambda n, d: d.replace(b'fmiVersion="2.0"', b'fmiVersion="1.0"')
                  if n == "modelDescription.xml" else d)
    with pytest.raises(FMUError, match=r"\(fmiVersion 1.0\) gives no modelIdentifier and no numberOfContinuousStates "
                                       "on fmiModelDescription, which FMI 1.0 requires"):
        load_fmu_component(bad, "c")


def test_entity_declarations_in_model_description(mass_fmu, tmp_path):
    def bomb(n, d):
        if n != "modelDescription.xml":
            return d
        return d.replace(b"<fmiModelDescription", b'<!DOCTYPE x [<!ENTITY a "aaaa">]>\n<fmiModelDescription', 1)

    bad = rebuild(mass_fmu, tmp_path / "dtd.fmu", bomb)
    with pytest.raises(FMUError, match="declares a DTD or entities"):
        load_fmu_component(bad, "c")


def test_duplicate_value_references(mass_fmu, tmp_path):
    with zipfile.ZipFile(mass_fmu) as zf:
        xml = zf.read("modelDescription.xml").decode()
    refs = re.findall(r'name="(\w+)"[^>]*valueReference="(\d+)"', xml)
    (_, ra), (b, _) = refs[0], refs[1]
    new = xml.replace(f'name="{b}"', f'name="{b}"', 1)
    new = re.sub(rf'(name="{b}"[^>]*valueReference=")\d+"', rf'\g<1>{ra}"', new, count=1)
    assert new != xml
    bad = rebuild(mass_fmu, tmp_path / "vr.fmu", lambda n, d: new.encode() if n == "modelDescription.xml" else d)
    with pytest.raises(FMUError, match=rf"share the Real valueReference {ra}: the FMU's variables collide"):
        load_fmu_component(bad, "c")


# -- SSP ---------------------------------------------------------------------------------------------
def test_ssp_malformed_parts(toy_ssp, tmp_path, private_tmp):
    cases = {
        "notxml": (edit_ssd(lambda d: d[: len(d) // 2]), "SystemStructure.ssd: not well-formed XML"),
        "laughs": (edit_ssd(lambda d: d.replace(
            b"<ssd:SystemStructureDescription",
            b'<!DOCTYPE l [<!ENTITY a "aaaaaaaaaa"><!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;">]>'
            b"<ssd:SystemStructureDescription", 1)), "declares a DTD or entities"),
        "novalue": (edit_ssd(lambda d: re.sub(rb'(<ssv:Real) value="[^"]*"', rb"\1", d, count=1)),
                    "has no value attribute"),
        "badnumber": (edit_ssd(lambda d: re.sub(rb'(<ssv:Real value=")[^"]*"', rb'\1twelve"', d, count=1)),
                      "is not a number"),
        "badjson": (edit_ssd(lambda d: re.sub(rb"(<rc:Scenario[^>]*>)\{", rb"\1{{", d, count=1)),
                    "annotation org.rotorcosim.scenario is not valid JSON"),
    }
    for name, (edit, message) in cases.items():
        bad = rebuild(toy_ssp, tmp_path / f"{name}.ssp", edit)
        with pytest.raises(SSPError, match=re.escape(message)):
            read_ssp(bad)
    assert list(private_tmp.iterdir()) == []  # every extraction folder removed at once


def test_ssv_file_malformed_or_bomb(toy_ssp, tmp_path, private_tmp):
    import xml.etree.ElementTree as ET

    from rotorcosim.master.scenario.ssp import NS

    def with_ssv(ssv: bytes) -> Path:
        with zipfile.ZipFile(toy_ssp) as zf:
            entries = {n: zf.read(n) for n in zf.namelist()}
        root = ET.fromstring(entries["SystemStructure.ssd"])
        binding = root.find(".//ssd:Component[@name='node']/ssd:ParameterBindings/ssd:ParameterBinding", NS)
        binding.remove(binding.find("ssd:ParameterValues", NS))
        binding.set("source", "resources/node.ssv")
        entries["SystemStructure.ssd"] = ET.tostring(root, encoding="UTF-8", xml_declaration=True)
        entries["resources/node.ssv"] = ssv
        out = tmp_path / f"ssv{len(list(tmp_path.iterdir()))}.ssp"
        with zipfile.ZipFile(out, "w") as zf:
            for n, data in entries.items():
                zf.writestr(n, data)
        return out

    with pytest.raises(SSPError, match=r"parameter file 'resources/node.ssv': not well-formed XML"):
        read_ssp(with_ssv(b"<ssv:ParameterSet"))
    with pytest.raises(SSPError, match=r"parameter file 'resources/node.ssv': declares a DTD"):
        read_ssp(with_ssv(b'<?xml version="1.0"?><!DOCTYPE x [<!ENTITY e SYSTEM "file:///etc/passwd">]><x>&e;</x>'))
    assert list(private_tmp.iterdir()) == []
