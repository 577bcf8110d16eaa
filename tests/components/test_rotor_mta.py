"""MTA (eqs. 16-22) against the full model and against plain modal truncation of the same size."""
import numpy as np
import pytest

from rotorcosim.components.rotor import verification as ver
from rotorcosim.components.rotor.component import LOAD_GROUPS, full_model
from rotorcosim.components.rotor.mta import augmentation_vectors, modes, mta_basis, project, unit_loads


@pytest.fixture(scope="module")
def full():
    return full_model()


def test_mta_basis_is_mass_orthonormal_and_static_complete(full):
    """The pseudo-modal set [Phi eta] is M-orthonormal (eq. 19's eigenvectors, Phi^T M eta = 0 follows from
    K^-1 M Phi = Phi w^-2), K~ is diagonal, and a static load at any port DOF is reproduced exactly by the reduced
    model (the span contains K^-1 F_o): the property that makes MTA better than modal truncation."""
    load_dofs = np.concatenate([full.ports[g] for g in LOAD_GROUPS])
    phi, n_aug = mta_basis(full.K, full.M, 30, load_dofs)
    n = phi.shape[1]
    # 16 load DOFs, 12 distinct: the rub rings act at the bearing nodes (engine.toml), so their x y are already
    # among the bearings' (a dependent load vector is dropped, not duplicated)
    assert len(set(load_dofs.tolist())) == 12
    assert n_aug == 12 and n - n_aug >= 30   # 30 modes, or more when the 30th is one of a degenerate group
    Mr, Kr = project(phi, full.M, full.K)
    np.testing.assert_allclose(Mr, np.eye(n), atol=1e-9)
    off = Kr - np.diag(np.diag(Kr))
    assert np.max(np.abs(off)) < 1e-8 * np.max(np.abs(Kr))
    F = unit_loads(full.n, load_dofs)
    exact = np.linalg.solve(full.K, F)[load_dofs]
    red = phi[load_dofs] @ np.linalg.solve(Kr, phi.T @ F)
    np.testing.assert_allclose(red, exact, rtol=1e-7, atol=1e-9 * np.max(np.abs(exact)))


def test_static_blade_loss_deflection_on_linear_supports_mta_exact_modal_not(full):
    """Static deflection at bearings #0/#5 under the blade-loss force with bearings #0/#5 as linear springs:
    exact solution (K + Ks)^-1 f of the full model. MTA is exact (the support forces act at port DOFs, inside its
    span); plain modal truncation of the same size (46 modes) is not."""
    M, C, K = ver.linear_system(full)
    f = np.zeros(full.n)
    f[full.ports["unbalance"][0]] = 2850.0
    rows = np.concatenate([full.ports["brg0"][:2], full.ports["brg5"][:2]])
    exact = np.linalg.solve(K, f)[rows]
    out = {}
    for kind in ("mta", "modal"):
        phi = ver.basis(full, kind, 30)
        Kr = phi.T @ K @ phi
        out[kind] = phi[rows] @ np.linalg.solve(Kr, phi.T @ f)
    err = {k: np.max(np.abs(v - exact)) / np.max(np.abs(exact)) for k, v in out.items()}
    assert err["mta"] < 1e-7
    assert err["modal"] > 100 * err["mta"]


def test_blade_loss_transient_mta_vs_full_and_modal(full):
    """Blade-loss transient (2850 N rotating at 16 000 rev/min from t = 0, 0.03 s, Newmark h = 2e-5 s) on linear
    #0/#5 supports: peak radial displacement at bearings #0 and #5 of the MTA model (30 modes + 12 vectors = 42,
    43 with the degenerate pair kept whole: the component's default) within 1 % of the full 580-DOF model, and
    closer than plain modal truncation of the same size; the same for the RMS error of the whole x, y histories
    at both bearings."""
    ref = ver.blade_loss_transient(full, "full")
    mta = ver.blade_loss_transient(full, "mta", 30)
    modal = ver.blade_loss_transient(full, "modal", 30)
    assert mta["size"] >= 42 and ref["size"] == full.n
    e_mta = [abs(mta[k] / ref[k] - 1) for k in ("peak0", "peak5")]
    e_modal = [abs(modal[k] / ref[k] - 1) for k in ("peak0", "peak5")]
    print(f"\npeaks full {ref['peak0'] * 1e3:.5f} / {ref['peak5'] * 1e3:.5f} mm; rel. error MTA {e_mta}, "
          f"modal {e_modal}")
    assert max(e_mta) < 0.01
    assert e_mta[0] < e_modal[0] and e_mta[1] < e_modal[1]
    # the whole history too, not just the peaks (RMS error relative to the RMS response, per bearing)
    def rms(r, cols):
        return np.sqrt(np.mean((r["x"][:, cols] - ref["x"][:, cols]) ** 2)) / np.sqrt(np.mean(ref["x"][:, cols] ** 2))
    for cols in (slice(0, 2), slice(2, 4)):
        assert rms(mta, cols) < 0.01
        assert rms(mta, cols) < rms(modal, cols)


def test_dependent_load_vectors_are_dropped():
    """Two identical load vectors give one augmentation vector (no singular eq. 19)."""
    rng = np.random.default_rng(1)
    A = rng.normal(size=(12, 12))
    M = A @ A.T + 12 * np.eye(12)
    K = np.diag(np.arange(1.0, 13.0)) * 1e4
    _, phi = modes(K, M, 3)
    F = unit_loads(12, [5, 5, 7])
    eta = augmentation_vectors(K, M, phi, F)
    assert eta.shape[1] == 2
    np.testing.assert_allclose(eta.T @ M @ eta, np.eye(2), atol=1e-10)
    np.testing.assert_allclose(phi.T @ M @ eta, 0.0, atol=1e-10)


def test_bad_mode_count(full):
    with pytest.raises(ValueError, match="number of modes"):
        modes(full.K, full.M, 0)


def test_a_degenerate_group_is_kept_whole():
    """Two identical uncoupled oscillators give a repeated eigenvalue: asking for the first mode of the pair keeps
    both (any single vector of their eigenspace would be LAPACK's arbitrary choice), an isolated one stays single."""
    from rotorcosim.components.rotor.mta import modes

    K = np.diag([1.0, 4.0, 4.0, 9.0])
    M = np.eye(4)
    w2, Phi = modes(K, M, 2)
    np.testing.assert_allclose(w2, [1.0, 4.0, 4.0])
    assert Phi.shape == (4, 3)
    assert modes(K, M, 1)[1].shape == (4, 1) and modes(K, M, 4)[1].shape == (4, 4)
