"""Conventions and their identification (convention.h) from Python.

The truths are written here: the real SH of bands 0..2 as Cartesian
polynomials (orthonormal, cs: y_1^{-1} = -k·y, y_1^1 = -k·x; nocs without the
phase), ambisonics' SN3D (ACN, no phase: 1, y, z, x, √3xy, √3yz,
(3z²−1)/2, √3xz, √3/2(x²−y²)) and N3D (SN3D × √(2l+1)), the complex
orthonormal Y_l^m, and the projections of a sum of directional lights
(c_k = Σ w U_k(d) / ∫U_k²).  A user basis built from them at the fixture's
directions must be named by identify_basis, with the same JSON as
`shlab identify --basis FILE --format json` field for field."""
import json
import os
import subprocess

import numpy as np
import pytest

import shlab

pytestmark = pytest.mark.skipif(not shlab.identify_available(),
                                reason="the loaded libshlab has no convention.h functions yet")

PI = np.pi
BAND = np.array([0, 1, 1, 1, 2, 2, 2, 2, 2])
ODD_M = np.array([0, 1, 0, 1, 0, 1, 0, 1, 0], bool)


def real_sh_nocs(d):
    """Orthonormal real SH of bands 0..2 without the Condon-Shortley phase, ACN, at unit d (..., 3)."""
    x, y, z = d[..., 0], d[..., 1], d[..., 2]
    k1, k2, k20 = np.sqrt(3 / (4 * PI)), 0.5 * np.sqrt(15 / PI), 0.25 * np.sqrt(5 / PI)
    return np.stack([0.5 / np.sqrt(PI) + 0 * x, k1 * y, k1 * z, k1 * x, k2 * x * y, k2 * y * z,
                     k20 * (3 * z * z - 1), k2 * x * z, 0.5 * k2 * (x * x - y * y)], axis=-1)


def real_sh_cs(d):
    return real_sh_nocs(d) * np.where(ODD_M, -1.0, 1.0)


def sn3d(d):
    """Ambisonics SN3D (ACN order, no phase) of bands 0..2."""
    x, y, z = d[..., 0], d[..., 1], d[..., 2]
    s = np.sqrt(3)
    return np.stack([1 + 0 * x, y, z, x, s * x * y, s * y * z, (3 * z * z - 1) / 2, s * x * z,
                     s / 2 * (x * x - y * y)], axis=-1)


def n3d(d):
    return sn3d(d) * np.sqrt(2 * BAND + 1)


def complex_sh(d):
    """Orthonormal complex Y_l^m (cs), bands 0..2, entry l(l+1)+m, as complex numbers."""
    x, y, z = d[..., 0], d[..., 1], d[..., 2]
    p, q = x + 1j * y, x - 1j * y
    a1, b1 = np.sqrt(3 / (4 * PI)), np.sqrt(3 / (8 * PI))
    a2, b2, c2 = np.sqrt(5 / (16 * PI)), np.sqrt(15 / (8 * PI)), np.sqrt(15 / (32 * PI))
    return np.stack([0.5 / np.sqrt(PI) + 0 * p, b1 * q, a1 * z + 0j, -b1 * p, c2 * q * q, b2 * z * q,
                     a2 * (3 * z * z - 1) + 0j, -b2 * z * p, c2 * p * p], axis=-1)


def mdesc(v):
    """Each band's entries in m = l..−l order."""
    return np.concatenate([v[..., l * l:(l + 1) * (l + 1)][..., ::-1] for l in range(3)], axis=-1)


def y_up(d):
    """A y-up library receives u = (x, z, −y) of the formulas' (x, y, z): s = (u_x, −u_z, u_y)."""
    return np.stack([d[..., 0], -d[..., 2], d[..., 1]], axis=-1)


def interleave(z):
    return np.ascontiguousarray(np.stack([z.real, z.imag], axis=-1).reshape(z.shape[:-1] + (-1,)))


# (name, the user's basis at unit directions d, a spec of that convention, ∫U_k² per entry)
BASES = [
    ("ambix", sn3d, "ambix", 4 * PI / (2 * BAND + 1)),
    ("n3d", n3d, "real,nocs,n3d", 4 * PI + 0 * BAND),
    ("nocs", real_sh_nocs, "nocs", 1 + 0 * BAND),
    ("cs mdesc", lambda d: mdesc(real_sh_cs(d)), "real,cs,mdesc", 1 + 0 * BAND),
    ("y-up cs", lambda d: real_sh_cs(y_up(d)), "real,cs,y-up", 1 + 0 * BAND),
    ("y-up sn3d", lambda d: sn3d(y_up(d)), "real,nocs,sn3d,y-up", 4 * PI / (2 * BAND + 1)),
    ("complex", lambda d: interleave(complex_sh(d)), "complex,cs", None),
]


