"""The Array tab's live readout: the live force is labelled instantaneous, the mean over
the steady window settles and is held, and after the slab has left the grid the readout
keeps the last values of a sliding slab (never "N_c0 = 0" or "–")."""
import numpy as np
import pytest

from app.figures.array_scene import _readout
from app.figures.array_readout import last_counted, settled_mean
from model import REGIMES
from model.arrays.array_motion import array_motion


@pytest.fixture(scope="module")
def motion():
    return array_motion(REGIMES["slider"], n_supports=60, n_frames=200)


def test_the_readout_labels_the_live_force_and_keeps_the_last_values(motion):
    early = _readout(motion, 10)
    assert "instantaneous" in early and "from τ =" in early
    last = _readout(motion, motion.n_frames - 1)
    assert int(motion.N_c0[-1]) == 0  # the slab has left the grid
    assert "the slab has left the grid" in last and "N_c0 = 0" not in last
    assert "–" not in last and "(settled)" in last


def test_the_settled_mean_is_the_steady_window_mean_and_is_held(motion):
    run = settled_mean(motion)
    after = motion.t > motion.steady[1]
    assert after.any()
    assert np.allclose(run[after], motion.steady_means()["FTx_over_mu0FN"], rtol=0.02)
    assert np.all(run[after] == run[after][0])
    g = last_counted(motion)
    first = int(np.argmax(motion.N_c0 > 0))  # before it nothing is counted yet
    assert np.all(motion.N_c0[g[first:]] > 0) and np.all(g <= np.arange(g.size))
