"""scripts/fetch-data: installs every model of scripts/data-manifest.json
with its checksum verified, keeps what is already right, refuses a file
that differs, and without a network names the address that failed and
says how to install from a local copy (--from)."""
import json
import os
import subprocess

import pytest

from conftest import ROOT

SCRIPT = os.path.join(ROOT, "scripts", "fetch-data")
SHARED = os.path.join(os.path.dirname(ROOT), "shared", "data")
with open(os.path.join(ROOT, "scripts", "data-manifest.json")) as f:
    FILES = json.load(f)["files"]


def fetch(*args, **env):
    return subprocess.run([SCRIPT, *map(str, args)], capture_output=True, text=True, timeout=120,
                          env=dict(os.environ, **env))


def test_the_manifest_names_every_file_with_its_checksum():
    assert len(FILES) == 10
    for e in FILES:
        assert len(e["sha256"]) == 64 and e["bytes"] > 0 and e["url"].startswith("https://"), e["path"]
        assert e["license"], e["path"]


def test_no_network_names_the_address_and_suggests_from(tmp_path):
    # A proxy that refuses every connection: the same failure as a machine
    # without a network, whether or not this one has one.
    out = fetch("--to", tmp_path, https_proxy="http://127.0.0.1:9", http_proxy="http://127.0.0.1:9")
    assert out.returncode == 1
    assert FILES[0]["url"] in out.stderr
    assert "scripts/fetch-data --from DIR" in out.stderr
    assert not any(p.is_file() for p in tmp_path.rglob("*")), "nothing unverified is installed"


@pytest.mark.skipif(not os.path.isdir(SHARED), reason="no local copy of the data in ../shared/data")
def test_from_a_local_copy_verifies_and_refuses_a_changed_file(tmp_path):
    dest, source = tmp_path / "data", tmp_path / "copy"
    out = fetch("--from", SHARED, "--to", dest)
    assert out.returncode == 0, out.stderr
    assert "10 files verified" in out.stdout and "(10 installed)" in out.stdout
    assert fetch("--to", dest, "--check").returncode == 0
    assert "(" not in fetch("--from", SHARED, "--to", dest).stdout  # nothing to install again

    # A copy whose head mesh changed by one byte is not installed.
    for e in FILES:
        (source / e["path"]).parent.mkdir(parents=True, exist_ok=True)
        (source / e["path"]).symlink_to(os.path.join(SHARED, e["path"]))
    head = source / "hair" / "sintel_head.obj"
    data = bytearray(head.read_bytes())
    data[100] ^= 1
    head.unlink()
    head.write_bytes(bytes(data))
    (dest / "hair" / "sintel_head.obj").unlink()
    out = fetch("--from", source, "--to", dest)
    assert out.returncode == 1
    assert "hair/sintel_head.obj" in out.stderr and "SHA-256" in out.stderr and "not installed" in out.stderr
    assert not (dest / "hair" / "sintel_head.obj").exists()
    check = fetch("--to", dest, "--check")
    assert check.returncode == 1 and "sintel_head.obj: missing" in check.stderr
