"""`make install` with DESTDIR staging installs the package where the
interpreter finds it under PREFIX/lib/python3.X/dist-packages, and once
copied to PREFIX it imports and loads PREFIX/lib/libshlab.so.0 (recorded at
install time), with no SHLAB_LIBRARY and from outside the tree.  Truth:
y_0^0 = 1/sqrt(4π)."""
import os
import shutil
import subprocess
import sys

import pytest


def test_staged_install_imports_from_prefix(tmp_path, root, build):
    if shutil.which("make") is None:
        pytest.skip("no make")
    final, stage = str(tmp_path / "final"), str(tmp_path / "stage")
    env = {k: v for k, v in os.environ.items() if k not in ("MAKEFLAGS", "MFLAGS", "MAKELEVEL", "SHLAB_LIBRARY")}
    rel_build = os.path.relpath(build, root)
    r = subprocess.run(["make", "-s", "-C", root, "install", "BUILD=" + rel_build, "PYTHON=" + sys.executable,
                        "DESTDIR=" + stage, "PREFIX=" + final], env=env, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-2000:]
    assert not os.path.exists(final)
    site = "lib/python%d.%d/dist-packages" % sys.version_info[:2]
    assert os.path.isfile(os.path.join(stage + final, site, "shlab", "__init__.py"))
    shutil.copytree(stage + final, final)
    env["PYTHONPATH"] = os.path.join(final, site)
    code = "import shlab, math; print(shlab.library_path()); print(shlab.__file__); " \
           "print(repr(float(shlab.eval_angles(1, 0.3, 0.2)[0] * math.sqrt(4 * math.pi))))"
    r = subprocess.run([sys.executable, "-c", code], env=env, cwd=str(tmp_path), capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    lib, pkg, y = r.stdout.split("\n")[:3]
    assert lib == os.path.join(final, "lib", "libshlab.so.0")
    assert pkg.startswith(os.path.join(final, site))
    assert abs(float(y) - 1.0) < 1e-15


def test_debian_python_searches_the_usr_local_site():
    # the directory `make install PREFIX=/usr/local` uses is on this interpreter's path
    want = "/usr/local/lib/python%d.%d/dist-packages" % sys.version_info[:2]
    if sys.executable != "/usr/bin/python3" and os.path.realpath(sys.executable) != os.path.realpath("/usr/bin/python3"):
        pytest.skip("not Debian's /usr/bin/python3")
    assert want in sys.path