def named(result, spec):
    """The identified class holds the convention of `spec` (its name or an alias)."""
    want = str(shlab.Convention(spec))
    return result.verdict == "identified" and (want == result.convention or want in
                                               result.candidates[0].aliases.split())


@pytest.fixture(scope="module")
def dirs():
    d, ex = shlab.fixture_directions(exact=True)
    return d, ex


@pytest.fixture(scope="module")
def shlab_bin(build):
    b = os.path.join(build, "shlab")
    if not os.access(b, os.X_OK):
        pytest.skip("no %s" % b)
    return b


def cli_identify(shlab_bin, tmp_path, values, name="basis.json", extra=()):
    path = str(tmp_path / name)
    with open(path, "w") as f:
        json.dump({"values": np.asarray(values).tolist()}, f)
    p = subprocess.run([shlab_bin, "identify", "--basis", path, "--format", "json"] + list(extra),
                       capture_output=True, text=True)
    assert p.returncode in (0, 1), p.stderr
    return path, json.loads(p.stdout), p.returncode


def test_fixture_directions_are_exact_unit_vectors(dirs):
    d, ex = dirs
    assert d.shape == (32, 3) and ex.shape == (32, 4)
    np.testing.assert_array_equal((ex[:, :3] ** 2).sum(1), ex[:, 3] ** 2)
    np.testing.assert_allclose(d, ex[:, :3] / ex[:, 3:], rtol=0, atol=1e-16)
    ld, w = shlab.fixture_light()
    np.testing.assert_allclose(w, [1, 0.5, 0.25])
    np.testing.assert_allclose(np.linalg.norm(ld, axis=1), 1, atol=1e-15)
    np.testing.assert_allclose(shlab.fixture_light_coeffs(3), (w[:, None] * real_sh_cs(ld)).sum(0), atol=1e-15)


def test_convention_descriptor():
    a = shlab.Convention.parse("ambix")
    assert str(a) == "real,nocs,sn3d,acn,neg-sin,z-up" and a.preset == "ambix"
    assert a == shlab.Convention("sn3d,nocs") and a != shlab.Convention("real,nocs,schmidt")
    assert str(shlab.Convention()) == "real,cs,ortho,acn,neg-sin,z-up" and shlab.Convention().preset == "cs"
    assert shlab.Convention("y-up").axes == 12 and str(shlab.Convention("+x+z-y")) == "real,cs,ortho,acn,neg-sin,y-up"
    assert shlab.Convention("real,cs,mdesc").preset is None
    assert str(shlab.Convention("healpix")) == "complex-half,cs,z-up"
    assert len({shlab.Convention("n3d,nocs"), shlab.Convention("real,nocs,n3d,acn")}) == 1
    assert shlab.Convention("complex").ndoubles(3) == 18 and shlab.Convention("healpix").order_of(12) == 3


@pytest.mark.parametrize("name,basis,spec,norm", BASES, ids=[b[0] for b in BASES])
def test_eval_convention_is_the_closed_form(dirs, name, basis, spec, norm):
    d = dirs[0]
    np.testing.assert_allclose(shlab.eval_convention(spec, 3, d), basis(d), rtol=0, atol=1e-14)
    np.testing.assert_allclose(shlab.eval_convention(spec, 3, d[5]), basis(d[5]), rtol=0, atol=1e-14)


@pytest.mark.parametrize("name,basis,spec,norm", BASES, ids=[b[0] for b in BASES])
def test_identify_basis_names_it(dirs, name, basis, spec, norm):
    r = shlab.identify_basis(basis(dirs[0]))
    assert named(r, spec), r
    assert r.order == 3 and r.candidates[0].fits and r.candidates[0].fits_through_order == 3
    assert r.conv is not None and str(r.conv) == r.convention
    assert r.to_shlab == "shlab convert --from %s --to cs --in FILE" % r.convention
    assert r.from_shlab == "shlab convert --from cs --to %s --in FILE" % r.convention


