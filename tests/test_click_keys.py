"""The keyboard's equivalents of a click on the regime map and the polar diagrams
(app/views/click_keys.py): each button sets what a click there sets -- the springs one
map cell along k_r or k_theta (clamped into the sliders' range), theta0 by its step."""
import pytest

from app.state import ExplorerState
from app.views.click_keys import DEFAULT_CELL, map_cell, map_steps, theta_steps
from model.runs.shipped_map import load_regime_map


def _buttons(column) -> dict:
    row = column.objects[1]
    return {b.label if hasattr(b, "label") else b.name: b for b in row.objects}


def test_the_map_buttons_move_the_springs_one_cell_of_the_map_on_show():
    m = load_regime_map(F_N=1.0)
    cell = map_cell(m)
    assert cell == pytest.approx(m.k_r[1] / m.k_r[0]) and map_cell(None) == DEFAULT_CELL
    state = ExplorerState(k_r=0.03, k_theta=0.03)
    buttons = _buttons(map_steps(state, lambda: cell))
    buttons["k_r +"].clicks += 1
    assert (state.k_r, state.k_theta) == pytest.approx((0.03 * cell, 0.03))
    buttons["k_θ −"].clicks += 1
    buttons["k_θ −"].clicks += 1
    assert (state.k_r, state.k_theta) == pytest.approx((0.03 * cell, 0.03 / cell ** 2))
    for _ in range(40):  # clamped into the sliders' range, as a click beyond the map
        buttons["k_r +"].clicks += 1
    assert state.k_r == state.param.k_r.bounds[1]


def test_the_polar_buttons_turn_theta0_and_wrap_round():
    state = ExplorerState(theta0=90.0)
    buttons = _buttons(theta_steps(state))
    assert set(buttons) == {"θ₀ −15°", "θ₀ −1°", "θ₀ +1°", "θ₀ +15°"}
    buttons["θ₀ +15°"].clicks += 1
    buttons["θ₀ −1°"].clicks += 1
    assert state.theta0 == 104.0
    state.theta0 = 5.0
    buttons["θ₀ −15°"].clicks += 1
    assert state.theta0 == 350.0