def test_same_json_as_the_cli(dirs, shlab_bin, tmp_path):
    d = dirs[0]
    bad = sn3d(d)
    bad[:, 6] = -bad[:, 6]                            # a sign error in band 2: no fit
    cases = [("ambix", sn3d(d), ()), ("y-up", real_sh_cs(y_up(d)), ()),
             ("complex", interleave(complex_sh(d)), ()), ("ambix2", sn3d(d)[:, :4], ()),
             ("bad", bad, ()),
             ("constant", np.tile([0.5 / np.sqrt(PI), 0.0], (32, 1)), ()), ("tight", sn3d(d) * (1 + 1e-6 * np.cos(7 * d[:, :1])), ("--tol", "1e-9"))]
    for name, values, extra in cases:
        path, cli, rc = cli_identify(shlab_bin, tmp_path, values, name + ".json", extra)
        tol = float(extra[1]) if extra else 1e-4
        py = shlab.identify_basis(values, tol=tol, file=path)
        assert py.as_dict() == cli, name
        assert rc == (0 if py.identified else 1)
    assert shlab.identify_basis(sn3d(d)[:, :4]).verdict == "ambiguous"


def test_ambiguous_at_order_2_needs_band_2(dirs):
    r = shlab.identify_basis(sn3d(dirs[0])[:, :4])
    assert r.verdict == "ambiguous" and r.needs == "band 2 (order 3): these agree on bands 0..1"
    assert r.needs_order == 3 and len(r.candidates) > 1 and all(c.fits for c in r.candidates)
    assert "convention" not in r and "to_shlab" not in r
    ambix = str(shlab.Convention("ambix"))
    assert any(ambix == c.convention or ambix in c.aliases.split() for c in r.candidates)


def test_identify_projection(dirs):
    ld, w = shlab.fixture_light()
    for name, basis, spec, norm in BASES:
        if norm is None:
            coeffs = interleave((w[:, None] * np.conj(complex_sh(ld))).sum(0))
        else:
            coeffs = (w[:, None] * basis(ld)).sum(0) / norm
        truth = (w[:, None] * real_sh_cs(ld)).sum(0)  # shlab's projection, from the closed form
        np.testing.assert_allclose(shlab.to_shlab(coeffs, spec), truth, rtol=0, atol=1e-14, err_msg=name)
        np.testing.assert_allclose(shlab.to_shlab(coeffs, spec), shlab.fixture_light_coeffs(3), rtol=0,
                                   atol=1e-14, err_msg=name)
        np.testing.assert_allclose(shlab.from_shlab(truth, spec), coeffs, rtol=0, atol=1e-14, err_msg=name)
        r = shlab.identify_projection(coeffs)
        assert r.input == "projection" and r.order == 3
        if r.verdict == "identified":
            assert named(r, spec), (name, r)
        else:  # the light cannot tell some bases apart: then the result says so
            assert r.verdict == "ambiguous" and r.needs_basis, (name, r)
            assert r.needs == "the basis values (--basis): the light's coefficients do not tell these apart"


def test_projection_same_json_as_the_cli(shlab_bin, tmp_path):
    ld, w = shlab.fixture_light()
    coeffs = (w[:, None] * real_sh_nocs(y_up(ld))).sum(0)
    path = str(tmp_path / "proj.txt")
    with open(path, "w") as f:
        f.write(",".join(repr(float(x)) for x in coeffs) + "\n")
    p = subprocess.run([shlab_bin, "identify", "--projection", path, "--format", "json"], capture_output=True,
                       text=True)
    assert p.returncode == 0, p.stderr
    py = shlab.identify_projection(coeffs, file=path)
    assert py.as_dict() == json.loads(p.stdout)
    assert py.convention == "real,nocs,ortho,acn,neg-sin,y-up"


SPECS = ["cs", "nocs", "ambix", "real,nocs,n3d", "fuma", "real,cs,mdesc,y-up", "real,schmidt,cossin,neg-cos",
         "real,nocs,fuma-order,+y-z+x", "y-up-lh", "complex", "complex,nocs,y-up", "healpix"]


def test_convert_round_trips():
    rng = np.random.default_rng(3)
    x = rng.normal(size=(2, 3, 16))                  # order 4, batched
    for spec in SPECS:
        u = shlab.from_shlab(x, spec)
        assert u.shape == (2, 3, shlab.Convention(spec).ndoubles(4))
        np.testing.assert_allclose(shlab.to_shlab(u, spec), x, rtol=0, atol=1e-13, err_msg=spec)
        for other in SPECS:
            v = shlab.convert_convention(u, spec, other)
            np.testing.assert_allclose(v, shlab.from_shlab(x, other), rtol=0, atol=1e-13, err_msg=spec + other)
            np.testing.assert_allclose(shlab.convert_convention(v, other, spec, order=4), u, rtol=0, atol=1e-13)
    # the identity conversion, and shlab's own spec
    np.testing.assert_array_equal(shlab.convert_convention(x[0, 0], "cs", "cs"), x[0, 0])
    # the represented function is kept: Σ c_shlab y(d) = Σ c_user U(d) at the user's d
    d = np.array([0.36, 0.48, 0.8])
    c = x[0, 0, :9]
    for spec in ("ambix", "real,cs,y-up", "real,nocs,n3d,mdesc", "y-up-lh", "fuma"):
        assert np.isclose(real_sh_cs(d) @ c, shlab.eval_convention(spec, 3, d) @ shlab.from_shlab(c, spec)), spec
    # ambix → n3d scales band l by 1/√(2l+1) (the basis grows by √(2l+1))
    c = rng.normal(size=9)
    np.testing.assert_allclose(shlab.convert_convention(c, "ambix", "real,nocs,n3d"), c / np.sqrt(2 * BAND + 1),
                               rtol=1e-14)


def test_errors(dirs, monkeypatch):
    d = dirs[0]
    with pytest.raises(shlab.Error) as e:
        shlab.Convention.parse("real,foo")
    assert e.value.status == 1 and "unknown convention token 'foo'" in e.value.message
    with pytest.raises(shlab.Error, match="given twice"):
        shlab.Convention("cs,nocs")
    with pytest.raises(shlab.Error, match="FuMa"):
        shlab.from_shlab(np.zeros(25), "fuma")
    with pytest.raises(shlab.Error, match="not a whole order"):
        shlab.to_shlab(np.zeros(3), "complex")
    with pytest.raises(ValueError, match="needs 18"):
        shlab.to_shlab(np.zeros(9), "complex", order=3)
    with pytest.raises(shlab.Error, match="orders 1..16"):
        shlab.identify_basis(np.zeros((32, 17 * 17)), order=17)
    with pytest.raises(shlab.Error, match="order 2 needs 4"):
        shlab.identify_basis(sn3d(d), order=2)
    with pytest.raises(shlab.Error, match="outside"):
        shlab.identify_basis(sn3d(d), tol=2)
    with pytest.raises(TypeError):
        shlab.Convention(3)
    # shapes and dtypes are refused before any C call
    import shlab.identify as ident

    def no_call(*a):
        raise AssertionError("C called")

    monkeypatch.setattr(ident, "_id_basis", no_call)
    monkeypatch.setattr(ident, "_id_proj", no_call)
    monkeypatch.setattr(ident, "_convert", no_call)
    with pytest.raises(ValueError, match="shape"):
        shlab.identify_basis(sn3d(d)[:31])
    with pytest.raises(ValueError, match="shape"):
        shlab.identify_basis(sn3d(d).ravel())
    with pytest.raises(ValueError, match="non-finite"):
        shlab.identify_basis(np.where(d[:, :1] > 0, np.nan, sn3d(d)))
    with pytest.raises(TypeError, match="interleaved"):
        shlab.identify_basis(complex_sh(d))
    with pytest.raises(TypeError):
        shlab.identify_basis(np.full((32, 9), "x"))
    with pytest.raises(ValueError, match="order must be >= 1"):
        shlab.identify_basis(sn3d(d), order=0)
    with pytest.raises(TypeError):
        shlab.identify_basis(sn3d(d), tol="small")
    with pytest.raises(ValueError, match="one vector"):
        shlab.identify_projection(np.zeros((2, 9)))
    with pytest.raises(TypeError, match="interleaved"):
        shlab.convert_convention(np.zeros(9, complex), "healpix", "cs")
    with pytest.raises(ValueError, match="needs"):
        shlab.convert_convention(np.zeros(8), "cs", "nocs", order=3)
    with pytest.raises(ValueError, match=r"\(\.\.\., 3\)"):
        shlab.eval_convention("cs", 3, np.zeros(4))
